// A model that names a material and declares one of its properties with
// another default than the material's: the host must refuse it, naming the
// property and the difference.
#include "test_models.hpp"

namespace {
struct Stiff {
    static constexpr const char* name = "stiff_solid";
    static constexpr const char* doc = "test material";
    static constexpr plab_property_desc properties[] = {
        plab::prop::number("k", "stiffness", "N/m", 2e5, 0.0, 1e12, PLAB_MIN_EXCLUSIVE, "spring")};
};
struct MismatchSpring : SpringBase {  // k: default 1e5
    static constexpr const char* name = "mismatch_spring";
    using material = Stiff;
    using SpringBase::SpringBase;
    void law(const plab::Contact& c) const { c.set_force(k * c.overlap() * c.normal()); c.set_stiffness(k); }
};
} // namespace

PLAB_PLUGIN(plab::add_contact_model<MismatchSpring>(r))
