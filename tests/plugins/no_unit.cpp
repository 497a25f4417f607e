// A property without an SI unit and with a default outside its range.
#include "test_models.hpp"
struct NoUnit : SpringBase {
    static constexpr const char* name = "no_unit";
    static constexpr plab_property_desc properties[] = {plab::prop::number("k", "stiffness", "", -1.0, 0.0, 1e12, 0, "spring")};
    using SpringBase::SpringBase;
    void law(const plab::Contact& c) const { c.set_force(k * c.overlap() * c.normal()); c.set_stiffness(k); }
};
PLAB_PLUGIN(plab::add_contact_model<NoUnit>(r))
