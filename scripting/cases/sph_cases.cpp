// Scene pieces shared by the SPH cases and tests: fixed boundary blocks
// (thesis §2.2.4) and the density passes of a scene.
#include "sph_cases.hpp"


namespace plab::cases {

using json = nlohmann::json;

json boundary_block(double x0, double y0, double x1, double y1, double db, double rest_density) {
    return {{"type", "lattice"}, {"group", "boundary"}, {"packing", "square"},
            {"box", {{"min", {x0, y0}}, {"max", {x1, y1}}}}, {"radius", db / 2}, {"spacing", db},
            {"mass", rest_density * db * db}, {"fix", {"all"}}};
}

json density_passes(int method, int boundary) {
    const json integration = {{"name", "sph_density_integration"}, {"properties", {{"boundary_group", boundary}}}};
    const json summation = {{"name", "sph_density_summation"}, {"material", "water"},
                            {"properties", {{"boundary_group", boundary}, {"normalised", method == 2 ? 1 : 0}}}};
    if (method == 0) return json::array({integration});
    if (method == 1) return json::array({summation});
    return json::array({integration, summation});  // eq. 9 filters the continuity density
}

} // namespace plab::cases
