// A spring with one property of every kind (abi.h PLAB_KIND_*), for the
// loader's parsing and refusal tests: the values the model receives are its
// instance's props (tests/scene/property_kinds_test.cpp).
#include "test_models.hpp"

namespace {
constexpr const char* shapes[] = {"round", "flat", "pointed"};
}

struct KindsProbe : SpringBase {
    static constexpr const char* name = "kinds_probe";
    static constexpr plab_property_desc properties[] = {
        plab::prop::number("k", "stiffness", "N/m", 1e5, 0.0, 1e12, PLAB_MIN_EXCLUSIVE, "spring", PLAB_MIX_HARMONIC),
        plab::prop::integer("layers", "layer count", "1", 1, 1, 10, "a count"),
        plab::prop::boolean("tension", "pulls too", false, "a switch"),
        plab::prop::choice("shape", "tip shape", shapes, 0, "a choice"),
        plab::prop::group("target_group", "target group", "a group the scene must name"),
        plab::prop::optional_group("skip_group", "skipped group", "a group or none"),
        plab::prop::number("stick", "stickiness", "1", 0.0, 0.0, 1.0, 0, "a number without a mixing rule"),
    };
    using SpringBase::SpringBase;
    void law(const plab::Contact& c) const { c.set_force(k * c.overlap() * c.normal()); c.set_stiffness(k); }
};
PLAB_PLUGIN(plab::add_contact_model<KindsProbe>(r))
