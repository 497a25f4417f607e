// Parallel bonds (issue: bonded structures): a single bond against its
// analytical force and strength, the cantilever against beam theory, and a
// brittle plate hit by a fast ball.
#include "../support/bonded_pair.hpp"
#include "simulation.hpp"

#include "../support/cantilever.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace plab;
using Catch::Matchers::Contains;

namespace {

using testing_support::bonded_pair;

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
                  {"bodies", {{{"type", "lattice"}, {"group", "g"}, {"solid", {{"min", {0, 0}}, {"size", {0.004, 2 * std::sqrt(3.0) * 0.001}}}},
                               {"radius", 0.001}, {"density", 2500}}}},
                  {"contact_models", {{{"groups", {"g", "g"}}, {"model", "linear_pbond"},
                                       {"calibrate", {{"method", "hexagonal_2d"}, {"E", 1e9}, {"nu", 0.4},
                                                      {"sigma_ult", 1e6}, {"radius", 0.001}}}}}}};
    CHECK_THROWS_WITH(Simulation(scene), Contains("scene.contact_models[0].calibrate.nu") && Contains("value 0.4") &&
                                            Contains("[0, 1/3)") && Contains("eq. 37") && Contains("negative"));
    scene["contact_models"][0]["calibrate"]["nu"] = 0.3333;
    CHECK_NOTHROW(Simulation(scene));  // approaching 1/3 is allowed
}

namespace {

// Largest sigma/sigma_c and tau/tau_c over the bonds of a hexagonal lattice
// (rows along x) after one step of the affine strain (exx, eyy, exy), the
// balls' spins held at zero, with the calibration keys `extra` added.
std::pair<double, double> strength_use_under_strain(const json& extra, double exx, double eyy, double exy) {
    const double r = 0.001, E = 70e9, nu = 0.3, sigma_ult = 310e6, dt = 1e-7;
    json calibrate = {{"method", "hexagonal_2d"}, {"E", E}, {"nu", nu}, {"sigma_ult", sigma_ult}, {"radius", r}};
    calibrate.update(extra);
    json scene = {{"dimension", 2},
                  {"plugins", {"linear_pbond"}},
                  {"bodies", {{{"type", "lattice"}, {"group", "strip"}, {"packing", "hexagonal"},
                               {"box", {{"min", {0, 0}}, {"max", {0.012, 0.008}}}}, {"radius", r}, {"density", 2800},
                               {"fix", {"all"}}}}},
                  {"contact_models", {{{"groups", {"strip", "strip"}}, {"model", "linear_pbond"},
                                       {"calibrate", calibrate}, {"properties", {{"pb_mcf", 0.0}}}}}},
                  {"timestep", {{"fixed", dt}}}};
    Simulation sim(scene);
    sim.set_quiet(true);
    World& w = sim.world();
    REQUIRE(w.bond(0, 0, 1e-9 * r) > 0);
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {  // fixed balls move at their prescribed velocity
        const Vec& p = w.bodies.position[i];
        w.bodies.velocity[i] = Vec((exx * p.x() + exy * p.y()) / dt, (exy * p.x() + eyy * p.y()) / dt, 0);
    }
    w.mark_dirty();
    w.prepare();
    w.step();
    CHECK(w.bond_breaks.empty());
    const ModelView inst = w.model(0);
    const int fn = inst.history_slot("bond_normal_force"), fsx = inst.history_slot("bond_shear_force_x"),
              fsy = inst.history_slot("bond_shear_force_y");
    const double ten = inst.property("pb_ten"), coh = inst.property("pb_coh");
    double sigma = 0, tau = 0;
    const ContactTable s = inst.balls();
    for (std::size_t k = 0; k < s.size(); ++k) {
        const double* h = s.history(k);
        sigma = std::max(sigma, h[fn] / (2 * r) / ten);
        tau = std::max(tau, std::hypot(h[fsx], h[fsy]) / (2 * r) / coh);
    }
    return {sigma, tau};
}

// ... under uniaxial stress sigma_ult / 2 along x (or y), so that no bond
// breaks: eps_axial = 1.01 sigma_ult / (2 E) (in tension only the bonds act,
// 1/1.01 of the calibrated stiffness, eq. 42), eps_lateral = -nu eps_axial;
// scaled to sigma_ult.
std::pair<double, double> strength_use_under_uniaxial_stress(const std::string& tension, bool along_x) {
    const double E = 70e9, nu = 0.3, sigma_ult = 310e6;
    const double eps = 1.01 * sigma_ult / (2 * E);
    const auto [sigma, tau] = strength_use_under_strain({{"tension", tension}}, along_x ? eps : -nu * eps,
                                                        along_x ? -nu * eps : eps, 0.0);
    return {2 * sigma, 2 * tau};
}

} // namespace

