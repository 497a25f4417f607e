// The shipped `hertz` model (physics/dem/hertz) against the analytical
// Hertz–Mindlin contact: the force at an overlap, the elastic contact time,
// the restitution it is asked for, two materials mixed, the Coulomb limit,
// energy conservation at e = 1, the 2D cylinder contact, and its step limit.
// The law is driven as the host calls it (plab::testing::Probe) on the
// library the build ships; the scenes are validation/hertz_impact's.
#include "../support/case_scene.hpp"

#include <plab/testing.hpp>
#include <plab_host/plugins.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

namespace {

using plab::json;
using plab::Simulation;
using plab::testing::Probe;
using namespace plab::testing_support;

// glass: the Probe's default ends are two 5 mm spheres of 2500 kg/m^3
constexpr double E = 7e10, nu = 0.25;
const double E_eff = E / (2 * (1 - nu * nu));                  // 1/E* = 2 (1 - nu^2)/E
const double G_eff = E / (2 * (1 + nu)) / (2 * (2 - nu));      // 1/G* = 2 (2 - nu)/G

const plab_contact_model_desc* hertz() {
    static const std::unique_ptr<plab::PluginHost> host = [] {
        auto h = std::make_unique<plab::PluginHost>();
        h->load(std::string(PLAB_PLUGIN_OUTPUT_DIR) + "/plab_hertz.so");
        return h;
    }();
    return host->model("hertz");
}

// Johnson (1985) §11.4: t_c = 2.8683 (m*^2 / (R* E*^2 v))^(1/5)
double hertz_contact_time(double m, double R, double v) { return 2.8682657 * std::pow(m * m / (R * E_eff * E_eff * v), 0.2); }

} // namespace

TEST_CASE("hertz: the normal force and stiffness are Hertz's at any overlap", "[hertz]") {
    Probe p(hertz(), {{"E", E}, {"nu", nu}});
    for (double d : {1e-9, 1e-7, 1e-5}) {
        INFO("overlap " << d);
        const plab::Vec3 f = p.force(-d);
        const double R = p.eff_radius();
        CHECK(f.x == Approx(4.0 / 3.0 * E_eff * std::sqrt(R) * std::pow(d, 1.5)).epsilon(1e-12));
        CHECK(f.y == 0.0);
        // the stable step's stiffness: the tangent normal stiffness 2 E* sqrt(R* d), larger than Mindlin's 8 G* sqrt(R* d)
        CHECK(p.outputs().stiffness == Approx(2 * E_eff * std::sqrt(R * d)).epsilon(1e-12));
        CHECK(8 * G_eff < 2 * E_eff);
    }
    CHECK(p.force(1e-9).x == 0.0);  // apart: nothing
}

TEST_CASE("hertz: an elastic impact lasts Hertz's contact time at 0.01 to 10 m/s and returns every joule", "[hertz]") {
    for (bool wall : {true, false}) {
        Probe p(hertz(), {{"E", E}, {"nu", nu}, {"e", 1.0}});
        p.wall = wall;
        for (double v : {0.01, 1.0, 10.0}) {
            INFO((wall ? "wall" : "two spheres") << ", v " << v);
            const double tc = hertz_contact_time(p.eff_mass(), p.eff_radius(), v);
            const plab::testing::Impact im = p.impact(v, tc / 2000);
            CHECK(im.duration == Approx(tc).epsilon(1e-3));
            CHECK(im.max_overlap == Approx(std::pow(15 * p.eff_mass() * v * v / (16 * E_eff * std::sqrt(p.eff_radius())), 0.4))
                                        .epsilon(1e-3));
            CHECK(im.restitution == Approx(1.0).epsilon(1e-6));
        }
    }
}

