// DEM validation cases: free_fall, restitution, rolling, energy_conservation.
// Each builds its scene in JSON, runs it through the same Simulation as
// `plab run`, and compares with the analytical solution.
#include "dem_cases.hpp"

#include "../generators.hpp"
#include "../simulation.hpp"
#include "../validation.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace plab::cases {

namespace {

json vec(int dim, double x, double y, double z = 0) {
    return dim == 2 ? json::array({x, y}) : json::array({x, y, z});
}

std::unique_ptr<Simulation> make(const json& scene) {
    auto sim = std::make_unique<Simulation>(scene);
    sim->set_quiet(true);
    return sim;
}

} // namespace

double free_fall_error(int dim, double dt, long steps) {
    const double y0 = 1000.0, v0 = 2.0, g = -9.81;  // stays well above y = 0: relative error is meaningful
    json scene = {{"dimension", dim},
                  {"gravity", vec(dim, 0, g)},
                  {"bodies", {{{"type", "ball"}, {"position", vec(dim, 0, y0)}, {"velocity", vec(dim, 0, v0)},
                               {"radius", 0.01}, {"density", 2500}}}},
                  {"timestep", {{"fixed", dt}}}};
    auto sim = make(scene);
    World& w = sim->world();
    double worst = 0;
    for (long k = 0; k < steps; ++k) {
        w.step();
        const double t = w.time;
        const double exact = y0 + v0 * t + 0.5 * g * t * t;
        worst = std::max(worst, std::fabs(w.bodies.position[0].y() - exact) / std::fabs(exact));
    }
    return worst;
}

Impact normal_impact(int dim, bool on_wall, double beta, int dp_mode) {
    const double r = 0.01, rho = 2500, kn = 1e5, v0 = 1.0, start_gap = 1e-4;
    json bodies = json::array();
    bodies.push_back({{"type", "ball"}, {"group", "a"}, {"position", vec(dim, 0, 0)}, {"velocity", vec(dim, v0, 0)},
                      {"radius", r}, {"density", rho}});
    json walls = json::array();
    if (on_wall) {
        const double x = r + start_gap;
        if (dim == 2) walls.push_back({{"type", "segment"}, {"from", {x, -1}}, {"to", {x, 1}}, {"group", "w"}});
        else walls.push_back({{"type", "plane"}, {"point", {x, 0, 0}}, {"normal", {-1, 0, 0}}, {"group", "w"}});
    } else {
        bodies.push_back({{"type", "ball"}, {"group", "a"}, {"position", vec(dim, 2 * r + start_gap, 0)},
                          {"velocity", vec(dim, -v0, 0)}, {"radius", r}, {"density", rho}});
    }
    const double m = dim == 2 ? rho * M_PI * r * r : rho * 4.0 / 3.0 * M_PI * r * r * r;
    const double m_eff = on_wall ? m : m / 2;
    const double omega = std::sqrt(kn / m_eff);
    Impact out;
    out.expected_duration = M_PI / (omega * std::sqrt(1 - beta * beta));
    out.expected_restitution = std::exp(-beta * M_PI / std::sqrt(1 - beta * beta));
    const double dt = out.expected_duration / 4000;
    json scene = {{"dimension", dim},
                  {"plugins", {"linear"}},
                  {"bodies", bodies},
                  {"walls", walls},
                  {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"},
                                       {"properties", {{"kn", kn}, {"ks", 0}, {"dp_nratio", beta}, {"dp_mode", dp_mode}}}}}},
                  {"timestep", {{"fixed", dt}}}};
    auto sim = make(scene);
    World& w = sim->world();
    // surface gap along x, from positions (exact leapfrog states)
    auto gap = [&]() {
        return on_wall ? (r + start_gap) - (w.bodies.position[0].x() + r)
                       : w.bodies.position[1].x() - w.bodies.position[0].x() - 2 * r;
    };
    auto closing_speed = [&]() {
        return on_wall ? w.bodies.velocity[0].x() : w.bodies.velocity[0].x() - w.bodies.velocity[1].x();
    };
    double t_in = -1, t_out = -1, prev_gap = gap(), prev_t = 0, force_free_steps = 0;
    const long max_steps = long(20 * out.expected_duration / dt);
    for (long k = 0; k < max_steps; ++k) {
        w.step();
        const double g = gap();
        if (t_in < 0 && g < 0) t_in = prev_t + (w.time - prev_t) * prev_gap / (prev_gap - g);
        if (t_in >= 0 && t_out < 0 && g >= 0) t_out = prev_t + (w.time - prev_t) * prev_gap / (prev_gap - g);
        // contact over and no force left: the rebound speed is final
        if (t_out >= 0 && w.active_contacts() == 0 && ++force_free_steps > 3) break;
        prev_gap = g;
        prev_t = w.time;
    }
    out.duration = t_out - t_in;
    out.restitution = -closing_speed() / (on_wall ? v0 : 2 * v0);
    return out;
}