TEST_CASE("bond strengths calibrated across the bonds (thesis eqs. 43-46) are reached at sigma_ult across the "
          "rows and at (3 - nu)/4 sigma_ult along them, and the along_bonds rule swaps that", "[bonds][calibration]") {
    const double nu = 0.3, weak = (3 - nu) / 4;
    const auto across_y = strength_use_under_uniaxial_stress("across_bonds", false);
    CHECK(across_y.first == Approx(1.0).epsilon(0.01));   // the +-60 degree bonds, 30 degrees from y
    CHECK(across_y.second == Approx(1.0).epsilon(0.01));  // eq. 44: their shear at the same load
    const auto across_x = strength_use_under_uniaxial_stress("across_bonds", true);
    CHECK(across_x.first == Approx(1.0 / weak).epsilon(0.01));  // the row bonds are over-stressed
    const auto along_x = strength_use_under_uniaxial_stress("along_bonds", true);
    CHECK(along_x.first == Approx(1.0).epsilon(0.01));
    CHECK(along_x.second == Approx(1.0).epsilon(0.01));
    const auto along_y = strength_use_under_uniaxial_stress("along_bonds", false);
    CHECK(along_y.first == Approx(weak).epsilon(0.01));
}

TEST_CASE("the calibrated bond shear strength is reached when the lattice is sheared along its rows to the "
          "material's shear strength tau_ult (default sqrt(3)/4 sigma_ult, thesis eq. 44)", "[bonds][calibration]") {
    const double E = 70e9, nu = 0.3, sigma_ult = 310e6;
    // pure shear tau / 2 (no bond breaks): eps_xy = 1.01 (1 + nu) tau / (2 E)
    // (the bonds carry 1/1.01 of the calibrated shear stiffness, eq. 42)
    for (const double tau_ult : {std::sqrt(3.0) / 4 * sigma_ult, 207e6}) {
        const json extra = tau_ult == 207e6 ? json{{"tau_ult", tau_ult}} : json::object();
        const auto use = strength_use_under_strain(extra, 0, 0, 1.01 * (1 + nu) * tau_ult / (2 * E));
        CHECK(2 * use.second == Approx(1.0).epsilon(0.01));
    }
    // a material stronger in shear than eq. 44 assumes: the 60 degree bonds under
    // uniaxial sigma_ult use only (sqrt3/4 sigma_ult)/tau_ult of the strength
    const double eps = 1.01 * sigma_ult / (2 * E);
    const auto uniaxial = strength_use_under_strain({{"tension", "along_bonds"}, {"tau_ult", 207e6}}, eps, -nu * eps, 0);
    CHECK(2 * uniaxial.second == Approx(std::sqrt(3.0) / 4 * sigma_ult / 207e6).epsilon(0.01));
    CHECK(2 * uniaxial.first == Approx(1.0).epsilon(0.01));
}

TEST_CASE("the calibrated cantilever deflects linearly in the load while deflections are small", "[bonds][cantilever]") {
    // (at 5000 N the 3-row beam bends 7 % of its length: geometric stiffening
    // of order (deflection/L)^2 then shows, 0.4 % here)
    using namespace testing_support;
    const auto small = solved_cantilever({{"variables.R", 0.001}, {"variables.P", 50}, {"variables.ratio", 1e-6}});
    const auto large = solved_cantilever({{"variables.R", 0.001}, {"variables.P", 500}, {"variables.ratio", 1e-6}});
    CHECK(at_end(*large, "deflection") / at_end(*small, "deflection") == Approx(10.0).epsilon(0.001));
}

