// Lattices built as the solid they stand for ("solid": its size is that of
// the balls' cells) and the calibration's density over those cells
// (issue 37); the frequency metric on a known sine.
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <map>

using namespace plab;
using Catch::Matchers::Contains;

namespace {

const double kSqrt3 = std::sqrt(3.0);

json lattice_scene(int dim, const std::string& packing, const json& min, const json& size, double r) {
    return {{"dimension", dim},
            {"bodies", {{{"type", "lattice"}, {"group", "s"}, {"packing", packing}, {"solid", {{"min", min}, {"size", size}}},
                         {"radius", r}, {"density", 2800}}}}};
}

// A calibrated 2D lattice solid L x h of radius r; `calibrate` keys added.
json calibrated_scene(double L, double h, double r, const json& calibrate = json::object()) {
    json scene = lattice_scene(2, "hexagonal", {0.01, -0.02}, {L, h}, r);
    json cal = {{"method", "hexagonal_2d"}, {"E", 70e9}, {"nu", 0.3}, {"sigma_ult", 1e8}, {"radius", r}};
    cal.update(calibrate);
    scene["plugins"] = {"linear_pbond"};
    scene["contact_models"] = {{{"groups", {"s", "s"}}, {"model", "linear_pbond"}, {"calibrate", cal}}};
    return scene;
}

double total_mass(const World& w) {
    double m = 0;
    for (double x : w.bodies.mass) m += x;
    return m;
}

} // namespace

TEST_CASE("lattice generator: a hexagonal solid's cells make up the size named, every row the same count",
          "[generator][scene]") {
    const double r = 0.001, L = 0.2, h = 4 * kSqrt3 * r, x0 = 0.01, y0 = -0.02;
    Simulation sim(lattice_scene(2, "hexagonal", {x0, y0}, {L, h}, r));
    const Bodies& b = sim.world().bodies;
    REQUIRE(b.size() == 400);
    // rows by height: each a row of cells 2r wide and sqrt(3) r high
    std::map<long, std::vector<double>> rows;
    for (std::size_t i = 0; i < b.size(); ++i) rows[std::lround((b.position[i].y() - y0) / (kSqrt3 * r) - 0.5)].push_back(b.position[i].x());
    REQUIRE(rows.size() == 4);
    double left = 0, right = 0;
    for (const auto& [j, xs] : rows) {
        CHECK(xs.size() == 100);
        left += *std::min_element(xs.begin(), xs.end()) - r;
        right += *std::max_element(xs.begin(), xs.end()) + r;
    }
    // the cells' mean edges are the solid's: x0 and x0 + L; in y the outer
    // rows' cells end half a row pitch beyond their centres
    CHECK(left / 4 == Approx(x0).margin(1e-15));
    CHECK(right / 4 == Approx(x0 + L).epsilon(1e-14));
    CHECK(rows.begin()->first == 0);
    double y_lo = kInf, y_hi = -kInf;
    for (const Vec& p : b.position) { y_lo = std::min(y_lo, p.y()); y_hi = std::max(y_hi, p.y()); }
    CHECK(y_lo - kSqrt3 * r / 2 == Approx(y0).epsilon(1e-14));
    CHECK(y_hi + kSqrt3 * r / 2 == Approx(y0 + h).epsilon(1e-14));
    // and their area is the solid's
    CHECK(double(b.size()) * 2 * kSqrt3 * r * r == Approx(L * h).epsilon(1e-13));
}

TEST_CASE("lattice generator: 3D cubic and hcp solids are whole numbers of their cells, centred in the size named",
          "[generator][scene]") {
    const double r = 0.001, a = 2 * r;
    Simulation cubic(lattice_scene(3, "cubic", {0, 0, 0}, {6 * a, 4 * a, 2 * a}, r));
    CHECK(cubic.world().bodies.size() == 48);
    // hcp cells a by a sqrt(3)/2 by a sqrt(2/3): 4 sqrt(2) r^3 each
    const double dy = a * kSqrt3 / 2, dz = a * std::sqrt(2.0 / 3.0);
    Simulation hcp(lattice_scene(3, "hcp", {0.1, 0.2, 0.3}, {4 * a, 6 * dy, 4 * dz}, r));
    const Bodies& b = hcp.world().bodies;
    REQUIRE(b.size() == 4 * 6 * 4);
    Vec mean = Vec::Zero();
    for (const Vec& p : b.position) mean += p / double(b.size());
    CHECK(mean.x() == Approx(0.1 + 2 * a).epsilon(1e-13));
    CHECK(mean.y() == Approx(0.2 + 3 * dy).epsilon(1e-13));
    CHECK(mean.z() == Approx(0.3 + 2 * dz).epsilon(1e-13));
    CHECK(double(b.size()) * 4 * std::sqrt(2.0) * r * r * r == Approx(4 * a * 6 * dy * 4 * dz).epsilon(1e-13));
}