double rolling_speed_ratio(int dim) {
    const double r = 0.01, rho = 2500, kn = 1e6, g = 9.81, v0 = 1.0;
    const double m = dim == 2 ? rho * M_PI * r * r : rho * 4.0 / 3.0 * M_PI * r * r * r;
    const double y = r - m * g / kn;  // resting overlap: no bounce at launch
    json walls = json::array();
    if (dim == 2) walls.push_back({{"type", "segment"}, {"from", {-1, 0}}, {"to", {5, 0}}});
    else walls.push_back({{"type", "plane"}, {"point", {0, 0, 0}}, {"normal", {0, 1, 0}}});
    json scene = {{"dimension", dim},
                  {"plugins", {"linear"}},
                  {"gravity", vec(dim, 0, -g)},
                  {"bodies", {{{"type", "ball"}, {"position", vec(dim, 0, y)}, {"velocity", vec(dim, v0, 0)},
                               {"radius", r}, {"density", rho}}}},
                  {"walls", walls},
                  {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"},
                                       {"properties", {{"kn", kn}, {"ks", kn}, {"fric", 0.3}, {"dp_nratio", 0.3},
                                                       {"dp_sratio", 0.3}}}}}},
                  {"timestep", {{"safety_factor", 0.2}}}};
    auto sim = make(scene);
    World& w = sim->world();
    // sliding lasts (v0 - v_f)/(mu g) ≈ 0.11 s; average the speed after 0.25 s
    double sum = 0;
    long n = 0;
    while (w.time < 0.35) {
        w.step();
        if (w.time > 0.25) { sum += w.bodies.velocity[0].x(); ++n; }
    }
    return sum / double(n) / v0;
}