TEST_CASE("a coarse cantilever (R = 1 mm, 3 rows) deflects within 6 % of Euler-Bernoulli and first breaks in "
          "tension on the bottom row at the clamp", "[bonds][cantilever]") {
    // 3 rows are a coarse beam; the tolerance is the one stated in
    // docs/speed-accuracy.md for this resolution (the 7-row beam meets 2 %).
    // The quick run of `plab validate cantilever`:
    using namespace testing_support;
    const auto c = solved_cantilever(case_run_sets("cantilever", "R 1 mm, 5000 N, ratio 1e-5"));
    const double nu = 0.33, R = 0.001;
    CHECK(at_end(*c, "deflection") == Approx(metric(*c, "deflection_nominal", "reference")).epsilon(0.06));  // P L^3/(3 E I)
    CHECK(at_end(*c, "deflection") == Approx(at_end(*c, "deflection_eq")).epsilon(0.06));  // the equivalent beam
    CHECK(at_end(*c, "break_in_tension") == 1);
    CHECK(at_end(*c, "break_x") < 4 * R + 2.2 * R);  // within two ball diameters of the clamp
    CHECK(at_end(*c, "break_y") < 0.0015);           // the bottom row: tension under an upward tip load
    // the thesis strengths hold for bonds at 30 degrees to the tension; the
    // bottom row's bonds lie along it and break at (3 - nu)/4 of the load
    // that brings the beam stress at their centre line to sigma_ult
    // (the clamp adds a local concentration at this resolution: 11 %)
    CHECK(at_end(*c, "break_load") == Approx(at_end(*c, "row_strength_load") * (3 - nu) / 4).epsilon(0.15));
    // strength for tension along the bonds, beta = 1 (eq. 49: the stress at the
    // bond's outer edge, for the outer row the beam's surface) and the
    // aluminium's tau_ult (207 MPa): the first break meets sigma_ult b h^2/(6L)
    // within 5 % (the issue's tolerance; -3.7 %), in tension. The quick static
    // run of `plab validate cantilever_failure`:
    const auto along = solved_cantilever(case_run_sets("cantilever_failure", "static, R 1 mm, ratio 1e-5"));
    CHECK(at_end(*along, "centre_break_load") / at_end(*c, "break_load") == Approx(4 / (3 - nu)).epsilon(1e-6));
    CHECK(at_end(*along, "thesis_rule_load") == Approx(at_end(*c, "break_load")).epsilon(1e-6));
    CHECK(at_end(*along, "break_load") == Approx(metric(*along, "first_break_nominal", "reference")).epsilon(0.05));
    CHECK(at_end(*along, "break_in_tension") == 1);
    CHECK(at_end(*along, "shear_break_load") > at_end(*along, "tension_break_load"));
    CHECK(at_end(*along, "break_x") < 4 * R + 2.2 * R);
    CHECK(at_end(*along, "break_y") < 0.0015);
}

TEST_CASE("a brittle plate hit at 20 m/s breaks locally without NaN and keeps its energy balance within 5 %",
          "[bonds][robustness]") {
    using namespace testing_support;
    Simulation sim(read_scene_file(std::string(PLAB_SOURCE_DIR) + "/tests/physics/scenes/plate_impact.json"));
    sim.set_quiet(true);
    bool finite = true;
    try {
        sim.run();
    } catch (const RunError&) {
        finite = false;
    }
    const std::vector<double> balance = sim.history("balance"), kinetic = sim.history("kinetic");
    const double input = kinetic.front(), broken = at_end(sim, "broken"), bonds = sim.history("intact").front();
    CHECK(finite);
    CHECK(std::fabs(balance.back() - balance.front()) / input < 0.05);
    CHECK(broken > 0);
    CHECK(broken < 0.25 * bonds);
    CHECK(at_end(sim, "max_speed") < 2 * 20.0);  // no fragment faster than an elastic rebound allows
}
