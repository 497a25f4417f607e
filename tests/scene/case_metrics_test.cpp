// Metrics and checks of validation cases on a ball in free fall, where the
// figures are known by hand: the mean over time of a history sampled at two
// steps, the RMS difference and the lead against a reference curve (with a
// row filter), and a check on the difference of two runs' metrics.
#include "metrics.hpp"
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

using namespace plab;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

fs::path scratch_dir() {
    const fs::path dir = fs::temp_directory_path() / ("plab_case_metrics_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir;
}

// A ball falling from rest at g (no contacts), its velocity recorded every step.
json falling_ball(double g = 10) {
    return {{"dimension", 2},
            {"variables", {{"g", g}}},
            {"gravity", {0, "$(-g)"}},
            {"plugins", {"linear"}},
            {"timestep", {{"fixed", 0.01}}},
            {"bodies", {{{"type", "ball"}, {"group", "ball"}, {"position", {0, 0}}, {"radius", 0.01}, {"density", 1000}}}},
            {"histories", {{"every", 1}, {"record", {{{"quantity", "time"}}, {{"name", "vy"}, {"quantity", "ball.velocity.y"}, {"id", 0}}}}}}};
}

double figure(const json& metrics, const Simulation& sim, const std::string& dir, const char* field) {
    const json out = evaluate_metrics(metrics, sim, dir);
    REQUIRE(out.size() == 1);
    INFO(out.dump());
    REQUIRE(out[0].contains(field));
    return out[0][field].get<double>();
}

} // namespace

TEST_CASE("time_mean weights each sample by the time since the one before it, and mean counts samples", "[metrics]") {
    Simulation sim(falling_ball());
    sim.set_quiet(true);
    World& w = sim.world();
    sim.cycle(50);  // 0.5 s at 0.01 s: v = -10 t
    w.fixed_dt = 0.04;
    sim.cycle(25);  // 1 s more at 0.04 s
    // right Riemann sums of -10 t: -1.275 over the first 0.5 s, -10.2 over the next 1 s
    const json time_mean = {{{"name", "v"}, {"history", "vy"}, {"reduce", "time_mean"}}};
    CHECK(figure(time_mean, sim, ".", "value") == Approx(-11.475 / 1.5));
    const json mean = {{{"name", "v"}, {"history", "vy"}, {"reduce", "mean"}}};
    CHECK(figure(mean, sim, ".", "value") == Approx(-382.5 / 76));  // 76 samples, t = 0 included
    // a window that starts between samples takes the interval from the sample before it
    const json window = {{{"name", "v"}, {"history", "vy"}, {"reduce", "time_mean"}, {"from", 0.52}, {"to", 1.51}}};
    CHECK(figure(window, sim, ".", "value") == Approx(-10 * (0.54 + 1.5) / 2));  // samples 0.54 ... 1.5, each 0.04 s
}

TEST_CASE("slope is the least-squares rate of one history against another, or against time", "[metrics]") {
    json scene = falling_ball();
    scene["histories"]["record"].push_back({{"name", "y"}, {"quantity", "ball.position.y"}, {"id", 0}});
    Simulation sim(scene);
    sim.set_quiet(true);
    sim.cycle(100);
    // v = -10 t exactly at every sample: dv/dt = -10, and dv/dv = 1
    CHECK(figure({{{"name", "a"}, {"history", "vy"}, {"reduce", "slope"}}}, sim, ".", "value") == Approx(-10).epsilon(1e-12));
    CHECK(figure({{{"name", "a"}, {"history", "vy"}, {"reduce", "slope"}, {"x", "vy"}, {"from", 0.3}}}, sim, ".", "value") ==
          Approx(1).epsilon(1e-12));
    // the leapfrog's y is quadratic in t: its slope over [0.5, 1] is the mean velocity there, -7.5 (to a step)
    CHECK(figure({{{"name", "a"}, {"history", "y"}, {"reduce", "slope"}, {"from", 0.5}}}, sim, ".", "value") == Approx(-7.5).epsilon(0.01));
    const json x_without_slope = {{{"name", "a"}, {"history", "vy"}, {"x", "y"}}};
    CHECK_THROWS_WITH(evaluate_metrics(x_without_slope, sim, "."), Contains("scene.metrics[0].x") && Contains("slope"));
}

