// The tutorial model against Hertz's analytical impact (Johnson, Contact
// Mechanics, §11.4): contact time t_c = 2.868 (m*^2 / (R* E*^2 v))^(1/5) and
// maximum overlap d_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5).
#define CATCH_CONFIG_MAIN
#include "hertz.hpp"

#include <plab/testing.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

using plab::testing::Probe;
using tutorial::Hertz;

namespace {
const double E = 70e9, nu = 0.25, E_eff = E / (2 * (1 - nu * nu));

double hertz_contact_time(double m, double R, double v) { return 2.868 * std::pow(m * m / (R * E_eff * E_eff * v), 0.2); }
double hertz_max_overlap(double m, double R, double v) { return std::pow(15 * m * v * v / (16 * E_eff * std::sqrt(R)), 0.4); }
} // namespace

TEST_CASE("an elastic sphere hitting a wall stays in contact for Hertz's time at three speeds", "[hertz]") {
    Probe p(plab::contact_model_desc<Hertz>(), {{"E", E}, {"nu", nu}, {"e", 1.0}});
    p.wall = true;
    for (double v : {0.1, 1.0, 10.0}) {
        const double tc = hertz_contact_time(p.eff_mass(), p.eff_radius(), v);
        const plab::testing::Impact im = p.impact(v, tc / 1000);
        const double err_t = im.duration / tc - 1, err_d = im.max_overlap / hertz_max_overlap(p.eff_mass(), p.eff_radius(), v) - 1;
        std::printf("hertz v = %5.1f m/s: contact time %.6e s (analytical %.6e, %+.3f %%), max overlap %+.3f %%, e = %.5f\n",
                    v, im.duration, tc, 100 * err_t, 100 * err_d, im.restitution);
        CHECK(std::fabs(err_t) < 0.02);
        CHECK(std::fabs(err_d) < 0.02);
        CHECK(im.restitution == Approx(1.0).margin(1e-3));
    }
}

TEST_CASE("two equal spheres meet with half the mass and half the radius of one", "[hertz]") {
    Probe p(plab::contact_model_desc<Hertz>(), {{"E", E}, {"nu", nu}});
    const double m = p.mass1 / 2, R = p.radius1 / 2, v = 2.0;
    const plab::testing::Impact im = p.impact(v, hertz_contact_time(m, R, v) / 1000);
    CHECK(im.duration == Approx(hertz_contact_time(m, R, v)).epsilon(0.02));
    CHECK(im.max_overlap == Approx(hertz_max_overlap(m, R, v)).epsilon(0.02));
}

TEST_CASE("the contact time of Hertz falls as v^(-1/5)", "[hertz]") {
    Probe p(plab::contact_model_desc<Hertz>(), {{"E", E}, {"nu", nu}});
    p.wall = true;
    const double t1 = p.impact(0.5, 1e-8).duration, t2 = p.impact(5.0, 1e-8).duration;
    CHECK(t1 / t2 == Approx(std::pow(10.0, 0.2)).epsilon(0.01));
}

TEST_CASE("Tsuji damping gives a restitution that does not depend on the impact speed", "[hertz]") {
    Probe p(plab::contact_model_desc<Hertz>(), {{"E", E}, {"nu", nu}, {"e", 0.5}});
    p.wall = true;
    const double e_slow = p.impact(0.1, 1e-8).restitution, e_fast = p.impact(10.0, 1e-9).restitution;
    std::printf("hertz e = 0.5 requested: measured %.4f at 0.1 m/s, %.4f at 10 m/s\n", e_slow, e_fast);
    CHECK(e_slow == Approx(e_fast).epsilon(0.01));
    CHECK(e_slow < 0.6);
    CHECK(e_slow > 0.4);
}

TEST_CASE("the tangential stiffness is Mindlin's 8 G* sqrt(R* d) and friction caps it at fric F_n", "[hertz]") {
    Probe p(plab::contact_model_desc<Hertz>(), {{"E", E}, {"nu", nu}, {"fric", 0.3}});
    p.wall = true;
    const double d = 1e-6, G_eff = E / (2 * (1 + nu)) / (2 * (2 - nu)), dt = 1e-7;
    const double kt = 8 * G_eff * std::sqrt(p.eff_radius() * d);
    const double fn = 4.0 / 3.0 * E_eff * std::sqrt(p.eff_radius()) * std::pow(d, 1.5);
    // a small tangential slide: elastic, F_t = -k_t v_t dt
    plab::Vec3 f = p.force(-d, {0, 1e-4, 0}, dt);
    CHECK(f.x == Approx(fn).epsilon(1e-12));
    CHECK(f.y == Approx(-kt * 1e-4 * dt).epsilon(1e-9));
    // keep sliding: the force stops at the Coulomb limit
    for (int k = 0; k < 10000; ++k) f = p.force(-d, {0, 1e-2, 0}, dt);
    CHECK(std::fabs(f.y) == Approx(0.3 * fn).epsilon(1e-12));
}

TEST_CASE("apart balls feel nothing and a touching contact states a stable timestep", "[hertz]") {
    Probe p(plab::contact_model_desc<Hertz>());
    const plab::Vec3 f = p.force(1e-6);
    CHECK(f.x == 0.0);
    p.force(0.0);
    CHECK(p.outputs().dt_limit > 0.0);
    CHECK(std::isfinite(p.outputs().dt_limit));
}
