// Shows what a law reads of a history vector it declares tangential (abi.h,
// PLAB_HISTORY_TANGENTIAL): each call records the normal component and the
// magnitude of the vector it was given, then stores a fixed vector out of
// any contact plane, which the host must turn into the next call's plane
// with its magnitude. A linear spring keeps the contacts those of a pile.
// Three models, one per path a batch takes: `tangential_probe` (packed
// ball–ball rows; ball–wall rows in full columns), `tangential_probe_centres`
// (a force between centres: the packed centre-force rows) and
// `tangential_probe_summed` (it accumulates a body field: full columns).
#include "test_models.hpp"

namespace {

struct TangentialProbe : SpringBase {
    static constexpr const char* name = "tangential_probe";
    // (in the xy plane, so that a 2D world's contact planes hold it too)
    static constexpr plab::Vec3 stored = {0.3, -0.4, 0.0};
    static constexpr plab::Vec3 stored_3d = {0.3, -0.4, 1.2};
    enum Slot : int { vec_x, vec_y, vec_z, seen_along_normal, seen_magnitude, slot_count };
    static constexpr plab_history_desc history[] = {
        plab::history_desc("vec_x", 0.0, PLAB_SWAP_NEGATE, "a tangential vector on end 2, x", PLAB_HISTORY_TANGENTIAL),
        plab::history_desc("vec_y", 0.0, PLAB_SWAP_NEGATE, "y"),
        plab::history_desc("vec_z", 0.0, PLAB_SWAP_NEGATE, "z"),
        plab::history_desc("seen_along_normal", 0.0, PLAB_SWAP_KEEP, "n . the vector the law was given"),
        plab::history_desc("seen_magnitude", 0.0, PLAB_SWAP_KEEP, "|the vector the law was given|"),
    };
    using SpringBase::SpringBase;
    void law(const plab::Contact& c) const {
        const plab::Vec3 n = c.normal(), seen = c.history_vec(vec_x);
        c.set_force(k * c.overlap() * n);
        c.set_stiffness(k);
        c.history(seen_along_normal) = plab::dot(seen, n);
        c.history(seen_magnitude) = plab::norm(seen);
        c.set_history_vec(vec_x, c.dim() == 3 ? stored_3d : stored);
    }
};

struct TangentialProbeCentres : TangentialProbe {
    static constexpr const char* name = "tangential_probe_centres";
    static constexpr uint32_t flags = PLAB_MODEL_FORCE_AT_CENTRES;
    using TangentialProbe::TangentialProbe;
};

struct TangentialProbeSummed : TangentialProbe {
    static constexpr const char* name = "tangential_probe_summed";
    static constexpr plab_field_desc fields_accumulated[] = {plab::field_desc("tangential_probe_count", "1", 0.0)};
    using TangentialProbe::TangentialProbe;
    void law(const plab::Contact& c) const {
        TangentialProbe::law(c);
        c.accumulate1(0, 1.0);
    }
};

} // namespace

PLAB_PLUGIN(plab::add_contact_model<TangentialProbe>(r) || plab::add_contact_model<TangentialProbeCentres>(r) ||
            plab::add_contact_model<TangentialProbeSummed>(r))
