// The named measurements of scripting/measurements/structure_measurements.cpp
// (the elastic_gate case), each on a tiny scene of its own whose answer is
// known: balls in free flight, balls at rest in strips.
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

using namespace plab;
using Catch::Matchers::Contains;

namespace {

json ball(const std::string& group, double x, double y, const json& velocity = {0, 0}) {
    return {{"type", "ball"}, {"group", group}, {"position", {x, y}}, {"radius", 0.001}, {"density", 1000},
            {"velocity", velocity}};
}

// Balls far apart, no gravity: each flies at its start velocity.
json flight(const std::vector<json>& bodies, const std::vector<json>& columns) {
    json record = json::array({{{"quantity", "time"}}});
    for (const json& c : columns) record.push_back(c);
    return {{"dimension", 2}, {"bodies", bodies}, {"timestep", {{"fixed", 1e-3}}},
            {"histories", {{"every", 1}, {"record", record}}}, {"commands", {{{"solve", {{"time", 0.01}}}}}}};
}

json displacement(const std::string& name, const json& near, const std::string& component) {
    return {{"name", name}, {"quantity", "measure.ball_displacement"},
            {"with", {{"group", "g"}, {"near", near}, {"component", component}}}};
}

} // namespace

TEST_CASE("ball_displacement follows the ball that started nearest the point, the first of two equally near", "[measurements]") {
    // balls 0 and 1 lie 1 m either side of the origin; 0 flies at (1, 2) m/s, 1 at rest
    const std::vector<json> bodies = {ball("g", -1, 0, {1, 2}), ball("g", 1, 0), ball("g", 0, 3, {5, 5}), ball("other", 0, 0, {9, 9})};
    Simulation sim(flight(bodies, {displacement("dx", {0, 0}, "x"), displacement("dy", {0, 0}, "y"),
                                   displacement("d", {0, 0}, "magnitude"), displacement("far", {0.9, 0}, "x")}));
    sim.set_quiet(true);
    sim.run();
    const double t = sim.history("time").back();
    REQUIRE(t == Approx(0.01));
    CHECK(sim.history("dx").front() == 0);
    CHECK(sim.history("dx").back() == Approx(1 * t).epsilon(1e-9));  // ball 0, not the "other" group's ball at the point
    CHECK(sim.history("dy").back() == Approx(2 * t).epsilon(1e-9));
    CHECK(sim.history("d").back() == Approx(std::sqrt(5.0) * t).epsilon(1e-9));
    CHECK(sim.history("far").back() == 0);  // nearer ball 1, at rest
}

TEST_CASE("ball_displacement names the path of a bad component or an empty group", "[measurements][scene]") {
    const std::vector<json> bodies = {ball("g", 0, 0), ball("h", 1, 1)};
    CHECK_THROWS_WITH(Simulation(flight(bodies, {displacement("dx", {0, 0}, "w")})),
                      Contains("scene.histories.record[1].with.component") && Contains("\"w\""));
    json no_balls = flight(bodies, {displacement("dx", {0, 0}, "x")});
    no_balls["histories"]["record"][1]["with"]["group"] = "nobody";
    CHECK_THROWS_WITH(Simulation(no_balls), Contains("scene.histories.record[1].with.group") && Contains("nobody"));
}

TEST_CASE("strip_top is the highest centre of the group from x_min up to but not including x_max, 0 in an empty strip", "[measurements]") {
    const std::vector<json> bodies = {ball("fluid", 0.05, 0.3), ball("fluid", 0.15, 0.5), ball("fluid", 0.25, 0.7), ball("other", 0.15, 0.9)};
    auto strip = [](const std::string& name, double lo, double hi) {
        return json{{"name", name}, {"quantity", "measure.strip_top"}, {"with", {{"group", "fluid"}, {"x_min", lo}, {"x_max", hi}}}};
    };
    Simulation sim(flight(bodies, {strip("a", 0.1, 0.2), strip("b", 0.15, 0.25), strip("all", 0, 1), strip("empty", 0.3, 0.4)}));
    sim.set_quiet(true);
    sim.run();
    CHECK(sim.history("a").back() == Approx(0.5));
    CHECK(sim.history("b").back() == Approx(0.5));  // x_min inclusive, x_max exclusive: the ball at 0.25 is out
    CHECK(sim.history("all").back() == Approx(0.7));  // the "other" group's higher ball is not counted
    CHECK(sim.history("empty").back() == 0);
    json bad = flight(bodies, {strip("a", 0.2, 0.1)});
    CHECK_THROWS_WITH(Simulation(bad), Contains("scene.histories.record[1].with.x_max") && Contains("empty"));
}