TEST_CASE("a curve metric gives the RMS difference in the reference's units, or how far the run leads", "[metrics]") {
    const fs::path dir = scratch_dir();
    // series A: at t = 0 (v = 0: only the RMS counts it), 0.2 (run -2 against -2.5: leads by 0.2), 0.4 (run -4
    // against -3.5: lags), 1.0 (equal), 2.0 (after the run); series B would lead everywhere
    std::ofstream(dir / "ref.csv") << "# a reference\nseries,t,v\nA,0,0\nA,0.2,-2.5\nB,0.2,-1\nA,0.4,-3.5\nA,1.0,-10\nA,2.0,-20\n";
    Simulation sim(falling_ball());
    sim.set_quiet(true);
    sim.cycle(100);
    const json series_a = {{{"column", 0}, {"equals", "A"}}};
    json m = json::array({{{"name", "v"}, {"history", "vy"},
                           {"reference", {{"file", "ref.csv"}, {"x_column", 1}, {"y_column", 2}, {"where", series_a}}}}});
    CHECK(figure(m, sim, dir.string(), "error") == Approx((0.2 + 0.5 / 3.5) / 3));
    m[0]["norm"] = "rms";
    CHECK(figure(m, sim, dir.string(), "error") == Approx(std::sqrt(0.5 / 4)));
    CHECK(figure(m, sim, dir.string(), "points") == 4);
    m[0]["norm"] = "lead";
    CHECK(figure(m, sim, dir.string(), "error") == Approx(0.2));
    std::ofstream(dir / "lagging.csv") << "t,v\n0.5,-4\n";  // the run (-5) lags only: no lead
    m[0]["reference"] = {{"file", "lagging.csv"}, {"x_column", 0}, {"y_column", 1}};
    CHECK(figure(m, sim, dir.string(), "error") == 0.0);
    m[0]["norm"] = "median";
    CHECK_THROWS_WITH(evaluate_metrics(m, sim, dir.string()), Contains("scene.metrics[0].norm") && Contains("rms"));
    fs::remove_all(dir);
}

TEST_CASE("a case check on the difference of two runs' metrics", "[metrics][validation]") {
    const fs::path dir = scratch_dir() / "cases", tiny = dir / "tiny";
    fs::create_directories(tiny);
    json scene = falling_ball();
    scene["metrics"] = {{{"name", "speed"}, {"history", "vy"}, {"scale", -1}}};
    scene["commands"] = {{{"cycle", 10}}};  // 0.1 s: 1 m/s at g = 10, 0.5 m/s at g = 5
    std::ofstream(tiny / "scene.json") << scene.dump(1);
    const json spec = {{"description", "two falls"},
                       {"runs", {{{"label", "g 10"}}, {{"label", "g 5"}, {"set", {{"variables.g", 5}}}}}},
                       {"checks", {{{"name", "faster at g 10"}, {"difference", {"g 10", "g 5"}}, {"metric", "speed"},
                                    {"field", "value"}, {"at_least", 0.49}},
                                   {{"name", "not by much"}, {"difference", {"g 10", "g 5"}}, {"metric", "speed"},
                                    {"field", "value"}, {"tolerance", 0.4}}}}};
    std::ofstream(tiny / "case.json") << spec.dump(1);
    const fs::path out = dir / "out.txt";
    const std::string cmd = "PLAB_VALIDATION_DIR=" + dir.string() + " " + PLAB_EXE + " validate tiny --quick > " + out.string() + " 2>&1";
    const int status = std::system(cmd.c_str());
    std::ifstream f(out);
    std::stringstream text;
    text << f.rdbuf();
    INFO(text.str());
    CHECK(status != 0);  // the second check fails
    CHECK_THAT(text.str(), Contains("faster at g 10: 0.5 (at least 0.49) PASS") && Contains("not by much: 0.5 (tolerance 0.4) FAIL"));
    fs::remove_all(dir.parent_path());
}
