// Parallel bonds (issue: bonded structures): a single bond against its
// analytical force and strength, the cantilever against beam theory, and a
// brittle plate hit by a fast ball.
#include "simulation.hpp"

#include <cases/bonded_cases.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace plab;
using Catch::Matchers::Contains;

namespace {

// Two bonded discs (r = 1 mm, touching); ball 1 is driven at `velocity`.
std::unique_ptr<Simulation> bonded_pair(const json& velocity, double pb_ten, double pb_coh) {
    json scene = {{"dimension", 2},
                  {"plugins", {"linear_pbond"}},
                  {"bodies", {{{"type", "ball"}, {"position", {0, 0}}, {"radius", 0.001}, {"density", 2500}, {"fix", {"all"}}},
                              {{"type", "ball"}, {"position", {0.002, 0}}, {"radius", 0.001}, {"density", 2500},
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

} // namespace

TEST_CASE("a bond pulled apart carries A kn_bar times its elongation, beyond the neighbour skin, and breaks in "
          "tension at sigma_c", "[bonds]") {
    const double v = 0.01, area = 2 * 0.001, kn_bar = 1e9, sigma_c = 1e6;
    auto sim = bonded_pair({v, 0.0}, sigma_c, 1e300);
    World& w = sim->world();
    const double skin = 0.25 * 0.001;
    bool checked_beyond_skin = false;
    while (w.bond_breaks.empty() && w.step_count < 20000) {
        w.step();
        if (!w.bond_breaks.empty()) break;
        const double elongation = w.bodies.position[1].x() - 0.002;
        // the force on ball 1 pulls it back: -A kn_bar elongation (the linear part is open)
        CHECK(w.bodies.force[1].x() == Approx(-area * kn_bar * elongation).epsilon(1e-9));
        checked_beyond_skin = checked_beyond_skin || elongation > 2 * skin;
    }
    CHECK(checked_beyond_skin);  // the bond survived neighbour rebuilds
    REQUIRE(w.bond_breaks.size() == 1);
    const BondBreak& b = w.bond_breaks[0];
    CHECK(b.mode == PLAB_BREAK_TENSION);
    // sigma = kn_bar * elongation reaches sigma_c at elongation sigma_c/kn_bar
    CHECK(b.time == Approx(sigma_c / (kn_bar * v)).margin(1.5 * w.fixed_dt));
    CHECK(b.point.x() == Approx(0.5 * w.bodies.position[1].x()).epsilon(1e-3));
    sim->cycle(10);
    CHECK(w.bodies.force[1].norm() == 0.0);  // a broken bond never carries load again
    CHECK(w.energies.bond_break == Approx(0.5 * sigma_c * sigma_c * area / kn_bar).epsilon(0.02));
}

TEST_CASE("a bond sheared sideways breaks in shear when |Fs|/A reaches tau_c", "[bonds]") {
    const double v = 0.01, ks_bar = 1e9, tau_c = 2e5;
    auto sim = bonded_pair({0.0, v}, 1e300, tau_c);
    World& w = sim->world();
    while (w.bond_breaks.empty() && w.step_count < 20000) w.step();
    REQUIRE(w.bond_breaks.size() == 1);
    CHECK(w.bond_breaks[0].mode == PLAB_BREAK_SHEAR);
    CHECK(w.bond_breaks[0].time == Approx(tau_c / (ks_bar * v)).epsilon(0.01));
}

TEST_CASE("the hexagonal calibration refuses nu >= 1/3 and says why", "[bonds][scene]") {
    json scene = {{"dimension", 2},
                  {"plugins", {"linear_pbond"}},
                  {"bodies", {{{"type", "ball"}, {"group", "g"}, {"position", {0, 0}}, {"radius", 0.001}, {"density", 2500}}}},
                  {"contact_models", {{{"groups", {"g", "g"}}, {"model", "linear_pbond"},
                                       {"calibrate", {{"method", "hexagonal_2d"}, {"E", 1e9}, {"nu", 0.4},
                                                      {"sigma_ult", 1e6}, {"radius", 0.001}}}}}}};
    CHECK_THROWS_WITH(Simulation(scene), Contains("scene.contact_models[0].calibrate.nu") && Contains("value 0.4") &&
                                            Contains("[0, 1/3)") && Contains("eq. 37") && Contains("negative"));
    scene["contact_models"][0]["calibrate"]["nu"] = 0.3333;
    CHECK_NOTHROW(Simulation(scene));  // approaching 1/3 is allowed
}

TEST_CASE("the calibrated cantilever deflects linearly in the load while deflections are small", "[bonds][cantilever]") {
    // (at 5000 N the 3-row beam bends 7 % of its length: geometric stiffening
    // of order (deflection/L)^2 then shows, 0.4 % here)
    using plab::cases::static_cantilever;
    const auto small = static_cantilever(0.001, 50, 1e-6), large = static_cantilever(0.001, 500, 1e-6);
    CHECK(large.deflection / small.deflection == Approx(10.0).epsilon(0.001));
}

TEST_CASE("a coarse cantilever (R = 1 mm, 3 rows) deflects within 6 % of Euler-Bernoulli and first breaks in "
          "tension at the clamp, within 5 % of sigma_ult h^2/(6L)", "[bonds][cantilever]") {
    // 3 rows are a coarse beam; the tolerance is the one stated in
    // docs/speed-accuracy.md for this resolution (the 7-row beam meets 2 %).
    const auto c = plab::cases::static_cantilever(0.001, 5000, 1e-5);
    CHECK(c.deflection == Approx(c.analytical).epsilon(0.06));
    CHECK(c.deflection == Approx(c.analytical_equivalent).epsilon(0.06));
    CHECK(c.first_break_load == Approx(c.strength_load).epsilon(0.05));
    CHECK(c.break_in_tension);
    CHECK(c.break_x < 4 * 0.001 + 2.2 * 0.001);  // within two ball diameters of the clamp
    CHECK(c.break_y < 0.0025);                    // tension side: the bottom fibre under an upward tip load
}

TEST_CASE("a brittle plate hit at 20 m/s breaks locally without NaN and keeps its energy balance within 5 %",
          "[bonds][robustness]") {
    const auto r = plab::cases::plate_impact(20.0, 0.002);
    CHECK(r.finite);
    CHECK(r.balance_error < 0.05);
    CHECK(r.broken > 0);
    CHECK(double(r.broken) < 0.25 * double(r.bonds));
    CHECK(r.max_speed < 2 * 20.0);  // no fragment faster than an elastic rebound allows
}
