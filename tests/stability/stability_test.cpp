// Stability at the extremes (issue 7): each model run at the edges of its
// parameters must either stay physical (bounded energy balance) or stop with
// the detector's diagnostic naming the quantity and the cause — never write
// garbage. Short runs; the table of outcomes is in docs/stability.md.
#include "simulation.hpp"

#include "../support/sph_boundary.hpp"
#include "../support/case_scene.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <map>

using namespace plab;
using Catch::Matchers::Contains;

namespace {

struct Outcome {
    bool stopped = false;
    std::string quantity, message;
    double balance_error = 0;  // |balance drift| / energy turned over, for runs that finish
};

// Runs `cycles` steps; the energy scale is the initial kinetic + strain
// energy plus the largest |work| done by gravity and boundaries.
Outcome run(Simulation& sim, long cycles) {
    World& w = sim.world();
    w.prepare();
    const double e0 = w.energies.balance();
    double scale = w.energies.kinetic + w.energies.strain, b0 = w.energies.body, w0 = w.energies.boundary;
    Outcome out;
    try {
        for (long k = 0; k < cycles; ++k) {
            w.step();
            scale = std::max(scale, std::fabs(w.energies.body - b0) + std::fabs(w.energies.boundary - w0) +
                                        w.energies.kinetic + w.energies.strain);
        }
    } catch (const RunError& e) {
        out.stopped = true;
        out.quantity = e.quantity();
        out.message = e.what();
    }
    out.balance_error = scale > 0 ? std::fabs(w.energies.balance() - e0) / scale : 0.0;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) REQUIRE(w.bodies.position[i].allFinite());  // never garbage
    return out;
}

// A 2D square lattice of touching discs in a box of walls under gravity:
// every ball has four springs, the stiffest case of the nominal estimate.
json packed_box(const std::string& model, const json& properties) {
    return {{"dimension", 2},
            {"gravity", {0, -9.81}},
            {"plugins", {model}},
            {"bodies", {{{"type", "lattice"}, {"group", "grains"}, {"packing", "square"},
                         {"box", {{"min", {0, 0}}, {"max", {0.02, 0.02}}}}, {"radius", 0.001}, {"density", 2500},
                         {"jitter", {{"velocity", 0.05}, {"seed", 7}}}}}},
            {"walls", {{{"type", "box"}, {"group", "walls"}, {"min", {0, 0}}, {"max", {0.02, 0.04}}}}},
            {"contact_models", {{{"groups", {"*", "*"}}, {"model", model}, {"properties", properties}}}}};
}

// Sets the fixed step to `factor` times the critical step the models report.
void at_factor(Simulation& sim, double factor) {
    World& w = sim.world();
    w.prepare();
    w.fixed_dt = factor * stable_timestep(w).critical;
}

} // namespace

// The snapshot keeps only the motion and the rows whose history is not the
// default (World::take_snapshot); what comes back must still be the state
// the run had at that step.
TEST_CASE("the last good state after a stop is the run's state at that step, contact history included", "[stability]") {
    const json props = {{"kn", 1e6}, {"ks", 1e6}, {"fric", 0.5}};
    Simulation failing(packed_box("linear", props));
    at_factor(failing, 2.2);
    failing.world().snapshot_interval = 5;  // it fails within a few dozen steps
    REQUIRE(run(failing, 3000).stopped);
    const World& a = failing.world();
    REQUIRE(a.step_count > 0);

    Simulation again(packed_box("linear", props));
    at_factor(again, 2.2);
    World& b = again.world();
    while (b.step_count < a.step_count) b.step();
    REQUIRE(a.bodies.size() == b.bodies.size());
    for (std::size_t i = 0; i < a.bodies.size(); ++i) {
        CHECK(a.bodies.position[i] == b.bodies.position[i]);
        CHECK(a.bodies.velocity[i] == b.bodies.velocity[i]);
        CHECK(a.bodies.angular_velocity[i] == b.bodies.angular_velocity[i]);
    }
    // shear history by key; the restore re-evaluates forces at dt = 0, which
    // re-projects the shear force into the contact plane: equal to rounding
    auto shear = [](const World& w) {
        std::map<std::pair<BodyId, BodyId>, Vec> m;
        for (const ContactTable& s : {w.model(0).balls(), w.model(0).walls()})
            for (std::size_t k = 0; k < s.size(); ++k) {
                const Vec f(s.history(k));
                if (f != Vec::Zero()) m[s.key(k)] = f;
            }
        return m;
    };
    const auto ha = shear(a), hb = shear(b);
    REQUIRE(hb.size() > 10);
    CHECK(ha.size() == hb.size());
    for (const auto& [key, f] : hb) {
        const auto it = ha.find(key);
        REQUIRE(it != ha.end());
        CHECK((it->second - f).norm() <= 1e-12 * f.norm());
    }
}

