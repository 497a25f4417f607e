// Shows which rows the host hands a model (abi.h: the active rows only, on
// every path) and that it forgets a separated contact's history. Its own
// row loop (`law_rows`), which the adapter runs only on a batch of active
// rows, is a linear spring that counts the steps a contact has lasted in
// history; law(), which the adapter runs on the active rows of a batch that
// holds an inactive one, gives a NaN force, which the host reports. Three
// models, one per packer (ForcePipeline::packer_of): `active_rows_probe`
// (ball pairs; wall rows from the table), `active_rows_probe_centres` (a
// force between centres) and `active_rows_probe_summed` (it accumulates a
// body field: from the table).
#include "test_models.hpp"

#include <limits>

namespace {

struct ActiveRowsProbe : SpringBase {
    static constexpr const char* name = "active_rows_probe";
    static constexpr plab_history_desc history[] = {
        plab::history_desc("steps_in_contact", 0.0, PLAB_SWAP_KEEP, "calls since the contact began")};
    using SpringBase::SpringBase;
    void spring(const plab::Contact& c) const {
        c.set_force(k * c.overlap() * c.normal());
        c.set_stiffness(k);
        c.history(0) += 1.0;
    }
    void law(const plab::Contact& c) const {
        c.set_force(std::numeric_limits<double>::quiet_NaN() * c.normal());
    }
    void law_rows(const plab_contact_batch& b, std::size_t k0, std::size_t k1) const {
        for (std::size_t k = k0; k < k1; ++k) spring(plab::Contact(b, uint32_t(k)));
    }
};

struct ActiveRowsProbeCentres : ActiveRowsProbe {
    static constexpr const char* name = "active_rows_probe_centres";
    static constexpr uint32_t flags = PLAB_MODEL_FORCE_AT_CENTRES;
    using ActiveRowsProbe::ActiveRowsProbe;
};

struct ActiveRowsProbeSummed : ActiveRowsProbe {
    static constexpr const char* name = "active_rows_probe_summed";
    static constexpr plab_field_desc fields_accumulated[] = {plab::field_desc("active_rows_probe_count", "1", 0.0)};
    using ActiveRowsProbe::ActiveRowsProbe;
    void law_rows(const plab_contact_batch& b, std::size_t k0, std::size_t k1) const {
        for (std::size_t k = k0; k < k1; ++k) {
            const plab::Contact c(b, uint32_t(k));
            spring(c);
            c.accumulate1(0, 1.0);
        }
    }
};

} // namespace

PLAB_PLUGIN(plab::add_contact_model<ActiveRowsProbe>(r) || plab::add_contact_model<ActiveRowsProbeCentres>(r) ||
            plab::add_contact_model<ActiveRowsProbeSummed>(r))