TEST_CASE("hertz: kinetic plus strain energy stays constant through an elastic impact", "[hertz]") {
    // the relative coordinate's leapfrog, as Probe::impact, with the energy at
    // whole steps: velocity the mean of the two half steps, strain the model's
    Probe p(hertz(), {{"E", E}, {"nu", nu}, {"e", 1.0}});
    p.wall = true;
    const double v0 = 1.0, m = p.eff_mass(), dt = hertz_contact_time(m, p.eff_radius(), v0) / 4000;
    const double e0 = 0.5 * m * v0 * v0;
    double gap = 0.5 * v0 * dt, v_half = -v0, worst = 0, strain_peak = 0;
    for (int k = 0; k < 20000 && !(gap > 0 && v_half > 0 && k > 10); ++k) {
        const double f = p.force(gap, {v_half, 0, 0}, dt).x;
        const double strain = p.outputs().strain_energy;
        const double v_next = v_half + dt * f / m, v_whole = 0.5 * (v_half + v_next);
        worst = std::max(worst, std::fabs(0.5 * m * v_whole * v_whole + strain - e0) / e0);
        strain_peak = std::max(strain_peak, strain);
        v_half = v_next;
        gap += dt * v_half;
    }
    CHECK(strain_peak > 0.99 * e0);  // (all of it is stored at the deepest point)
    CHECK(worst < 1e-6);             // the leapfrog's O(dt^2) at 4000 steps a contact
}

TEST_CASE("hertz: the restitution is the e asked for, at every speed, and higher without the dashpot's pull", "[hertz]") {
    for (double e : {0.1, 0.3, 0.5, 0.7, 0.9, 0.99})
        for (double v : {0.01, 10.0}) {
            INFO("e " << e << ", v " << v);
            Probe p(hertz(), {{"E", E}, {"nu", nu}, {"e", e}});
            p.wall = true;
            const double tc = hertz_contact_time(p.eff_mass(), p.eff_radius(), v);
            CHECK(p.impact(v, tc / 4000).restitution == Approx(e).epsilon(1e-3));
        }
    Probe clipped(hertz(), {{"E", E}, {"nu", nu}, {"e", 0.5}, {"dp_mode", 1}});
    clipped.wall = true;
    const double tc = hertz_contact_time(clipped.eff_mass(), clipped.eff_radius(), 1.0);
    CHECK(clipped.impact(1.0, tc / 4000).restitution > 0.52);  // (0.550: the dashpot no longer pulls the ball back)
}

TEST_CASE("hertz: the tangential force is Mindlin's spring, capped at fric F_n, the slip dissipated", "[hertz]") {
    const double fric = 0.3, d = 1e-6, dt = 1e-7;
    Probe p(hertz(), {{"E", E}, {"nu", nu}, {"fric", fric}});
    p.wall = true;
    const double R = p.eff_radius(), fn = 4.0 / 3.0 * E_eff * std::sqrt(R) * std::pow(d, 1.5);
    const double kt = 8 * G_eff * std::sqrt(R * d);
    plab::Vec3 f = p.force(-d, {0, 1e-4, 0}, dt);  // a small slide: elastic, -S_t v_t dt
    CHECK(f.y == Approx(-kt * 1e-4 * dt).epsilon(1e-9));
    CHECK(p.outputs().slip_energy == 0.0);
    double slip = 0;
    for (int k = 0; k < 2000; ++k) {
        f = p.force(-d, {0, 1e-2, 0}, dt);
        slip += p.outputs().slip_energy;
    }
    CHECK(std::fabs(f.y) == Approx(fric * fn).epsilon(1e-12));
    CHECK(f.x == Approx(fn).epsilon(1e-12));
    // sliding at 1e-2 m/s, the friction force does fric F_n v dt of work a step, all of it slip
    CHECK(p.outputs().slip_energy == Approx(fric * fn * 1e-2 * dt).epsilon(1e-6));
    // in all: fric F_n times the slide less the spring's elastic travel fric F_n / S_t
    CHECK(slip == Approx(fric * fn * (2000 * 1e-2 * dt - fric * fn / kt)).epsilon(0.01));
}