TEST_CASE("linear model: 0.5 and 0.9 x the critical step are stable, 1.1 x too (the estimate is conservative), "
          "2 x stops with the timestep named", "[stability]") {
    const json props = {{"kn", 1e6}, {"ks", 1e6}};
    // the leapfrog's energy error is bounded and grows as (omega dt)^2 towards the limit
    for (auto [f, bound] : {std::pair{0.5, 0.02}, {0.9, 0.1}, {1.1, 0.25}}) {
        Simulation sim(packed_box("linear", props));
        at_factor(sim, f);
        const Outcome o = run(sim, 3000);
        INFO("factor " << f << ": " << o.message);
        CHECK_FALSE(o.stopped);
        CHECK(o.balance_error < bound);
    }
    Simulation sim(packed_box("linear", props));
    at_factor(sim, 2.0);
    const Outcome o = run(sim, 3000);
    REQUIRE(o.stopped);
    CHECK(o.quantity == "energy gain");
    CHECK_THAT(o.message, Contains("unstable: energy gain") && Contains("x the stable limit") &&
                              Contains("model linear for group grains") && Contains("last good state"));
}

TEST_CASE("linear_pbond: a bonded block is stable at 0.5 and 0.9 x the critical step and stops at 2 x", "[stability][bonds]") {
    const json props = {{"kn", 1e6}, {"ks", 1e6}, {"pb_kn", 1e9}, {"pb_ks", 1e9}, {"pb_ten", 1e12}, {"pb_coh", 1e12}};
    std::map<double, Outcome> outcome;
    for (double f : {0.5, 0.9, 1.1, 2.0}) {
        Simulation sim(packed_box("linear_pbond", props));
        World& w = sim.world();
        REQUIRE(w.bond(0, 0, 1e-9) > 0);
        at_factor(sim, f);
        outcome[f] = run(sim, 3000);
        INFO("factor " << f << ": " << outcome[f].message);
        if (f < 1) {
            CHECK_FALSE(outcome[f].stopped);
            CHECK(outcome[f].balance_error < 0.1);
        } else if (!outcome[f].stopped) {
            CHECK(outcome[f].balance_error < 0.25);  // stable is fine, garbage is not
        } else {
            CHECK_THAT(outcome[f].message, Contains("x the stable limit") && Contains("model linear_pbond"));
        }
    }
    CHECK(outcome[2.0].stopped);
}

