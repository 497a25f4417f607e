// Scene variables and "$(expressions)" (scripting/variables.cpp), history
// columns computed from others, field probes and the validation runner's
// measurements, on small scenes whose answers are known.
#include "simulation.hpp"
#include "variables.hpp"
#include "../support/static_tank.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

using namespace plab;
using Catch::Matchers::Contains;

namespace {

json one_ball(const json& variables, const json& radius) {
    return {{"dimension", 2}, {"variables", variables},
            {"bodies", {{{"type", "ball"}, {"position", {0, 0}}, {"radius", radius}, {"density", 1000}}}}};
}

// The quick static tank (0.15 m of water, dp 10 mm, 0.3 s) with pressure
// probes of two kernel radii at two depths and one outside the fluid.
json quick_tank_scene_for_probe() {
    json scene = testing_support::quick_tank_scene();
    const auto probe = [](const char* name, double x, double y) {
        return json{{"name", name}, {"quantity", "probe.sph_pressure"}, {"point", {x, y}}, {"radius", 0.02}, {"group", "fluid"}};
    };
    scene["histories"] = {{"every", 10}, {"record", {{{"quantity", "time"}}, probe("p_low", 0.075, 0.03), probe("p_mid", 0.075, 0.075),
                                                    probe("p_outside", 0.075, 0.5)}}};
    scene.erase("metrics");
    return scene;
}

} // namespace

TEST_CASE("scene variables may use each other in any order and fill the $(...) values", "[scene]") {
    // "b" sorts before "a" uses it: the order of the keys does not matter
    const json scene = resolve_variables(one_ball({{"b", "2 * a"}, {"a", 3}, {"c", "ceil(b / 4) + floor(pi)"}}, "$(b / 100)"));
    CHECK(scene["variables"]["b"].get<double>() == 6);
    CHECK(scene["variables"]["c"].get<double>() == 5);  // ceil(1.5) + floor(3.14...)
    CHECK(scene["bodies"][0]["radius"].get<double>() == Approx(0.06).epsilon(1e-15));
    Simulation sim(one_ball({{"r", 0.02}}, "$(r)"));
    CHECK(sim.world().bodies.radius[0] == 0.02);
}

TEST_CASE("elliptic_k is the complete elliptic integral of the first kind", "[scene]") {
    // K(0) = pi/2; K(sin 30 deg) = 1.6857503548125961 (Abramowitz & Stegun table 17.1)
    const json scene = resolve_variables(one_ball({{"k0", "elliptic_k(0)"}, {"k30", "elliptic_k(sin(pi / 6))"}}, 0.01));
    CHECK(scene["variables"]["k0"].get<double>() == Approx(M_PI / 2).epsilon(1e-15));
    CHECK(scene["variables"]["k30"].get<double>() == Approx(1.6857503548125961).epsilon(1e-14));
    CHECK_THROWS_WITH(resolve_variables(one_ball({{"k", "elliptic_k(1)"}}, 0.01)), Contains("scene.variables.k") && Contains("not finite"));
}

TEST_CASE("a clump's history columns: its spin about the principal axes and its energy, and a ball's id is not a clump's", "[scene][clump]") {
    json scene = {{"dimension", 3}, {"gravity", {0, 0, 0}},
                  {"bodies", {{{"type", "rigid"}, {"shape", {{"type", "box"}, {"size", {0.1, 0.2, 0.3}}}}, {"density", 1000},
                               {"pebbles", {{{"position", {0, 0, 0}}, {"radius", 0.05}}}}, {"position", {1, 2, 3}},
                               {"orientation", {{"axis", {0, 0, 1}}, {"angle", 90}}}, {"angular_velocity", {0, 2, 0}}},
                              {{"type", "ball"}, {"position", {5, 0, 0}}, {"radius", 0.01}, {"density", 1000}}}},
                  {"timestep", {{"fixed", 1e-3}}},
                  {"histories", {{"every", 1}, {"record", {{{"name", "w_principal"}, {"quantity", "clump.principal_angular_velocity.x"}, {"id", 0}},
                                                         {{"name", "w_largest"}, {"quantity", "clump.principal_angular_velocity.z"}, {"id", 0}},
                                                         {{"name", "w_world"}, {"quantity", "clump.angular_velocity.magnitude"}, {"id", 0}},
                                                         {{"name", "E"}, {"quantity", "clump.kinetic_energy"}, {"id", 0}},
                                                         {{"name", "z"}, {"quantity", "clump.position.z"}, {"id", 0}}}}}},
                  {"commands", {{{"cycle", 1}}}}};
    Simulation sim(scene);
    sim.set_quiet(true);
    sim.run();
    // turned 90 deg about z, the body's x axis lies along world y: the spin is about body x, whose
    // moment m (b^2 + c^2) / 12 is the largest (principal z); none about the smallest's axis (body z)
    const double m = 1000 * 0.1 * 0.2 * 0.3, I = m * (0.2 * 0.2 + 0.3 * 0.3) / 12;
    CHECK(std::fabs(sim.history("w_principal")[0]) < 1e-12);
    CHECK(std::fabs(sim.history("w_largest")[0]) == Approx(2).epsilon(1e-12));
    CHECK(sim.history("w_world")[0] == Approx(2));
    CHECK(sim.history("E")[0] == Approx(0.5 * I * 4).epsilon(1e-12));
    CHECK(sim.history("z")[0] == 3);
    scene["histories"]["record"][0]["id"] = 1;
    CHECK_THROWS_WITH(Simulation(scene), Contains("scene.histories.record[0].id") && Contains("no clump has id 1"));
}

