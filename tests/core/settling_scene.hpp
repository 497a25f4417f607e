// A settling pile for the kernel tests (determinism, restart): `count`
// random balls falling into an open box, the linear model with friction
// and damping, so contacts form, slide and carry history.
#pragma once

#include <nlohmann/json.hpp>

inline nlohmann::json settling_scene(int dim, int count) {
    using nlohmann::json;
    auto v = [dim](double x, double y, double z) { return dim == 2 ? json::array({x, y}) : json::array({x, y, z}); };
    return {{"dimension", dim},
            {"plugins", {"linear"}},
            {"gravity", v(0, -9.81, 0)},
            {"bodies", {{{"type", "random_fill"}, {"group", "grains"}, {"box", {{"min", v(0, 0, 0)}, {"max", v(0.1, 0.1, 0.1)}}},
                         {"radius", {0.002, 0.004}}, {"density", 2500}, {"count", count}, {"seed", 3}}}},
            {"walls", {{{"type", "box"}, {"min", v(0, 0, 0)}, {"max", v(0.1, 0.2, 0.1)}}}},
            {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"},
                                 {"properties", {{"kn", 1e4}, {"ks", 5e3}, {"fric", 0.5}, {"dp_nratio", 0.2}}}}}}};
}
