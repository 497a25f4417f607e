// A block of SPH solid (physics/sph_solid) for the solid's tests: a square
// (2D) or cubic (3D) lattice of particles of one material, moving with a
// velocity profile.
#pragma once

#include "simulation.hpp"

#include <cmath>
#include <string>

namespace plab::testing_support {

inline constexpr double kE = 2e6, kNu = 0.3, kRho = 1000, kDp = 0.002;

// A block of SPH solid, n particles a side (default 10 in 2D, 6 in 3D), every
// particle fixed (velocity held) when `fixed`, moving with the velocity
// `profile` (expressions of x, y, z) for `cycles` steps of dt.
inline json moving_block(int dim, const json& profile, int cycles, double dt, bool fixed = true, int n = 0) {
    if (n == 0) n = dim == 2 ? 10 : 6;
    const double side = n * kDp;
    const json box = dim == 2 ? json{{"min", {0, 0}}, {"max", {side, side}}}
                              : json{{"min", {0, 0, 0}}, {"max", {side, side, side}}};
    json body = {{"type", "lattice"}, {"group", "solid"}, {"packing", dim == 2 ? "square" : "cubic"}, {"box", box},
                 {"radius", kDp / 2}, {"spacing", kDp}, {"mass", kRho * std::pow(kDp, dim)}, {"fix", {"rotation"}}};
    const json all = dim == 2 ? json{{"min", {-1, -1}}, {"max", {1, 1}}} : json{{"min", {-1, -1, -1}}, {"max", {1, 1, 1}}};
    json set = {{"region", all}, {"velocity_profile", profile}};
    if (fixed) set["fix"] = {"all"};
    return {{"dimension", dim},
            {"plugins", {"sph_solid"}},
            {"bodies", {body}},
            {"materials", {{"steel", {{"groups", {"solid"}}, {"rest_density", kRho}, {"youngs_modulus", kE},
                                      {"poissons_ratio", kNu}, {"smoothing_length", 1.3 * kDp},
                                      {"particle_spacing", kDp}}}}},
            {"contact_models", {{{"groups", {"solid", "solid"}}, {"model", "sph_solid"}, {"properties", {{"alpha", 0.0}}}}}},
            {"passes", {{{"name", "sph_solid_stress"}, {"material", "steel"}, {"properties", {{"artificial_stress", 0.0}}}}}},
            {"timestep", {{"fixed", dt}}},
            {"commands", {{{"set", set}}, {{"cycle", cycles}}}}};
}

// One per-body field of body i.
inline double field_at(const World& w, const std::string& name, std::size_t i) {
    return w.fields.column(w.fields.index(name))[i];
}

} // namespace plab::testing_support
