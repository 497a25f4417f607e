// Histories of a scene: histories.at_end adds the state the run ends in.
#include <simulation.hpp>

#include <catch2/catch.hpp>

using namespace plab;

namespace {

// A ball falling under g = 10 m/s² at a fixed step of 1 ms, its step count
// sampled every 7 steps; `steps` cycles.
json falling_ball(long steps, bool at_end) {
    return {{"dimension", 2},
            {"gravity", {0, -10}},
            {"bodies", {{{"type", "ball"}, {"position", {0, 1}}, {"radius", 0.01}, {"density", 1000}}}},
            {"timestep", {{"fixed", 1e-3}}},
            {"histories", {{"every", 7}, {"at_end", at_end},
                           {"record", {{{"name", "step"}, {"quantity", "step"}}}}}},
            {"commands", {{{"cycle", steps}}}}};
}

std::vector<double> steps_sampled(json scene) {
    Simulation sim(scene);
    sim.set_quiet(true);
    sim.run();
    return sim.history("step");
}

} // namespace

TEST_CASE("histories.at_end takes a last row of the state the run ends in, never twice", "[scene][histories]") {
    CHECK(steps_sampled(falling_ball(10, false)) == std::vector<double>{0, 7});
    CHECK(steps_sampled(falling_ball(10, true)) == std::vector<double>{0, 7, 10});
    CHECK(steps_sampled(falling_ball(14, true)) == std::vector<double>{0, 7, 14});  // step 14 was sampled
}