TEST_CASE("stiffness ratio 1e4 and mass ratio 1e4 between touching balls: the automatic step stays stable and "
          "conserves energy", "[stability]") {
    // three discs in a row, moving into each other; a soft and a stiff contact
    json scene = {{"dimension", 2},
                  {"plugins", {"linear"}},
                  {"bodies", {{{"type", "ball"}, {"group", "a"}, {"position", {0, 0}}, {"radius", 0.001}, {"density", 2500}, {"velocity", {0.1, 0}}},
                              {{"type", "ball"}, {"group", "b"}, {"position", {0.002, 0}}, {"radius", 0.001}, {"density", 2500}},
                              {{"type", "ball"}, {"group", "c"}, {"position", {0.004, 0}}, {"radius", 0.001}, {"density", 2500}, {"velocity", {-0.1, 0}}}}},
                  {"contact_models", {{{"groups", {"a", "b"}}, {"model", "linear"}, {"properties", {{"kn", 1e4}, {"ks", 1e4}}}},
                                      {{"groups", {"b", "c"}}, {"model", "linear"}, {"properties", {{"kn", 1e8}, {"ks", 1e8}}}}}}};
    SECTION("stiffness ratio 1e4") {
        Simulation sim(scene);
        const Outcome o = run(sim, 20000);
        INFO(o.message);
        CHECK_FALSE(o.stopped);
        CHECK(o.balance_error < 0.1);  // accuracy, not stability: the stiff contact lasts ~4 steps
    }
    SECTION("mass ratio 1e4 (density 2.5e7 against 2500) with equal springs") {
        scene["bodies"][1]["density"] = 2.5e7;
        scene["contact_models"][1]["properties"] = {{"kn", 1e4}, {"ks", 1e4}};
        Simulation sim(scene);
        const Outcome o = run(sim, 20000);
        INFO(o.message);
        CHECK_FALSE(o.stopped);
        CHECK(o.balance_error < 0.1);
        // the light balls bounce off the heavy one: momentum is conserved exactly
        const World& w = sim.world();
        double p = 0;
        for (std::size_t i = 0; i < 3; ++i) p += w.bodies.mass[i] * w.bodies.velocity[i].x();
        CHECK(std::fabs(p) < 1e-12);
    }
}

namespace {

// A brittle bonded plate (rock-like, hexagonal calibration) clamped at both
// ends; a steel ball touches its middle at `speed`.
std::unique_ptr<Simulation> plate(double speed, double nu) {
    const double r = 0.001, pr = 0.002, t = 0.0087;
    const double top = r + 3 * std::sqrt(3.0) * r + r;  // surface of the 4th (top) hexagonal row: touching
    json scene = {
        {"dimension", 2},
        {"plugins", {"linear", "linear_pbond"}},
        {"bodies", {{{"type", "lattice"}, {"group", "plate"}, {"packing", "hexagonal"}, {"box", {{"min", {0, 0}}, {"max", {0.04, t}}}},
                     {"radius", r}, {"density", 2400}},
                    {{"type", "ball"}, {"group", "projectile"}, {"position", {0.02, top + pr}}, {"velocity", {0, -speed}},
                     {"radius", pr}, {"density", 7800}}}},
        {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"}, {"properties", {{"kn", 5e8}, {"ks", 5e8}, {"fric", 0.3}}}},
                            {{"groups", {"plate", "plate"}}, {"model", "linear_pbond"},
                             {"calibrate", {{"method", "hexagonal_2d"}, {"E", 30e9}, {"nu", nu}, {"sigma_ult", 30e6}, {"radius", r}}},
                             {"properties", {{"fric", 0.3}}}}}},
        {"timestep", {{"safety_factor", 0.5}}}};
    auto sim = std::make_unique<Simulation>(scene);
    sim->set_quiet(true);
    World& w = sim->world();
    const int g = w.find_group("plate");
    REQUIRE(w.bond(g, g, 1e-9) > 0);
    for (std::size_t i = 0; i < w.bodies.size(); ++i)
        if (w.bodies.group[i] == g && (w.bodies.position[i].x() < 2.5 * r || w.bodies.position[i].x() > 0.04 - 2.5 * r))
            w.bodies.fixity[i] = 63;
    return sim;
}

} // namespace

TEST_CASE("impact from 0.01 to 100 m/s on a bonded plate: elastic and intact at low speed, broken bonds with a "
          "closed energy balance at 30 and 100 m/s", "[stability][bonds]") {
    for (double v : {0.01, 1.0, 30.0, 100.0}) {
        auto sim = plate(v, 0.2);
        const Outcome o = run(*sim, 1500);
        const World& w = sim->world();
        INFO("speed " << v << " m/s: " << o.message << "; breaks " << w.bond_breaks.size());
        CHECK_FALSE(o.stopped);
        CHECK(o.balance_error < 0.01);
        const double vy = w.bodies.velocity.back().y();  // the projectile felt the plate
        CHECK(std::fabs(vy + v) > 1e-3 * v);
        if (v <= 1.0) CHECK(w.bond_breaks.empty());
        else CHECK_FALSE(w.bond_breaks.empty());
    }
}

