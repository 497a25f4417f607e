// Scenes shared by the kernel tests (determinism, restart).
// A settling pile: `count` random balls falling into an open box, the
// linear model with friction and damping, so contacts form, slide and carry history.
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

// A 2D brittle plate hit by a steel ball at 30 m/s: bonds bend and break.
inline nlohmann::json breaking_plate_scene() {
    using nlohmann::json;
    return {{"dimension", 2},
            {"plugins", {"linear", "linear_pbond"}},
            {"bodies", {{{"type", "lattice"}, {"group", "plate"}, {"packing", "hexagonal"},
                         {"box", {{"min", {0, 0}}, {"max", {0.04, 0.008}}}}, {"radius", 0.001}, {"density", 2400}},
                        {{"type", "ball"}, {"group", "projectile"}, {"position", {0.02, 0.0115}},
                         {"velocity", {0, -30}}, {"radius", 0.002}, {"density", 7800}}}},
            {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"}, {"properties", {{"kn", 5e8}}}},
                                {{"groups", {"plate", "plate"}}, {"model", "linear_pbond"},
                                 {"calibrate", {{"method", "hexagonal_2d"}, {"E", 30e9}, {"nu", 0.2},
                                                {"sigma_ult", 5e6}, {"radius", 0.001}}}}}}};
}