// Two boxes of elastic balls (no damping, no friction). `packed`: a lattice
// squeezed by walls 5 % of a radius inside its extent, brought to equilibrium
// with local damping, then damping off and random velocities of 0.01 m/s:
// contacts persist, so a symplectic integrator must show no secular drift.
// Not packed: a dilute gas at 1 m/s, where every contact onset costs an
// O((ω dt)²) energy error of random sign. Energies are relative to the
// energy that moves (E0 minus the static strain of the squeezed packing).
EnergyRecord energy_drift(int dim, double fraction, long steps, bool packed) {
    const double r = 0.01, n_side = 8;
    const double extent = packed ? 2 * r * n_side : (dim == 2 ? 0.2 : 0.1);
    const double squeeze = packed ? 0.05 * r : 0.0;
    const double margin = packed ? 0.0 : 0.005;
    json lattice = {{"type", "lattice"}, {"packing", dim == 2 ? "square" : "cubic"},
                    {"box", {{"min", vec(dim, margin, margin, margin)},
                             {"max", vec(dim, extent - margin, extent - margin, extent - margin)}}},
                    {"radius", r}, {"spacing", packed ? 2 * r : 2.5 * r}, {"density", 2500},
                    {"local_damping", packed ? 0.7 : 0.0},
                    {"jitter", {{"position", packed ? 0.0 : 0.1 * r}, {"velocity", packed ? 0.0 : 1.0}, {"seed", 7}}}};
    json scene = {{"dimension", dim},
                  {"plugins", {"linear"}},
                  {"bodies", {lattice}},
                  {"walls", {{{"type", "box"}, {"min", vec(dim, squeeze, squeeze, squeeze)},
                              {"max", vec(dim, extent - squeeze, extent - squeeze, extent - squeeze)}}}},
                  {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"},
                                       {"properties", {{"kn", 1e5}, {"ks", 0}, {"fric", 0}}}}}}};
    auto sim = make(scene);
    World& w = sim->world();
    w.prepare();
    w.fixed_dt = fraction * w.nominal_timestep().critical;
    double static_strain = 0;
    if (packed) {
        while (w.unbalanced_force_ratio() > 1e-9) w.step();
        static_strain = w.energies.strain;
        Rng rng(11);
        for (std::size_t i = 0; i < w.bodies.size(); ++i) {
            w.bodies.local_damping[i] = 0;
            w.bodies.velocity[i].setZero();
            for (int c = 0; c < dim; ++c) w.bodies.velocity[i][c] = rng.uniform(-0.01, 0.01);
        }
        w.mark_dirty();
        w.prepare();
        w.energies = Energies{w.energies.kinetic, w.energies.strain};
    }
    auto total = [&]() { return w.energies.kinetic + w.energies.strain - w.energies.boundary - static_strain; };
    const double e0 = total();
    const long window = std::max(1L, steps / 10);
    double first = 0, last = 0, worst = 0;
    for (long k = 0; k < steps; ++k) {
        w.step();
        const double e = total();
        worst = std::max(worst, std::fabs(e - e0) / e0);
        if (k < window) first += e;
        if (k >= steps - window) last += e;
    }
    return {std::fabs(last - first) / double(window) / e0, worst};
}

} // namespace plab::cases

namespace {

using namespace plab;
using namespace plab::cases;

std::string line(const char* fmt, double a, double b, double c, double d = 0) {
    char buf[200];
    std::snprintf(buf, sizeof buf, fmt, a, b, c, d);
    return buf;
}

PLAB_VALIDATION_CASE("energy_conservation",
                     "elastic balls in a box, no damping or friction: no secular energy drift with persistent "
                     "contacts; second-order fall of the leapfrog error with dt",
                     [](bool quick) {
    const long steps = quick ? 20000 : 100000;
    CaseResult r{0, 1e-4, "relative energy drift of the packed box (mean of last vs first 10 % of the run) at 0.1 x critical", ""};
    for (int dim : {2, 3}) {
        const EnergyRecord a = energy_drift(dim, 0.1, steps, true), b = energy_drift(dim, 0.05, 2 * steps, true);
        r.error = std::max(r.error, a.drift);
        char buf[300];
        std::snprintf(buf, sizeof buf,
                      "    %dD packed: drift %.3g at 0.1 dt_crit, %.3g at 0.05; max fluctuation %.3g and %.3g (ratio %.2f)\n",
                      dim, a.drift, b.drift, a.max_fluctuation, b.max_fluctuation, a.max_fluctuation / b.max_fluctuation);
        r.details += buf;
    }
    for (int dim : {2, 3}) {
        const long gas_steps = steps / 5;
        const EnergyRecord a = energy_drift(dim, 0.1, gas_steps, false), b = energy_drift(dim, 0.05, 2 * gas_steps, false);
        char buf[300];
        std::snprintf(buf, sizeof buf,
                      "    %dD gas (collisions): drift %.3g at 0.1 dt_crit, %.3g at 0.05 (ratio %.2f) over %ld / %ld steps\n",
                      dim, a.drift, b.drift, a.drift / b.drift, gas_steps, 2 * gas_steps);
        r.details += buf;
    }
    return r;
});

} // namespace