TEST_CASE("bond calibration with nu approaching 1/3 stays stable, nu above 1/3 is refused", "[stability][bonds]") {
    for (double nu : {0.25, 0.33, 0.3333}) {
        auto sim = plate(1.0, nu);
        const Outcome o = run(*sim, 1000);
        INFO("nu " << nu << ": " << o.message);
        CHECK_FALSE(o.stopped);
        CHECK(o.balance_error < 0.01);
    }
    CHECK_THROWS_WITH(plate(1.0, 0.34), Contains("calibrate.nu") && Contains("[0, 1/3)"));
}

TEST_CASE("a disordered, overlapping initial packing relaxes under the automatic step without gaining energy",
          "[stability]") {
    json scene = packed_box("linear", {{"kn", 1e6}, {"ks", 1e6}, {"fric", 0.5}, {"dp_nratio", 0.2}});
    scene["bodies"][0]["jitter"] = {{"position", 0.0003}, {"velocity", 0.1}, {"seed", 11}};  // 30 % of r
    Simulation sim(scene);
    const Outcome o = run(sim, 5000);
    INFO(o.message);
    CHECK_FALSE(o.stopped);
    const Energies& e = sim.world().energies;
    CHECK(e.dashpot > 0);  // the overlaps were released and damped, not amplified
}

