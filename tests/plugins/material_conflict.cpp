// Registers the material "probe_solid" (material_probe.cpp) with other
// properties: the host refuses it when material_probe is loaded first.
#include <plab/contact_model.hpp>

namespace {
struct OtherProbeSolid {
    static constexpr const char* name = "probe_solid";
    static constexpr const char* doc = "test material, declared otherwise";
    static constexpr plab_property_desc properties[] = {
        plab::prop::number("k", "stiffness", "N/m", 2e5, 0.0, 1e12, PLAB_MIN_EXCLUSIVE, "spring", PLAB_MIX_HARMONIC)};
};
} // namespace

PLAB_PLUGIN(plab::add_material<OtherProbeSolid>(r))