TEST_CASE("a scene without variables or expressions is left as it is", "[scene]") {
    const json scene = one_ball(json::object(), 0.01);
    CHECK(resolve_variables(scene) == scene);
    json text = scene;
    text["description"] = "radius $(not an expression) stays text";
    CHECK(resolve_variables(text)["description"] == text["description"]);
}

TEST_CASE("an unknown name, a cycle or a bad expression names its JSON path", "[scene][errors]") {
    CHECK_THROWS_WITH(resolve_variables(one_ball({{"a", 1}}, "$(a + b)")), Contains("scene.bodies[0].radius") && Contains("a + b"));
    CHECK_THROWS_WITH(resolve_variables(one_ball({{"a", "b + 1"}, {"b", "a"}}, 0.01)), Contains("scene.variables.a"));
    CHECK_THROWS_WITH(resolve_variables(one_ball({{"a", "sqrt(-1)"}}, 0.01)), Contains("scene.variables.a") && Contains("not finite"));
    CHECK_THROWS_WITH(resolve_variables(one_ball({{"a", json::array({1})}}, 0.01)), Contains("scene.variables.a"));
    CHECK_THROWS_WITH(Simulation(one_ball({{"r", 0.0}}, "$(r)")), Contains("scene.bodies[0].radius"));
}

TEST_CASE("a history column can be a formula of the columns before it and the variables", "[scene]") {
    json scene = one_ball({{"v", 2.0}}, 0.01);
    scene["bodies"][0]["velocity"] = {"$(v)", 0};
    scene["timestep"] = {{"fixed", 1e-3}};
    scene["histories"] = {{"every", 1},
                          {"record", {{{"quantity", "time"}},
                                      {{"name", "x"}, {"quantity", "ball.position.x"}, {"id", 0}},
                                      {{"name", "x_exact"}, {"expression", "v * time"}},
                                      {{"name", "error"}, {"expression", "abs(x - x_exact)"}}}}};
    scene["commands"] = {{{"cycle", 50}}};
    Simulation sim(scene);
    sim.set_quiet(true);
    sim.run();
    const auto t = sim.history("time"), x_exact = sim.history("x_exact"), error = sim.history("error");
    REQUIRE(t.size() == 51);
    for (std::size_t k = 0; k < t.size(); ++k) {
        CHECK(x_exact[k] == Approx(2.0 * t[k]).epsilon(1e-15));
        CHECK(error[k] < 1e-12);  // uniform motion: the leapfrog is exact
    }
    scene["histories"]["record"][2]["expression"] = "v * later";  // a column not (yet) recorded
    CHECK_THROWS_WITH(Simulation(scene), Contains("scene.histories.record[2].expression"));
}

TEST_CASE("a pressure probe in a tank at rest reads the hydrostatic pressure at its depth", "[scene][sph]") {
    Simulation sim(quick_tank_scene_for_probe());
    sim.set_quiet(true);
    sim.run();
    const double rho0 = 1000, g = 9.81, H = 0.15;
    const std::vector<double> t = sim.history("time");
    // averaged over the last 20 % of the run, as the static tank case does: the acoustic ringing (period 2H/c0) filtered
    const auto late_mean = [&](const std::vector<double>& p) {
        double sum = 0;
        int n = 0;
        for (std::size_t k = 0; k < p.size(); ++k)
            if (t[k] >= 0.24) { sum += p[k]; ++n; }
        return sum / n;
    };
    for (const auto& [name, y] : {std::pair<const char*, double>{"p_low", 0.03}, {"p_mid", 0.075}}) {
        const double p = late_mean(sim.history(name)), exact = rho0 * g * (H - y);
        INFO(name << ": " << p << " Pa against " << exact);
        CHECK(p == Approx(exact).epsilon(0.05));
    }
    CHECK(std::isnan(sim.history("p_outside").back()));  // no fluid within reach of a point outside the tank
}

TEST_CASE("one scene is a resolution study: --set variables.dp changes every quantity derived from it", "[scene]") {
    using namespace testing_support;
    for (const double dp : {0.01, 0.005}) {
        const json scene = resolve_variables(case_scene("dam_break", {{"variables.dp", dp}}));
        Simulation sim(scene);
        int fluid = 0;
        for (std::size_t i = 0; i < sim.world().bodies.size(); ++i) fluid += sim.world().bodies.group[i] == 0;
        CHECK(fluid == int(std::lround(0.1 / dp * 0.2 / dp)));  // the a x 2a column at spacing dp
        CHECK(scene["materials"]["water"]["smoothing_length"].get<double>() == Approx(1.3 * dp));
        CHECK(scene["bodies"][0]["mass"].get<double>() == Approx(1000 * dp * dp));
    }
}