TEST_CASE("1e-6 m and 10 m balls behave the same in the same units: restitution is scale-free", "[stability]") {
    // two equal balls collide head on; kn ~ E R and v ~ R keep overlap/R and e fixed
    auto restitution = [](double R) {
        const double kn = 1e7 * R, v = 0.1;  // t_c ~ sqrt(m/k) ~ R, so overlap/R ~ v t_c/R is fixed
        json scene = {{"dimension", 3},
                      {"plugins", {"linear"}},
                      {"bodies", {{{"type", "ball"}, {"position", {0, 0, 0}}, {"radius", R}, {"density", 2500}, {"velocity", {v, 0, 0}}},
                                  {{"type", "ball"}, {"position", {2.0001 * R, 0, 0}}, {"radius", R}, {"density", 2500}, {"velocity", {-v, 0, 0}}}}},
                      {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"}, {"properties", {{"kn", kn}, {"ks", kn}, {"dp_nratio", 0.2}}}}}}};
        Simulation sim(scene);
        sim.set_quiet(true);
        const Outcome o = run(sim, 2000);
        INFO("R " << R << ": " << o.message);
        CHECK_FALSE(o.stopped);
        return sim.world().bodies.velocity[1].x() / v;
    };
    const double e_mm = restitution(1e-3);
    CHECK(e_mm > 0.4);
    CHECK(e_mm < 0.9);
    CHECK(restitution(1e-6) == Approx(e_mm).epsilon(1e-6));
    CHECK(restitution(10.0) == Approx(e_mm).epsilon(1e-6));
}

// ---- SPH ------------------------------------------------------------------

namespace {

// A small dam break (column 0.04 x 0.08 m, dp 0.01 m, tank 0.2 m) with
// boundary balls at dp/2; c0 = `mach_factor` times the largest speed
// sqrt(2 g H). `jitter` displaces the fluid lattice by up to that fraction of dp.
// `scale` multiplies every length (Froude scaling: speeds and times go as
// its square root).
json small_dam_break(double mach_factor, double jitter = 0, double scale = 1) {
    const double g = 9.81, a = 0.04 * scale, H = 0.08 * scale, dp = 0.01 * scale, db = dp / 2, h = 1.3 * dp;
    const double t = std::ceil(2 * h / db) * db, length = 0.2 * scale;
    const double c0 = mach_factor * std::sqrt(2 * g * H);
    const json sph = {{"smoothing_length", h}, {"kernel", "wendland_c2"}, {"speed_of_sound", c0}, {"viscosity", "artificial"}, {"alpha", 0.1}};
    auto block = [db](double x0, double y0, double x1, double y1) { return testing_support::boundary_block(x0, y0, x1, y1, db); };
    json fluid = {{"type", "lattice"}, {"group", "fluid"}, {"packing", "square"},
                  {"box", {{"min", {0, 0}}, {"max", {a, H}}}}, {"radius", dp / 2}, {"spacing", dp},
                  {"mass", 1000 * dp * dp}, {"fix", {"rotation"}}};
    if (jitter > 0) fluid["jitter"] = {{"position", jitter * dp}, {"seed", 5}};
    return {{"dimension", 2},
            {"gravity", {0, -g}},
            {"plugins", {"sph"}},
            {"bodies", {fluid, block(-t, -t, length + t, 0), block(-t, 0, 0, 2 * H), block(length, 0, length + t, 2 * H)}},
            {"contact_models", {{{"groups", {"fluid", "fluid"}}, {"model", "sph"}, {"properties", sph}},
                                {{"groups", {"fluid", "boundary"}}, {"model", "sph"}, {"properties", sph}}}},
            {"passes", {{{"name", "sph_density_integration"}, {"properties", {{"boundary_group", "boundary"}}}},
                        {{"name", "sph_eos"}, {"properties", {{"speed_of_sound", c0}, {"boundary_group", "boundary"},
                                                              {"hydrostatic_gravity", g}, {"surface_level", H}}}},
                        {{"name", "sph_wall_pressure"}, {"properties", {{"smoothing_length", h}, {"kernel", "wendland_c2"},
                                                                        {"speed_of_sound", c0}, {"boundary_group", "boundary"},
                                                                        {"gravity_y", -g}}}}}}};
}

long steps_for(Simulation& sim, double seconds) {
    World& w = sim.world();
    w.prepare();
    const double dt = w.fixed_dt > 0 ? w.fixed_dt : w.safety_factor * stable_timestep(w).critical;
    return long(seconds / dt);
}

} // namespace

TEST_CASE("SPH: 0.5, 0.9, 1.1 and 2 x the CFL step (0.25 h/c0) are stable (the CFL number 0.25 is a margin), 8 x stops with the timestep named",
          "[stability][sph]") {
    for (double f : {0.5, 0.9, 1.1, 2.0, 8.0}) {
        Simulation sim(small_dam_break(10));
        sim.set_quiet(true);
        at_factor(sim, f);
        const Outcome o = run(sim, steps_for(sim, 0.15));
        INFO("factor " << f << ": " << o.message);
        if (f <= 2.0) {
            CHECK_FALSE(o.stopped);
        } else {
            REQUIRE(o.stopped);
            CHECK_THAT(o.message, Contains("x the stable limit") && Contains("model sph"));
        }
    }
}

TEST_CASE("SPH: c0 = 5, 10 and 20 x the largest speed run, 3 x stops on the density band (issue 4)", "[stability][sph]") {
    for (double m : {5.0, 10.0, 20.0}) {
        Simulation sim(small_dam_break(m));
        sim.set_quiet(true);
        const Outcome o = run(sim, steps_for(sim, 0.15));
        INFO("c0 = " << m << " x: " << o.message);
        CHECK_FALSE(o.stopped);
    }
    Simulation sim(small_dam_break(3));
    sim.set_quiet(true);
    // the pass knows balls by index; the message must name the user's id
    World& w = sim.world();
    for (auto& id : w.bodies.id) id += 1000;
    w.bodies.next_id += 1000;
    const Outcome o = run(sim, steps_for(sim, 0.15));
    REQUIRE(o.stopped);
    CHECK(o.quantity == "sph_density");
    CHECK_THAT(o.message, Contains("outside rho0 (1 +- 0.05)") && Contains("speed of sound") && Contains("too low") &&
                              Contains("last good state"));
    CHECK_THAT(o.message, Contains("pass sph_eos: ball id 10") && Contains(" (group fluid) has density"));
    CHECK_THAT(o.message, !Contains("ball index"));
}

TEST_CASE("SPH: 1e-6 m and 10 m particles make the same dam break in the same units (no hidden length scale)",
          "[stability][sph]") {
    // Froude scaling: lengths x s, times and speeds x sqrt(s), c0 = 10 sqrt(2 g H)
    // scales with them, so x/s at t/sqrt(s) must not depend on s
    auto front = [](double dp) {
        const double s = dp / 0.01;
        Simulation sim(small_dam_break(10, 0, s));
        sim.set_quiet(true);
        World& w = sim.world();
        const Outcome o = run(sim, steps_for(sim, 0.1 * std::sqrt(s)));
        INFO("dp " << dp << " m: " << o.message);
        CHECK_FALSE(o.stopped);
        double x = -kInf;
        for (std::size_t i = 0; i < w.bodies.size(); ++i)
            if (w.bodies.group[i] == 0) x = std::max(x, w.bodies.position[i].x());
        return x / s;
    };
    const double x_cm = front(0.01);
    CHECK(x_cm > 0.04 * 1.5);  // the surge has moved out
    CHECK(front(1e-6) == Approx(x_cm).epsilon(1e-6));
    CHECK(front(10.0) == Approx(x_cm).epsilon(1e-6));
}

TEST_CASE("SPH: a disordered initial lattice (20 % of dp) relaxes without leaving the density band", "[stability][sph]") {
    Simulation sim(small_dam_break(10, 0.2));
    sim.set_quiet(true);
    const Outcome o = run(sim, steps_for(sim, 0.1));
    INFO(o.message);
    CHECK_FALSE(o.stopped);
}

// ---- SPH-DEM coupling ----------------------------------------------------

namespace {

struct Settling {
    bool stopped = false;
    std::string quantity, message;
    std::vector<double> t, y, v;  // the disc's height (m) and vertical velocity (m/s)
};

// The sedimentation case's scene (validation/sedimentation) at its coarse
// resolution (dp 2.5 mm, the disc's diameter), the disc of density
// rho_f / ratio released at rest at y = 0.04 m, run for `seconds`.
Settling settle(double ratio, double seconds, double floor_kn = 0) {
    std::vector<std::pair<std::string, json>> sets = {{"variables.dp", 0.0025}, {"variables.rho_s", 1000.0 / ratio}};
    if (floor_kn > 0) sets.push_back({"variables.floor_kn", floor_kn});
    json scene = testing_support::case_scene("sedimentation", sets);
    scene.erase("commands");
    scene.erase("histories");
    scene.erase("metrics");
    Simulation sim(scene);
    sim.set_quiet(true);
    World& w = sim.world();
    const std::size_t disc = w.bodies.size() - 1;
    REQUIRE(w.group_names()[w.bodies.group[disc]] == "disc");
    w.prepare();
    Settling out;
    try {
        while (w.time < seconds) {
            w.step();
            out.t.push_back(w.time);
            out.y.push_back(w.bodies.position[disc].y());
            out.v.push_back(w.bodies.velocity[disc].y());
        }
    } catch (const RunError& e) {
        out.stopped = true;
        out.quantity = e.quantity();
        out.message = e.what();
    }
    for (const Vec& x : w.bodies.position) REQUIRE(x.allFinite());  // never garbage
    return out;
}

} // namespace

TEST_CASE("fluid/solid density ratio 0.1, 1 and 10: a heavy disc sinks no faster than buoyant free fall, a neutral one "
          "hovers, a light one rises to the lid", "[stability][coupling]") {
    constexpr double g = 9.81, d = 0.0025, terminal_1250 = 0.0555;  // Glowinski: rho_s = 1250 settles at 0.0555 m/s
    SECTION("ratio 0.1 (rho_s = 10000): sinks; drag only slows it, so |v| <= g (1 - rho_f/rho_s) t") {
        const Settling s = settle(0.1, 0.1);
        INFO(s.message);
        REQUIRE_FALSE(s.stopped);
        CHECK(s.y.back() < 0.04 - 10 * d);
        for (std::size_t k = 0; k < s.t.size(); ++k) {
            CHECK(s.v[k] < 0.01 * g * s.t[k] + 1e-6);  // downward from the first steps
            CHECK(-s.v[k] <= 1.05 * g * 0.9 * s.t[k] + 1e-3);
        }
    }
    SECTION("ratio 1 (rho_s = rho_f): hovers; the drift is a fraction of the rho_s = 1250 disc's settling speed") {
        const Settling s = settle(1.0, 0.2);
        INFO(s.message);
        REQUIRE_FALSE(s.stopped);
        const double mean_v = (s.y.back() - 0.04) / s.t.back();
        CHECK(std::fabs(mean_v) < 0.25 * terminal_1250);
        CHECK(std::fabs(s.y.back() - 0.04) < d);
    }
    SECTION("ratio 10 (rho_s = 100): rises and comes to rest under the lid, inside the box") {
        const Settling s = settle(10.0, 0.2);
        INFO(s.message);
        REQUIRE_FALSE(s.stopped);
        CHECK(s.y.back() > 0.055);
        CHECK(s.y.back() < 0.06);
        CHECK(std::fabs(s.v.back()) < 0.01);
    }
}

TEST_CASE("a heavy disc on a floor contact sized for a light one stops on the overlap as its centre crosses the "
          "floor, and a stiffer floor holds it", "[stability][coupling]") {
    // rho_s = 10000 reaches ~0.5 m/s: the floor's kn 1e3 N/m lets it overlap v sqrt(m/k) ~ 3 mm > r; the
    // box's floor is a segment, whose side the contact remembers (facet_distance), so the overlap passes r
    const Settling soft = settle(0.1, 0.3);
    REQUIRE(soft.stopped);
    CHECK(soft.quantity == "overlap");
    CHECK_THAT(soft.message, Contains("(group disc)") && Contains("wall 'box'") && Contains("max_overlap"));
    const Settling stiff = settle(0.1, 0.3, 1e5);
    INFO(stiff.message);
    CHECK_FALSE(stiff.stopped);
    CHECK(stiff.y.back() > 0.0);
    CHECK(stiff.y.back() < 0.00125 + 1e-4);  // resting on the floor
}

// A segment (2D) or triangle (3D) has two faces and an unsigned distance: a
// ball driven through one must not be pushed out of the far face as if it
// had always been there. The contact remembers its side, also across
// neighbour-list rebuilds, and the overlap check stops the run as the centre
// crosses.
TEST_CASE("a ball driven through a segment or triangle wall stops on the overlap as its centre crosses it, with and "
          "without rebuilds at every step", "[stability]") {
    for (int dim : {2, 3}) {
        for (double skin : {0.002, 1e-9}) {
            CAPTURE(dim, skin);
            auto v = [dim](double x, double y, double z) { return dim == 2 ? json::array({x, y}) : json::array({x, y, z}); };
            const json wall = dim == 2 ? json{{"type", "segment"}, {"name", "sheet"}, {"from", {-0.05, 0}}, {"to", {0.05, 0}}}
                                       : json{{"type", "rectangle"}, {"name", "sheet"},
                                              {"corners", {{-0.05, 0, -0.05}, {0.05, 0, -0.05}, {0.05, 0, 0.05}, {-0.05, 0, 0.05}}}};
            // kn 10 N/m: the ball (0.31 kg in 2D, 4 g in 3D) would overlap v sqrt(m/k) >> r
            const json scene = {{"dimension", dim},
                                {"plugins", {"linear"}},
                                {"skin", skin},
                                {"timestep", {{"fixed", 1e-4}}},
                                {"domain", {{"min", v(-0.1, -0.1, -0.1)}, {"max", v(0.1, 0.1, 0.1)}}},
                                {"bodies", {{{"type", "ball"}, {"group", "ball"}, {"position", v(0.001, 0.03, 0.002)},
                                             {"radius", 0.01}, {"density", 1000}, {"velocity", v(0, -1, 0)}}}},
                                {"walls", {wall}},
                                {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"},
                                                     {"properties", {{"kn", 10}, {"ks", 10}}}}}}};
            Simulation sim(scene);
            sim.set_quiet(true);
            World& w = sim.world();
            w.prepare();
            double y_last = w.bodies.position[0].y();
            std::string quantity, message;
            try {
                for (int k = 0; k < 1000; ++k) {
                    w.step();
                    y_last = w.bodies.position[0].y();
                }
            } catch (const RunError& e) {
                quantity = e.quantity();
                message = e.what();
            }
            INFO(message);
            REQUIRE(quantity == "overlap");
            CHECK_THAT(message, Contains("wall 'sheet'"));
            // the last completed step left the centre above the sheet, within one step's travel (1e-4 m)
            CHECK(y_last >= 0.0);
            CHECK(y_last < 1.5e-4);
        }
    }
}
