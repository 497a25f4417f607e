// heap_angle (scripting/measurements/granular_measurements.cpp, the
// angle_of_repose case) on flanks of known slope: balls at rest, no gravity.
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

using namespace plab;
using Catch::Matchers::Contains;

namespace {

constexpr double kR = 0.001;

// one ball per 4 mm strip from x = 0 to 0.04 m, its top on y = slope x
// (centres at slope x - R), plus a ball far above (a hopper's) and one below
json flank(double slope, const json& with) {
    json bodies = json::array();
    for (int s = 0; s < 10; ++s) {
        const double x = 0.002 + 0.004 * s;
        bodies.push_back({{"type", "ball"}, {"group", "heap"}, {"position", {x, slope * x - kR}}, {"radius", kR}, {"density", 1000}});
    }
    bodies.push_back({{"type", "ball"}, {"group", "heap"}, {"position", {0.01, 0.5}}, {"radius", kR}, {"density", 1000}});
    bodies.push_back({{"type", "ball"}, {"group", "heap"}, {"position", {0.03, -0.5}}, {"radius", kR}, {"density", 1000}});
    json measure = {{"group", "heap"}, {"x_min", 0.0}, {"x_max", 0.04}, {"strip_width", 0.004}};
    measure.update(with);
    return {{"dimension", 2}, {"bodies", bodies}, {"timestep", {{"fixed", 1e-4}}},
            {"histories", {{"every", 1}, {"record", {{{"quantity", "time"}}, {{"name", "angle"}, {"quantity", "measure.heap_angle"}, {"with", measure}}}}}},
            {"commands", {{{"cycle", 1}}}}};
}

double angle_of(const json& scene) {
    Simulation sim(scene);
    sim.set_quiet(true);
    sim.run();
    return sim.history("angle").back();
}

} // namespace

TEST_CASE("heap_angle is the angle of the flank's surface line, the balls below y_min or above y_max left out", "[measurements]") {
    for (double degrees : {10.0, 30.0, 45.0}) {
        INFO(degrees << " degrees");
        const double slope = std::tan(degrees * M_PI / 180);
        CHECK(angle_of(flank(slope, {{"y_min", -0.1}, {"y_max", 0.1}})) == Approx(degrees).epsilon(1e-9));
        CHECK(angle_of(flank(-slope, {{"y_min", -0.1}, {"y_max", 0.1}})) == Approx(degrees).epsilon(1e-9));  // a left flank
    }
    // without the bounds the hopper's and the fallen ball are the tops of their strips: the line tilts
    CHECK(std::fabs(angle_of(flank(std::tan(M_PI / 6), json::object())) - 30.0) > 1.0);
}

TEST_CASE("heap_angle reads an empty strip as the bare base y_min, is NaN without one where < 3 strips hold balls, and names "
          "the path of a bad strip width", "[measurements][scene]") {
    // every strip of [0.1, 0.14] is empty: with y_min the bare, level base; without it no surface to fit
    CHECK(angle_of(flank(1.0, {{"x_min", 0.1}, {"x_max", 0.14}, {"y_min", -0.1}, {"y_max", 0.1}})) == Approx(0.0).margin(1e-9));
    CHECK(std::isnan(angle_of(flank(1.0, {{"x_min", 0.1}, {"x_max", 0.14}, {"y_max", 0.1}}))));
    json wide = flank(1.0, {{"strip_width", 0.02}});
    CHECK_THROWS_WITH(Simulation(wide), Contains("scene.histories.record[1].with.strip_width") && Contains("three strips"));
}

namespace {

// A square lattice of fixed balls (radius R, spacing s < 2R: every
// neighbour pair overlaps by d = 2R - s), linear springs kn: each contact
// pushes with kn d, one x contact and one y contact per cell of s^2, so
// the contact stress is -kn d / s in xx and yy (tension positive), zero
// in xy. The box [s/4, s/4 + m s]^2 holds m^2 of each kind of contact
// point (x contacts at ((i + 1/2) s, j s), y contacts at (i s, (j + 1/2) s)).
json compressed_lattice(const json& component) {
    const double s = 0.0019;
    const double lo = 0.25 * s, hi = 0.25 * s + 6 * s;
    json bodies = json::array();  // (a lattice generator refuses overlapping spacings)
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j)
            bodies.push_back({{"type", "ball"}, {"group", "grid"}, {"position", {i * s, j * s}}, {"radius", kR},
                              {"density", 2500}, {"fix", {"all"}}});
    return {{"dimension", 2},
            {"plugins", {"linear"}},
            {"bodies", bodies},
            {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"}, {"properties", {{"kn", 1e5}}}}}},
            {"timestep", {{"fixed", 1e-6}}},
            {"histories", {{"every", 1}, {"record", {{{"name", "s"}, {"quantity", "measure.contact_stress"},
                                                      {"with", {{"min", {lo, lo}}, {"max", {hi, hi}}, {"component", component}}}}}}}}};
}

} // namespace

TEST_CASE("contact_stress of a uniformly compressed square lattice is -kn d / s, without shear", "[measurements]") {
    const double s = 0.0019, d = 2 * kR - s, expected = -1e5 * d / s;
    for (const char* component : {"xx", "yy", "xy", "pressure"}) {
        INFO(component);
        Simulation sim(compressed_lattice(component));
        sim.set_quiet(true);
        sim.cycle(1);
        const double got = sim.history("s").back();
        if (std::string(component) == "xy") CHECK(std::fabs(got) <= 1e-9 * std::fabs(expected));
        else if (std::string(component) == "pressure") CHECK(got == Approx(-expected).epsilon(1e-12));
        else CHECK(got == Approx(expected).epsilon(1e-12));
    }
}
