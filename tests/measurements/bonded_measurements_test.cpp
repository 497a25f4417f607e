// The named measurements of bonded structures (scripting/measurements/
// bonded_measurements.cpp), each on a tiny bonded lattice or pair whose
// answer is known by hand.
#include "../support/bonded_pair.hpp"
#include "measurements/measurement.hpp"
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace plab;

namespace {

const double R = 0.001;

// A measurement made from `with` on the world as it is now.
Measurement make(const std::string& name, const json& with, const World& w) {
    return measurements().at(name).make(Node(with, "with"), w);
}

// Three hexagonal rows of R = 1 mm discs, 20 mm long (10 balls in rows 0
// and 2 at x = 1, 3, ..., 19 mm; 9 in row 1 at x = 2, ..., 18 mm), bonded by
// explicit bond stiffnesses; every ball fixed, so only prescribed motion moves them.
json strip(double pb_kn, double pb_ks) {
    const double h = 2 * R + 2 * std::sqrt(3.0) * R;
    return {{"dimension", 2},
            {"plugins", {"linear_pbond"}},
            {"bodies", {{{"type", "lattice"}, {"group", "strip"}, {"packing", "hexagonal"},
                         {"box", {{"min", {0, 0}}, {"max", {0.02, h + 0.01 * R}}}}, {"radius", R}, {"density", 2800},
                         {"fix", {"all"}}}}},
            {"contact_models", {{{"groups", {"strip", "strip"}}, {"model", "linear_pbond"},
                                 {"properties", {{"kn", 1e6}, {"ks", 1e6}, {"pb_kn", pb_kn}, {"pb_ks", pb_ks}, {"pb_mcf", 0.0}}}}}},
            {"timestep", {{"fixed", 1e-7}}}};
}

using testing_support::bonded_pair;

} // namespace

TEST_CASE("clamp_line is where the clamped balls' material ends, averaged over the rows", "[measurements][bonds]") {
    Simulation sim(strip(1e9, 1e9));
    World& w = sim.world();
    for (const double depth : {2.2, 3.2}) {
        for (std::size_t i = 0; i < w.bodies.size(); ++i)  // only the clamp is fully fixed
            w.bodies.fixity[i] = w.bodies.position[i].x() < depth * R ? dof_all : std::uint8_t(dof_y);
        const double clamp = make("clamp_line", {{"group", "strip"}}, w)(w);
        // 2.2 R: rows 0 and 2 end at 2R (their ball at R), row 1 at 3R (its ball at 2R);
        // 3.2 R: rows 0 and 2 end at 4R (balls at R and 3R), row 1 still at 3R
        CHECK(clamp == Approx(depth == 2.2 ? (2 + 3 + 2) * R / 3 : (4 + 3 + 4) * R / 3).epsilon(1e-12));
    }
}

TEST_CASE("fibre_stress_error of a uniformly stretched strip is what its even stress adds to beam theory's",
          "[measurements][bonds]") {
    // A stretch eps along x (eps_yy = 0) in one step: an outer-row ball away
    // from the ends holds its two row bonds (elongation 2R eps) and two 60
    // degree bonds (elongation R eps / 2, shear 3/4 R eps along x), all open
    // (no linear contact force), with force = k_bar A displacement, A = 2R.
    // The ball stress sum r_c f_x / (pi R^2) is then
    //   s = A eps (17 kn_bar + 3 ks_bar) / (4 pi),
    // the same on the top and bottom rows, while -M y / I is odd in y: the
    // cross term cancels, and the error is sqrt(1 + N (a s)^2 / sum t^2).
    const double kn_bar = 1e12, ks_bar = 5e11, eps = 1e-6, dt = 1e-7, P = 2, a = M_PI / (2 * std::sqrt(3.0));
    Simulation sim(strip(kn_bar, ks_bar));
    sim.set_quiet(true);
    World& w = sim.world();
    REQUIRE(w.bond(0, 0, 1e-9 * R) > 0);
    const double height = 3 * std::sqrt(3.0) * R, inertia = height * height * height / 12, y_mid = std::sqrt(3.0) * R + R;
    const json with = {{"group", "strip"}, {"load", P}, {"load_id", 9}, {"height", height}, {"x_from", 3 * R},
                       {"x_to", 17 * R}, {"area_ratio", a}};
    const Measurement error = make("fibre_stress_error", with, w);
    std::vector<Vec> start = w.bodies.position;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) w.bodies.velocity[i] = Vec(eps * start[i].x() / dt, 0, 0);
    w.mark_dirty();
    w.prepare();
    w.step();
    const double x_load = w.bodies.position[9].x();  // the last ball of row 0
    double sum_t2 = 0;
    int fibres = 0;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        const Vec& p = start[i];
        const bool outer = std::fabs(p.y() - R) < 1e-9 || std::fabs(p.y() - (R + 2 * std::sqrt(3.0) * R)) < 1e-9;
        if (!outer || p.x() < 3 * R - 1e-9 || p.x() > 17 * R + 1e-9) continue;
        sum_t2 += std::pow(P * (x_load - p.x()) * (p.y() - y_mid) / inertia, 2);
        ++fibres;
    }
    REQUIRE(fibres == 16);  // 8 balls of each outer row, x = 3 ... 17 mm
    const double s = 2 * R * eps * (17 * kn_bar + 3 * ks_bar) / (4 * M_PI);
    CHECK(error(w) == Approx(std::sqrt(1 + fibres * a * a * s * s / sum_t2)).epsilon(1e-3));
}

