// Two bonded discs (R = 1 mm, touching, both fixed, linear_pbond with
// kn_bar = ks_bar = 1e9); ball 1 is driven at `velocity`. For the bond tests
// and the bond measurements' tests.
#pragma once

#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <memory>

namespace plab::testing_support {

inline std::unique_ptr<Simulation> bonded_pair(const json& velocity, double pb_ten, double pb_coh) {
    const double R = 0.001;
    json scene = {{"dimension", 2},
                  {"plugins", {"linear_pbond"}},
                  {"bodies", {{{"type", "ball"}, {"position", {0, 0}}, {"radius", R}, {"density", 2500}, {"fix", {"all"}}},
                              {{"type", "ball"}, {"position", {2 * R, 0}}, {"radius", R}, {"density", 2500},
                               {"fix", {"all"}}, {"velocity", velocity}}}},
                  {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear_pbond"},
                                       {"properties", {{"kn", 1e6}, {"ks", 1e6}, {"pb_kn", 1e9}, {"pb_ks", 1e9},
                                                       {"pb_ten", pb_ten}, {"pb_coh", pb_coh}}}}}},
                  {"timestep", {{"fixed", 1e-5}}}};
    auto sim = std::make_unique<Simulation>(scene);
    sim->set_quiet(true);
    REQUIRE(sim->world().bond(0, 0, 1e-9) == 1);
    return sim;
}

} // namespace plab::testing_support
