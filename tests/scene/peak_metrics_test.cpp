// Scene metrics of a peak (scripting/metrics.cpp; the elastic_gate case's
// free end): the time of a history's maximum, a reduction against the same
// reduction of a reference curve, and the RMS difference over the curve's
// peak. The history is a ball thrown up, y = v0 t - g t²/2 (peak v0²/2g at
// v0/g); the reference is that parabola shifted up by d.
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

using namespace plab;
namespace fs = std::filesystem;

namespace {

constexpr double v0 = 1.0, g = 9.81, d = 0.001;

double parabola(double t) { return v0 * t - 0.5 * g * t * t; }

// The reference CSV beside a scene in a fresh folder: series "up" (the
// parabola + d, its largest point at t = 0.10) and a series "other" that the
// metrics' "where" must leave out.
std::string reference_folder() {
    const fs::path dir = fs::temp_directory_path() / "plab_peak_metrics_test";
    fs::create_directories(dir);
    std::ofstream f(dir / "thrown.csv");
    f << "# a test curve\nseries,t,y\n";
    for (double t : {0.02, 0.05, 0.08, 0.10, 0.13, 0.16}) f << "up," << t << "," << parabola(t) + d << "\n";
    f << "other,0.1019,5\nother,0.05,-3\n";
    return dir.string();
}

json metric(const std::string& name, json extra) {
    json m = {{"name", name}, {"history", "y"},
              {"reference", {{"file", "thrown.csv"}, {"x_column", 1}, {"y_column", 2}, {"where", {{{"column", 0}, {"equals", "up"}}}}}}};
    m.update(extra);
    return m;
}

json metric_of(const Simulation& sim, const std::string& name) {
    const json summary = sim.summary();  // (a range over summary()["metrics"] would outlive the temporary)
    for (const json& m : summary["metrics"])
        if (m["name"] == name) return m;
    FAIL("no metric " << name);
    return {};
}

} // namespace

TEST_CASE("metrics of a peak: its time, against the reference's peak, and the RMS over the reference's peak", "[metrics]") {
    const json scene = {
        {"dimension", 2},
        {"gravity", {0, -g}},
        {"bodies", {{{"type", "ball"}, {"group", "b"}, {"position", {0, 0}}, {"radius", 0.001}, {"density", 1000}, {"velocity", {0, v0}}}}},
        {"timestep", {{"fixed", 1e-5}}},
        {"histories", {{"every", 1}, {"record", {{{"quantity", "time"}}, {{"name", "y"}, {"quantity", "group.max.position.y"}, {"group", "b"}}}}}},
        {"metrics", json::array({json{{"name", "peak_time_exact"}, {"history", "y"}, {"reduce", "time_of_max"}, {"analytical", v0 / g}},
                                 metric("peak_time", {{"reduce", "time_of_max"}}),
                                 metric("peak", {{"reduce", "max"}}),
                                 metric("rms", {{"norm", "rms_over_peak"}}),
                                 metric("mean", json::object())})},
        {"commands", {{{"solve", {{"time", 0.15}}}}}}};
    Simulation sim(scene, reference_folder());
    sim.set_quiet(true);
    sim.run();
    CHECK(metric_of(sim, "peak_time_exact")["error"].get<double>() < 1e-3);  // the peak's time within a step or so
    const json pt = metric_of(sim, "peak_time"), pk = metric_of(sim, "peak");
    CHECK(pt["value"].get<double>() == Approx(v0 / g).margin(2e-5));
    CHECK(pt["reference"].get<double>() == Approx(0.10));  // the "up" series' largest point, not "other"'s
    CHECK(pt["error"].get<double>() == Approx(v0 / g - 0.10).margin(2e-5));  // absolute, in s
    const double ref_peak = parabola(0.10) + d;
    CHECK(pk["value"].get<double>() == Approx(v0 * v0 / (2 * g)).epsilon(1e-3));
    CHECK(pk["reference"].get<double>() == Approx(ref_peak));
    CHECK(pk["error"].get<double>() == Approx(ref_peak - v0 * v0 / (2 * g)).epsilon(0.02));
    // RMS over the five points inside the run (the one at 0.16 s is past its end), over the reference's peak
    const json rms = metric_of(sim, "rms");
    CHECK(rms["points"].get<int>() == 5);
    CHECK(rms["error"].get<double>() == Approx(d / ref_peak).epsilon(0.02));
    // the default stays the mean relative error
    double mean = 0;
    for (double t : {0.02, 0.05, 0.08, 0.10, 0.13}) mean += d / (parabola(t) + d) / 5;
    CHECK(metric_of(sim, "mean")["error"].get<double>() == Approx(mean).epsilon(0.02));
}