TEST_CASE("hertz: 2D is the cylinder contact pi/4 E* L d, a linear spring with exact restitution", "[hertz]") {
    Probe p(hertz(), {{"E", E}, {"nu", nu}, {"e", 1.0}});
    p.dim = 2;
    p.wall = true;
    p.mass1 = 2500 * M_PI * 0.005 * 0.005;  // a disc 1 m thick
    const double kn = M_PI / 4 * E_eff;   // L = 1 m
    CHECK(p.force(-1e-7).x == Approx(kn * 1e-7).epsilon(1e-12));
    CHECK(p.force(-1e-5).x == Approx(kn * 1e-5).epsilon(1e-12));
    const double tc = M_PI * std::sqrt(p.eff_mass() / kn);  // half a period of the spring, at any speed
    for (double v : {0.01, 10.0}) CHECK(p.impact(v, tc / 2000).duration == Approx(tc).epsilon(1e-3));
    Probe damped(hertz(), {{"E", E}, {"nu", nu}, {"e", 0.5}});
    damped.dim = 2;
    damped.wall = true;
    damped.mass1 = p.mass1;
    CHECK(damped.impact(1.0, tc / 4000).restitution == Approx(0.5).epsilon(1e-3));
}

TEST_CASE("hertz: the step limit is 0.2 of the smaller ball's Rayleigh time", "[hertz]") {
    Probe p(hertz(), {{"E", E}, {"nu", nu}});
    p.radius2 = 0.002;
    p.mass2 = 2500 * 4.0 / 3.0 * M_PI * 0.002 * 0.002 * 0.002;
    p.force(-1e-7);
    const double G = E / (2 * (1 + nu));
    // Li, Xu & Thornton (2005): T_R = pi R sqrt(rho / G) / (0.1631 nu + 0.8766)
    const double rayleigh = M_PI * 0.002 * std::sqrt(2500 / G) / (0.1631 * nu + 0.8766);
    CHECK(p.outputs().dt_limit == Approx(0.2 * rayleigh).epsilon(1e-9));
}

TEST_CASE("hertz: two materials of one Poisson's ratio meet with Hertz's E*, and two ratios are refused", "[hertz]") {
    // glass on steel, head on: 1/E* = (1 - nu^2)(1/E_glass + 1/E_steel), which the
    // harmonic mix of E, 2 E1 E2 / (E1 + E2), gives in the scene's E* = E / (2 (1 - nu^2))
    const double E_glass = 6.3e10, E_steel = 2.1e11, E_mixed = 2 * E_glass * E_steel / (E_glass + E_steel);
    auto sets = std::vector<std::pair<std::string, json>>{
        {"variables.E", E_mixed},
        {"variables.v0", 1.0},
        {"bodies.1.group", "b"},
        {"materials", {{"glass", {{"groups", {"a"}}, {"E", E_glass}, {"nu", nu}}},
                       {"steel", {{"groups", {"b"}}, {"E", E_steel}, {"nu", nu}}}}},
        {"contact_models.0", {{"groups", {"a", "b"}}, {"model", "hertz"}, {"properties", {{"e", 1}}}}}};
    const auto sim = run_scene(case_scene("hertz_impact", sets, "scene_ball.json"));
    CHECK(metric(*sim, "contact_time", "error") < 1e-3);
    CHECK(metric(*sim, "restitution", "error") < 1e-6);

    sets[3].second["steel"]["nu"] = 0.3;
    try {
        Simulation refused(case_scene("hertz_impact", sets, "scene_ball.json"));
        FAIL("two Poisson's ratios in one rule were accepted");
    } catch (const std::exception& ex) {
        const std::string msg = ex.what();
        INFO(msg);
        CHECK((msg.find("scene.materials.steel.nu") != std::string::npos || msg.find("scene.materials.glass.nu") != std::string::npos));
    }
}

TEST_CASE("hertz: a property out of its range is refused naming its path, value and range", "[hertz]") {
    const auto refusal = [](const char* key, json value) {
        try {
            Simulation sim(case_scene("hertz_impact", {{std::string("contact_models.0.properties.") + key, value}},
                                      "scene_wall.json"));
        } catch (const std::exception& ex) {
            return std::string(ex.what());
        }
        return std::string("accepted");
    };
    const std::string e = refusal("e", 0), nu_bad = refusal("nu", 0.5), E_bad = refusal("E", -7e10);
    CHECK_THAT(e, Catch::Contains("scene.contact_models[0].properties.e") && Catch::Contains("(0, 1]"));
    CHECK_THAT(nu_bad, Catch::Contains("scene.contact_models[0].properties.nu") && Catch::Contains("[0, 0.5)"));
    CHECK_THAT(E_bad, Catch::Contains("scene.contact_models[0].properties.E") && Catch::Contains("-7e+10"));
}