TEST_CASE("lattice generator: a size that is not a whole number of rows within the tolerance is refused by its path",
          "[generator][scene]") {
    const double r = 0.001;
    // 3.5 rows of sqrt(3) r
    const json scene = lattice_scene(2, "hexagonal", {0, 0}, {0.02, 3.5 * kSqrt3 * r}, r);
    CHECK_THROWS_WITH(Simulation(scene), Contains("scene.bodies[0].solid.size[1]") && Contains("value 0.00606") &&
                                             Contains("3.5 rows") && Contains("valid range") && Contains("for 4 rows") &&
                                             Contains("for 3 rows"));
    // 10.03 columns: within the default 1 %, 10 columns made
    Simulation near(lattice_scene(2, "hexagonal", {0, 0}, {10.03 * 2 * r, 2 * kSqrt3 * r}, r));
    CHECK(near.world().bodies.size() == 20);
    json tight = lattice_scene(2, "hexagonal", {0, 0}, {10.03 * 2 * r, 2 * kSqrt3 * r}, r);
    tight["bodies"][0]["solid"]["size_tolerance"] = 0.001;
    CHECK_THROWS_WITH(Simulation(tight), Contains("scene.bodies[0].solid.size[0]") && Contains("10.03 columns"));
    json negative = lattice_scene(2, "hexagonal", {0, 0}, {-0.01, 0.01}, r);
    CHECK_THROWS_WITH(Simulation(negative), Contains("scene.bodies[0].solid.size[0]") && Contains("(0, inf)"));
    json both = lattice_scene(2, "hexagonal", {0, 0}, {0.02, 0.02}, r);
    both["bodies"][0]["box"] = {{"min", {0, 0}}, {"max", {1, 1}}};
    CHECK_THROWS_WITH(Simulation(both), Contains("scene.bodies[0]") && Contains("exactly one of \"box\""));
}

TEST_CASE("calibration: the lattice's mass is rho x its equivalent section x the thickness, to round-off",
          "[calibration][generator][scene]") {
    const double r = 0.0005, L = 0.1, h = 6 * kSqrt3 * r, rho = 2800;
    Simulation sim(calibrated_scene(L, h, r));
    CHECK(total_mass(sim.world()) == Approx(rho * L * h).epsilon(1e-13));
    // the factor is 2 sqrt(3)/pi: discs fill pi/(2 sqrt(3)) of their cells
    CHECK(sim.world().bodies.mass[0] == Approx(rho * M_PI * r * r * 2 * kSqrt3 / M_PI).epsilon(1e-14));
    Simulation thin(calibrated_scene(L, h, r, {{"thickness", 0.01}}));
    CHECK(total_mass(thin.world()) == Approx(rho * L * h * 0.01).epsilon(1e-13));
    // the rotational inertia follows the mass (a disc's m r^2 / 2)
    CHECK(thin.world().bodies.inertia[0] == Approx(0.5 * thin.world().bodies.mass[0] * r * r).epsilon(1e-14));
    // opted out: the balls keep the density given
    Simulation kept(calibrated_scene(L, h, r, {{"density", "ball"}}));
    CHECK(total_mass(kept.world()) == Approx(rho * double(kept.world().bodies.size()) * M_PI * r * r).epsilon(1e-13));
    CHECK(sim.summary()["structures"][1]["density_factor"].get<double>() == Approx(2 * kSqrt3 / M_PI).epsilon(1e-15));
}

TEST_CASE("calibration: the density is refused for a lattice it does not describe, by path", "[calibration][scene]") {
    const double r = 0.001;
    json square = calibrated_scene(0.02, 0.02, r);
    square["bodies"][0]["packing"] = "square";
    CHECK_THROWS_WITH(Simulation(square), Contains("scene.contact_models[0].calibrate.method") && Contains("square lattice") &&
                                              Contains("calibrate.density"));
    json radius = calibrated_scene(0.02, 2 * kSqrt3 * r, r, {{"radius", 0.002}});
    CHECK_THROWS_WITH(Simulation(radius), Contains("scene.contact_models[0].calibrate.radius") && Contains("value 0.002") &&
                                              Contains("not the radius 0.001"));
    json loose = calibrated_scene(0.02, 2 * kSqrt3 * r, r);
    loose["bodies"].push_back({{"type", "ball"}, {"group", "s"}, {"position", {0.5, 0.5}}, {"radius", r}, {"density", 2800}});
    CHECK_THROWS_WITH(Simulation(loose), Contains("scene.contact_models[0].calibrate") && Contains("1 balls not made by a lattice"));
    json bad = calibrated_scene(0.02, 2 * kSqrt3 * r, r, {{"density", "cells"}});
    CHECK_THROWS_WITH(Simulation(bad), Contains("scene.contact_models[0].calibrate.density") && Contains("section"));
}

TEST_CASE("the frequency metric finds a sine's frequency from its rising crossings", "[metrics][scene]") {
    // 7.3 Hz sampled every ms over 1 s, offset from zero (the mean is the level)
    json scene = {{"dimension", 2},
                  {"bodies", {{{"type", "ball"}, {"position", {0, 0}}, {"radius", 0.01}, {"density", 1000}}}},
                  {"timestep", {{"fixed", 1e-3}}},
                  {"histories", {{"every", 1}, {"record", {{{"quantity", "time"}},
                                                           {{"name", "s"}, {"expression", "0.2 + sin(2 * pi * 7.3 * time + 0.4)"}}}}}},
                  {"metrics", {{{"name", "f"}, {"history", "s"}, {"reduce", "frequency"}, {"analytical", 7.3}},
                               {{"name", "T"}, {"history", "s"}, {"reduce", "period"}, {"analytical", 1 / 7.3}}}},
                  {"commands", {{{"solve", {{"time", 1.0}}}}}}};
    Simulation sim(scene);
    sim.set_quiet(true);
    sim.run();
    const json m = sim.summary()["metrics"];
    CHECK(m[0]["value"].get<double>() == Approx(7.3).epsilon(1e-4));
    CHECK(m[1]["value"].get<double>() == Approx(1 / 7.3).epsilon(1e-4));
}
