// Clumps down an incline (issue 27's rigid_incline): the plane is y = 0 and
// gravity is tilted by θ = 20°. A sphere clump and a cylinder clump roll
// without slip at (5/7) g sinθ and (2/3) g sinθ: the inertia of the true
// shape, not of the pebbles, sets them. A box clump slides at g (sinθ − μ cosθ).
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace plab;

namespace {

constexpr double kTheta = 20 * 3.14159265358979323846 / 180, kG = 9.81;

json incline(const json& clump, double fric) {
    return {{"dimension", 3},
            {"plugins", {"linear"}},
            {"gravity", {kG * std::sin(kTheta), -kG * std::cos(kTheta), 0}},
            {"bodies", {clump}},
            {"walls", {{{"type", "plane"}, {"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}},
            {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"},
                                 {"properties", {{"kn", 1e6}, {"ks", 1e6}, {"fric", fric}, {"dp_nratio", 0.7}}}}}}};
}

// The clump's acceleration down the slope, from its velocity at 0.05 s and 0.25 s.
double acceleration(const json& scene) {
    Simulation sim(scene);
    sim.set_quiet(true);
    World& w = sim.world();
    double t1 = 0, v1 = 0;
    while (w.time < 0.25) {
        sim.cycle(1);
        if (t1 == 0 && w.time >= 0.05) { t1 = w.time; v1 = w.clumps.velocity[0].x(); }
    }
    return (w.clumps.velocity[0].x() - v1) / (w.time - t1);
}

json pebble(double x, double y, double z, double r) { return {{"position", {x, y, z}}, {"radius", r}}; }

} // namespace

TEST_CASE("a sphere clump and a cylinder clump roll at (5/7) and (2/3) g sin(theta), a box clump slides", "[clump][incline]") {
    const double R = 0.01;
    const json sphere = {{"type", "clump"}, {"shape", {{"type", "sphere"}, {"radius", R}}}, {"density", 2500},
                         {"pebbles", {pebble(0, 0, 0, R)}}, {"position", {0, R, 0}}};
    const double a_sphere = acceleration(incline(sphere, 0.5));
    INFO("sphere " << a_sphere << " against " << 5.0 / 7 * kG * std::sin(kTheta));
    CHECK(a_sphere == Approx(5.0 / 7 * kG * std::sin(kTheta)).epsilon(0.01));

    json pebbles = json::array();  // along the cylinder's axis (z)
    for (double z : {-0.015, -0.005, 0.005, 0.015}) pebbles.push_back(pebble(0, 0, z, R));
    const json cylinder = {{"type", "clump"}, {"shape", {{"type", "cylinder"}, {"radius", R}, {"height", 0.04}}},
                           {"density", 2500}, {"pebbles", pebbles}, {"position", {0, R, 0}}};
    const double a_cylinder = acceleration(incline(cylinder, 0.5));
    INFO("cylinder " << a_cylinder << " against " << 2.0 / 3 * kG * std::sin(kTheta));
    CHECK(a_cylinder == Approx(2.0 / 3 * kG * std::sin(kTheta)).epsilon(0.01));

    json corners = json::array();  // small pebbles at the corners of a 2 cm cube
    const double h = 0.008, r = 0.002;
    for (double x : {-h, h})
        for (double y : {-h, h})
            for (double z : {-h, h}) corners.push_back(pebble(x, y, z, r));
    const double mu = 0.2;
    const json box = {{"type", "clump"}, {"shape", {{"type", "box"}, {"size", {0.02, 0.02, 0.02}}}}, {"density", 2500},
                      {"pebbles", corners}, {"position", {0, h + r, 0}}};
    const double a_box = acceleration(incline(box, mu));
    INFO("box " << a_box << " against " << kG * (std::sin(kTheta) - mu * std::cos(kTheta)));
    CHECK(a_box == Approx(kG * (std::sin(kTheta) - mu * std::cos(kTheta))).epsilon(0.01));
}
