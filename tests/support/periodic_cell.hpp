// Scenes in a periodic cell [0, L]^dim, periodic along every axis, for the
// periodic-cell and Lees–Edwards tests: a linear contact and 2D balls.
#pragma once

#include "simulation.hpp"

#include <plab_host/contacts.hpp>

#include <utility>

namespace plab::testing_support {

inline const json kCellLinear = {{"kn", 1e4}, {"ks", 5e3}, {"fric", 0.5}, {"dp_nratio", 0.1}};

// The cell with `balls`; sheared at `shear_rate` (flow x, gradient y, the
// balls' velocities as given) when it is not zero.
inline json periodic_cell_scene(int dim, double L, json balls, double shear_rate = 0) {
    auto v = [dim](double x) { return dim == 2 ? json::array({x, x}) : json::array({x, x, x}); };
    json axes = dim == 2 ? json::array({"x", "y"}) : json::array({"x", "y", "z"});
    json domain = {{"min", v(0)}, {"max", v(L)}, {"periodic", axes}};
    if (shear_rate != 0) domain["shear"] = {{"rate", shear_rate}, {"initial_velocity", "as_given"}};
    return {{"dimension", dim},
            {"plugins", {"linear"}},
            {"domain", std::move(domain)},
            {"bodies", std::move(balls)},
            {"timestep", {{"fixed", 1e-5}}},
            {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"}, {"properties", kCellLinear}}}}};
}

// A 2D ball of radius 2 mm, 2500 kg/m3, in group "g".
inline json cell_ball(double x, double y, double vx, double vy, double spin) {
    return {{"type", "ball"}, {"group", "g"}, {"position", {x, y}}, {"velocity", {vx, vy}},
            {"angular_velocity", spin}, {"radius", 0.002}, {"density", 2500}};
}

// Σ m |v|: the scale against which momentum round-off is judged.
inline double momentum_scale(const World& w) {
    double scale = 0;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) scale += w.bodies.mass[i] * w.bodies.velocity[i].norm();
    return scale;
}

// Runs `blocks` blocks of `steps` cycles and counts, after each, the active
// contacts of model 0 whose two stored centres `across(x1, x2)` calls far
// apart: pairs that meet through the boundary.
template <class Across> std::size_t cycle_counting_across(Simulation& sim, int blocks, int steps, Across across) {
    const World& w = sim.world();
    std::size_t n = 0;
    for (int block = 0; block < blocks; ++block) {
        sim.cycle(steps);
        const ContactTable t = w.model(0).balls();
        for (std::size_t k = 0; k < t.size(); ++k)
            if (t.active(k) && across(w.bodies.position[t.end1(k)], w.bodies.position[t.end2(k)])) ++n;
    }
    return n;
}

} // namespace plab::testing_support
