// Histories and metrics of a scene: histories.at_end adds the state the
// run ends in; a metric's `against` takes its solution from another column.
#include <simulation.hpp>

#include <catch2/catch.hpp>

#include <cmath>

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

TEST_CASE("a metric against another history takes that column, reduced alike, as its solution", "[scene][metrics]") {
    json scene = {{"dimension", 2},
                  {"gravity", {0, -10}},
                  {"bodies", {{{"type", "ball"}, {"position", {0, 1}}, {"radius", 0.01}, {"density", 1000}}}},
                  {"timestep", {{"fixed", 1e-3}}},
                  {"histories", {{"every", 5}, {"record", {{{"quantity", "time"}},
                                                            {{"name", "y"}, {"quantity", "ball.position.y"}, {"id", 0}},
                                                            {{"name", "drop"}, {"expression", "1 - y"}},
                                                            {{"name", "exact"}, {"expression", "5 * time^2"}},
                                                            {{"name", "half"}, {"expression", "drop / 2"}}}}}},
                  {"metrics", {{{"name", "fall"}, {"history", "drop"}, {"against", "exact"}},
                               {{"name", "twice"}, {"history", "drop"}, {"against", "half"}},
                               {{"name", "largest"}, {"history", "drop"}, {"reduce", "max"}, {"against", "half"}}}},
                  {"commands", {{{"cycle", 100}}}}};
    Simulation sim(scene);
    sim.set_quiet(true);
    sim.run();
    const json m = sim.summary()["metrics"];
    const double drop = 1 - sim.world().bodies.position[0].y();
    CHECK(m[0]["value"].get<double>() == drop);
    CHECK(m[0]["reference"].get<double>() == Approx(0.05).epsilon(1e-9));  // g t² / 2 at t = 0.1 s, the last row
    CHECK(m[0]["error"].get<double>() == Approx(std::fabs(drop - 0.05) / 0.05).margin(1e-12));  // the leapfrog is exact: 0
    CHECK(m[1]["error"].get<double>() == Approx(1.0).epsilon(1e-12));       // |d - d/2| / |d/2|
    CHECK(m[2]["reference"].get<double>() == Approx(0.5 * m[2]["value"].get<double>()).epsilon(1e-12));
}