TEST_CASE("linear_first_break gives the load at which a bond reaches its strength, by linearity", "[measurements][bonds]") {
    const double v = 0.01, kn_bar = 1e9, sigma_c = 1e6, tau_c = 2e5, P = 3;
    SECTION("pulled apart: tension, at the contact point") {
        auto sim = bonded_pair({v, 0.0}, sigma_c, tau_c);
        World& w = sim->world();
        const Measurement load = make("linear_first_break", {{"load", P}}, w);
        CHECK(std::isnan(load(w)));  // nothing is loaded yet
        for (int k = 0; k < 20; ++k) w.step();
        // sigma = kn_bar * elongation (bonded_test.cpp: the force is A kn_bar elongation)
        const double elongation = w.bodies.position[1].x() - 2 * R;
        CHECK(load(w) == Approx(P * sigma_c / (kn_bar * elongation)).epsilon(1e-9));
        CHECK(make("linear_first_break", {{"load", P}, {"criterion", "tension_at_centre"}}, w)(w) == Approx(load(w)));
        CHECK(make("linear_first_break", {{"load", P}, {"criterion", "tension"}, {"tensile_strength", 2 * sigma_c}}, w)(w) ==
              Approx(2 * load(w)));
        CHECK(std::isnan(make("linear_first_break", {{"load", P}, {"criterion", "shear"}}, w)(w)));  // no shear
        CHECK(make("linear_first_break", {{"load", P}, {"give", "in_tension"}}, w)(w) == 1);
        CHECK(make("linear_first_break", {{"load", P}, {"give", "x"}}, w)(w) == Approx(0.5 * w.bodies.position[1].x()).epsilon(1e-3));
        CHECK(make("linear_first_break", {{"load", P}, {"give", "y"}}, w)(w) == Approx(0.0).margin(1e-12));
    }
    SECTION("sheared sideways: shear, when |Fs|/A reaches tau_c") {
        auto sim = bonded_pair({0.0, v}, 1e300, tau_c);
        World& w = sim->world();
        for (int k = 0; k < 20; ++k) w.step();
        const double ks_bar = 1e9, shift = w.bodies.position[1].y();  // tau = ks_bar * shift (bonded_test.cpp, 1 %)
        CHECK(make("linear_first_break", {{"load", P}, {"criterion", "shear"}}, w)(w) == Approx(P * tau_c / (ks_bar * shift)).epsilon(0.01));
        CHECK(make("linear_first_break", {{"load", P}}, w)(w) == Approx(P * tau_c / (ks_bar * shift)).epsilon(0.01));
        CHECK(make("linear_first_break", {{"load", P}, {"give", "in_tension"}}, w)(w) == 0);
    }
    SECTION("a 3D scene is refused, naming the path") {
        json scene = {{"dimension", 3}, {"plugins", {"linear_pbond"}},
                      {"bodies", {{{"type", "ball"}, {"position", {0, 0, 0}}, {"radius", R}, {"density", 2500}}}}};
        Simulation sim(scene);
        CHECK_THROWS_WITH(make("linear_first_break", {{"load", P}}, sim.world()), Catch::Matchers::Contains("with") &&
                                                                                    Catch::Matchers::Contains("3D"));
    }
}

TEST_CASE("first_bond_break says where, when and how the first bond broke, NaN before any", "[measurements][bonds]") {
    const double v = 0.01, kn_bar = 1e9, sigma_c = 1e6;
    auto sim = bonded_pair({v, 0.0}, sigma_c, 1e300);
    World& w = sim->world();
    const Measurement x = make("first_bond_break", {{"give", "x"}}, w), y = make("first_bond_break", {{"give", "y"}}, w);
    const Measurement t = make("first_bond_break", {{"give", "time"}}, w);
    const Measurement tension = make("first_bond_break", {{"give", "in_tension"}}, w);
    CHECK(std::isnan(x(w)));
    while (w.bond_breaks.empty() && w.step_count < 20000) w.step();
    REQUIRE(w.bond_breaks.size() == 1);
    CHECK(t(w) == Approx(sigma_c / (kn_bar * v)).margin(1.5 * w.fixed_dt));  // sigma = kn_bar v t reaches sigma_c
    CHECK(x(w) == Approx(0.5 * w.bodies.position[1].x()).epsilon(1e-3));
    CHECK(y(w) == Approx(0.0).margin(1e-12));
    CHECK(tension(w) == 1);
    auto sheared = bonded_pair({0.0, v}, 1e300, 2e5);
    World& s = sheared->world();
    while (s.bond_breaks.empty() && s.step_count < 20000) s.step();
    REQUIRE(s.bond_breaks.size() == 1);
    CHECK(make("first_bond_break", {{"give", "in_tension"}}, s)(s) == 0);
}
