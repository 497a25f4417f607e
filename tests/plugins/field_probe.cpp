// Exercises body-field columns in a contact batch: reads `probe_value` at
// both ends and accumulates the other end's value into `probe_sum`, with
// the linear spring as its force so contacts behave. `probe_claims` counts
// the host's claims that probe_value is at its default (ABI 7), -1e9 for a
// claim the values belie.
#include "test_models.hpp"
struct FieldProbe : SpringBase {
    static constexpr const char* name = "field_probe";
    static constexpr plab_field_desc fields_read[] = {plab::field_desc("probe_value", "1", 2.0)};
    static constexpr plab_field_desc fields_accumulated[] = {plab::field_desc("probe_sum", "1", 0.0), plab::field_desc("probe_claims", "1", 0.0)};
    using SpringBase::SpringBase;
    void law(const plab::Contact& c) const {
        c.set_force(k * c.overlap() * c.normal());
        c.set_stiffness(k);
        if (c.field_at_default(0)) c.accumulate1(1, c.field1(0) == 2.0 ? 1.0 : -1e9);
        if (c.with_wall()) {
            c.accumulate1(0, c.field2(0));  // NaN: a wall has no body fields
            return;
        }
        c.accumulate1(0, c.field2(0));
        c.accumulate2(0, c.field1(0));
    }
};
PLAB_PLUGIN(plab::add_contact_model<FieldProbe>(r))
