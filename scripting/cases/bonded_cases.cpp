// Bonded-structure validation: the thesis cantilever (§6.2, Tables 4–6) and
// robustness of a plate hit by a fast ball.
#include "bonded_cases.hpp"

#include "../simulation.hpp"
#include "../validation.hpp"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <vector>

namespace plab::cases {

namespace {

// thesis Table 4
constexpr double kLength = 0.201, kE = 70e9, kNu = 0.33, kSigmaUlt = 310e6, kDensity = 2800, kHeight = 0.006196;
const double kSqrt3 = std::sqrt(3.0);

int rows_for(double r) { return int(std::lround((kHeight - 2 * r) / (kSqrt3 * r))) + 1; }
double height_of(double r, int rows) { return 2 * r + (rows - 1) * kSqrt3 * r; }

// The beam: a hexagonal lattice bonded with the thesis calibration, the
// left end (ball centres within clamp_depth·R of x = 0) clamped.
std::unique_ptr<Simulation> beam(double r, const json& damping, const StrengthRule& rule, double clamp_depth) {
    const int rows = rows_for(r);
    json lattice = {{"type", "lattice"}, {"group", "beam"}, {"packing", "hexagonal"},
                    {"box", {{"min", {0, 0}}, {"max", {kLength, height_of(r, rows) + 0.01 * r}}}},
                    {"radius", r}, {"density", kDensity}};
    lattice.update(damping);
    json calibrate = {{"method", "hexagonal_2d"}, {"E", kE}, {"nu", kNu}, {"sigma_ult", kSigmaUlt}, {"radius", r},
                      {"tension", rule.tension}};
    if (rule.tau_ult > 0) calibrate["tau_ult"] = rule.tau_ult;
    json scene = {{"dimension", 2},
                  {"plugins", {"linear_pbond"}},
                  {"bodies", {lattice}},
                  {"contact_models", {{{"groups", {"beam", "beam"}}, {"model", "linear_pbond"},
                                       {"calibrate", calibrate},
                                       {"properties", {{"pb_mcf", rule.moment_factor}}}}}},
                  {"timestep", {{"safety_factor", 0.8}}}};
    auto sim = std::make_unique<Simulation>(scene);
    sim->set_quiet(true);
    World& w = sim->world();
    w.bond(w.find_group("beam"), w.find_group("beam"), 1e-9 * r);
    for (std::size_t i = 0; i < w.bodies.size(); ++i)
        if (w.bodies.position[i].x() < clamp_depth * r) w.bodies.fixity[i] = 63;
    w.mark_dirty();
    return sim;
}

// Where the clamped material ends, averaged over the rows: the clamp line of
// the equivalent continuum beam (each row's last fixed centre + R).
double clamp_line(const World& w, double r, int rows) {
    std::vector<double> face(rows, 0.0);
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        if (w.bodies.fixity[i] != 63) continue;  // clamped: every degree of freedom
        const int row = int(std::lround((w.bodies.position[i].y() - r) / (kSqrt3 * r)));
        if (row >= 0 && row < rows) face[row] = std::max(face[row], w.bodies.position[i].x() + r);
    }
    double sum = 0;
    for (double f : face) sum += f;
    return sum / rows;
}

int tip_index(const World& w) {
    int tip = 0;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        const Vec& p = w.bodies.position[i];
        const Vec& q = w.bodies.position[tip];
        if (p.y() < q.y() - 1e-12 || (std::fabs(p.y() - q.y()) <= 1e-12 && p.x() > q.x())) tip = int(i);
    }
    return tip;
}

// Mass-proportional damping at twice the first bending frequency
// ω1 = 1.875² √(EI / (m' L⁴)): every mode then decays as fast as the first.
double critical_viscous_damping(double r) {
    const double h = height_of(r, rows_for(r));
    const double mass_per_length = kDensity * M_PI * r * r * (h / (kSqrt3 * r) + 0.5) / (2 * r);
    return 2 * 3.516 * std::sqrt(kE * h * h * h / 12 / (mass_per_length * std::pow(kLength, 4)));
}

// σ11 along the top and bottom rows against beam theory -M(x) (y - y_mid)/I,
// M(x) = P (x_tip - x), on the equivalent beam.
// Rows are picked by the balls' initial positions (the beam has deflected).
void fibre_stress(const World& w, const std::vector<Vec>& initial, Cantilever& c, double load, double x_tip) {
    const auto sigma = w.ball_stress();
    double y_min = kInf, y_max = -kInf;
    for (const Vec& p : initial) { y_min = std::min(y_min, p.y()); y_max = std::max(y_max, p.y()); }
    const double y_mid = 0.5 * (y_min + y_max);
    const double inertia = std::pow(c.equivalent_height, 3) / 12;
    const double cell = M_PI / (2 * kSqrt3);  // ball area / hexagonal cell area
    double diff2 = 0, ref2 = 0;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        const Vec& p = initial[i];
        const bool fibre = std::fabs(p.y() - y_min) < 0.1 * c.radius || std::fabs(p.y() - y_max) < 0.1 * c.radius;
        if (!fibre || p.x() < 0.2 * kLength || p.x() > 0.8 * kLength) continue;
        const double theory = -load * (x_tip - p.x()) * (p.y() - y_mid) / inertia;
        diff2 += std::pow(sigma[i](0, 0) * cell - theory, 2);
        ref2 += theory * theory;
    }
    c.fibre_stress_error = ref2 > 0 ? std::sqrt(diff2 / ref2) : 0;
    c.fibre_stress_scale = std::sqrt(ref2);
}

} // namespace

Cantilever static_cantilever(double r, double load, double ratio, const StrengthRule& rule, double clamp_depth) {
    const std::clock_t t0 = std::clock();
    auto sim = beam(r, {{"viscous_damping", critical_viscous_damping(r)}}, rule, clamp_depth);
    World& w = sim->world();
    Cantilever out;
    out.radius = r;
    out.rows = rows_for(r);
    out.balls = long(w.bodies.size());
    out.height = height_of(r, out.rows);
    const int tip = tip_index(w);
    const double y0 = w.bodies.position[tip].y();
    const std::vector<Vec> initial = w.bodies.position;
    w.bodies.enable_applied_loads();
    w.bodies.applied_force[tip] = Vec(0, load, 0);
    w.prepare();
    while (out.steps < 20000000) {
        for (int k = 0; k < 50; ++k) w.step();
        out.steps += 50;
        if (w.unbalanced_force_ratio() <= ratio) break;
    }
    out.deflection = w.bodies.position[tip].y() - y0;
    const double inertia = out.height * out.height * out.height / 12;
    out.analytical = load * std::pow(kLength, 3) / (3 * kE * inertia);
    out.strength_load = kSigmaUlt * out.height * out.height / (6 * kLength);
    out.clamp_line = clamp_line(w, r, out.rows);
    out.equivalent_height = out.rows * kSqrt3 * r;
    out.equivalent_length = w.bodies.position[tip].x() - out.clamp_line;
    const double inertia_eq = std::pow(out.equivalent_height, 3) / 12;
    out.analytical_equivalent = load * std::pow(out.equivalent_length, 3) / (3 * kE * inertia_eq);
    out.strength_load_equivalent = kSigmaUlt * out.equivalent_height * out.equivalent_height / (6 * out.equivalent_length);

    fibre_stress(w, initial, out, load, w.bodies.position[tip].x());

    // first break by linearity: the lattice is linear-elastic until a bond
    // breaks, in tension (eq. 49) or in shear (eq. 50, 2D: no twist)
    const ModelInstance& inst = *w.instances()[0];
    const int state = inst.history_slot("bond_state"), fn = inst.history_slot("bond_normal_force");
    const int fs = inst.history_slot("bond_shear_force_x");
    const int mz = inst.history_slot("bond_moment_z");
    const double sigma_c = inst.property("pb_ten"), tau_c = inst.property("pb_coh");
    double worst = 0, worst_centre = 0, worst_tension = 0, worst_shear = 0;
    const ContactSet& s = inst.balls;
    for (std::size_t k = 0; k < s.size(); ++k) {
        const double* h = &s.history[k * inst.stride];
        if (h[state] <= 0) continue;
        const double r_bar = std::min(w.end_radius(s, k, false), w.end_radius(s, k, true)) * inst.property("pb_rmul");
        const double area = 2 * r_bar, inertia = 2 * r_bar * r_bar * r_bar / 3;  // 2D strip, unit thickness
        const double centre = h[fn] / area;
        const double sigma = centre + rule.moment_factor * std::fabs(h[mz]) * r_bar / inertia;  // eq. 49
        const double tau = std::hypot(h[fs], h[fs + 1]) / area;                             // eq. 50
        worst_centre = std::max(worst_centre, centre / sigma_c);
        worst_tension = std::max(worst_tension, sigma / sigma_c);
        worst_shear = std::max(worst_shear, tau / tau_c);
        if (std::max(sigma / sigma_c, tau / tau_c) > worst) {
            worst = std::max(sigma / sigma_c, tau / tau_c);
            const Vec point = w.contact_point(s, k);
            out.break_x = point.x();
            out.break_y = point.y();
            out.break_in_tension = sigma / sigma_c >= tau / tau_c;
        }
    }
    out.first_break_load = worst > 0 ? load / worst : 0;
    out.first_break_load_centre = worst_centre > 0 ? load / worst_centre : 0;
    out.first_tension_break_load = worst_tension > 0 ? load / worst_tension : 0;
    out.first_shear_break_load = worst_shear > 0 ? load / worst_shear : 0;
    // the equivalent beam's stress at the bottom row's centre, (rows - 1) √3 R / 2
    // from the neutral axis, at the breaking bond reaches σ_ult under this load
    const double y_row = (out.rows - 1) * kSqrt3 * r / 2;
    out.row_strength_load = kSigmaUlt * inertia_eq / (y_row * (w.bodies.position[tip].x() - out.break_x));
    out.cpu_seconds = double(std::clock() - t0) / CLOCKS_PER_SEC;
    return out;
}

VelocityFailure velocity_failure(double r, double velocity, const StrengthRule& rule) {
    auto sim = beam(r, {{"local_damping", 0.7}}, rule, kClampDepth);
    World& w = sim->world();
    const int tip = tip_index(w);
    w.bodies.local_damping[tip] = 0;  // the reaction is then the contact force alone
    w.bodies.fixity[tip] |= dof_y;
    w.bodies.velocity[tip] = Vec(0, velocity, 0);
    w.mark_dirty();
    VelocityFailure out;
    while (w.bond_breaks.empty() && out.steps < 50000000) {
        w.step();
        ++out.steps;
    }
    out.reaction = -w.bodies.force[tip].y();
    if (!w.bond_breaks.empty()) {
        const BondBreak& b = w.bond_breaks.front();
        out.x = b.point.x();
        out.y = b.point.y();
        out.tension = b.mode == PLAB_BREAK_TENSION;
        out.time = b.time;
    }
    return out;
}

Impact plate_impact(double speed, double duration) {
    const double r = 0.001, projectile_r = 0.002, thickness = 0.0195;
    json scene = {
        {"dimension", 2},
        {"plugins", {"linear", "linear_pbond"}},
        {"bodies",
         {{{"type", "lattice"}, {"group", "plate"}, {"packing", "hexagonal"},
           {"box", {{"min", {0, 0}}, {"max", {0.08, thickness}}}}, {"radius", r}, {"density", 2400}},
          {{"type", "ball"}, {"group", "projectile"}, {"position", {0.04, thickness + projectile_r + 1e-4}},
           {"velocity", {0, -speed}}, {"radius", projectile_r}, {"density", 7800}}}},
        {"contact_models",
         {{{"groups", {"*", "*"}}, {"model", "linear"}, {"properties", {{"kn", 5e8}, {"ks", 5e8}, {"fric", 0.3}}}},
          {{"groups", {"plate", "plate"}}, {"model", "linear_pbond"},
           {"calibrate", {{"method", "hexagonal_2d"}, {"E", 30e9}, {"nu", 0.2}, {"sigma_ult", 30e6}, {"radius", r}}},
           {"properties", {{"fric", 0.3}}}}}},
        {"timestep", {{"safety_factor", 0.5}}}};
    Simulation sim(scene);
    sim.set_quiet(true);
    World& w = sim.world();
    const int plate = w.find_group("plate");
    Impact out;
    out.bonds = long(w.bond(plate, plate, 1e-9));
    for (std::size_t i = 0; i < w.bodies.size(); ++i)  // clamp both ends of the plate
        if (w.bodies.group[i] == plate && (w.bodies.position[i].x() < 2.5 * r || w.bodies.position[i].x() > 0.08 - 2.5 * r))
            w.bodies.fixity[i] = 63;
    w.prepare();
    const double e0 = w.energies.balance();
    out.input_energy = w.energies.kinetic;
    try {
        while (w.time < duration) w.step();
    } catch (const RunError&) {
        out.finite = false;
    }
    out.balance_error = std::fabs(w.energies.balance() - e0) / out.input_energy;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) out.max_speed = std::max(out.max_speed, w.bodies.velocity[i].norm());
    out.broken = long(w.bond_breaks.size());
    for (const BondBreak& b : w.bond_breaks)
        out.farthest_break = std::max(out.farthest_break, std::fabs(b.point.x() - 0.04));
    return out;
}

} // namespace plab::cases

namespace {

using namespace plab;
using namespace plab::cases;

PLAB_VALIDATION_CASE("cantilever",
                     "thesis 6.2: tip deflection vs P L^3/(3EI) for 50, 500, 5000 N and the first-break load vs "
                     "sigma_ult b h^2/(6L), against the continuum beam the lattice represents",
                     [](bool quick) {
    // 2 % for the 7-row beam and finer; the 3-row quick beam is coarse: 6 %
    CaseResult result{0, quick ? 0.06 : 0.02,
                      quick ? "relative error of the tip deflection vs the equivalent beam, R = 1 mm (first-break load "
                              "reported; judged by cantilever_failure)"
                            : "max relative error of the tip deflection vs the equivalent beam, R = 0.5 mm at three "
                              "loads and R = 0.25 mm (R = 1 mm reported; first-break load judged by cantilever_failure)",
                      ""};
    const double ratio = quick ? 1e-5 : 1e-7;
    char line[400];
    // full: R = 0.5 mm at three loads, then the resolution study at 5000 N
    std::vector<std::pair<double, double>> runs = {{0.0005, 50.0}, {0.0005, 500.0}, {0.0005, 5000.0},
                                                   {0.001, 5000.0}, {0.00025, 5000.0}};
    if (quick) runs = {{0.001, 5000.0}};
    for (const auto& [r, load] : runs) {
        const Cantilever c = static_cantilever(r, load, ratio);
        const double err = (c.deflection - c.analytical_equivalent) / c.analytical_equivalent;
        const double err_nominal = (c.deflection - c.analytical) / c.analytical;
        // judged: case 1 (R = 0.5 mm) and the finer beam; the issue's
        // resolution study asks for R = 1 mm's error to be reported
        if (quick || r <= 0.0005 + 1e-12) result.error = std::max(result.error, std::fabs(err));
        std::snprintf(line, sizeof line,
                      "    R %.2g mm, %d rows, %ld balls, P %5.0f N: tip deflection %.6g m; equivalent beam (L %.5f, h "
                      "%.6f) %.6g m, error %+.2f %%; nominal (L 0.201, h %.6f) %.6g m, error %+.2f %%; %ld steps, "
                      "cpu %.1f s\n",
                      r * 1e3, c.rows, c.balls, load, c.deflection, c.equivalent_length, c.equivalent_height,
                      c.analytical_equivalent, 100 * err, c.height, c.analytical, 100 * err_nominal, c.steps,
                      c.cpu_seconds);
        result.details += line;
        if (load == 5000.0) {
            const double ferr = (c.first_break_load - c.strength_load_equivalent) / c.strength_load_equivalent;
            const double ferr_nominal = (c.first_break_load - c.strength_load) / c.strength_load;
            std::snprintf(line, sizeof line,
                          "    first break (linear in P): %.1f N; equivalent beam %.1f N, error %+.2f %%; nominal "
                          "sigma_ult h^2/(6L) = %.1f N, error %+.2f %%; at x = %.4f m, y = %.4f m, in %s\n",
                          c.first_break_load, c.strength_load_equivalent, 100 * ferr, c.strength_load,
                          100 * ferr_nominal, c.break_x, c.break_y, c.break_in_tension ? "tension" : "shear");
            result.details += line;
            std::snprintf(line, sizeof line, "    sigma11 on the top and bottom fibres vs -M y / I: RMS error %.2f %%\n",
                          100 * c.fibre_stress_error);
            result.details += line;
        }
    }
    return result;
});

PLAB_VALIDATION_CASE("cantilever_failure",
                     "thesis 6.2 failure: the bottom tip ball driven upward (local damping 0.7) until the first bond "
                     "breaks; reaction vs sigma_ult b h^2/(6L)",
                     [](bool quick) {
    // Strength rule (docs/bonded-structures.md): the fibres are rows of bonds
    // along the tension, so the tensile strength is calibrated for tension
    // along the bonds, and beta = 1 in eq. 49 makes sigma the stress at the
    // bond's outer edge, which for the outermost row is the beam's surface,
    // where beam theory reaches sigma_ult. The shear strength is the
    // aluminium's (tau_ult 207 MPa): eq. 44 assumes 0.43 sigma_ult, with which
    // a row pulled to sigma_ult reaches its shear strength in the 60 degree
    // bonds at the same time, and the clamp's concentration then breaks a
    // bond in shear first at R = 0.5 mm (-19.6 %). The thesis's rule (eq. 43,
    // beta = 0) is reported beside it: it breaks ~20 % early.
    // 0.2 m/s (quick: on R = 1 mm): the load rises over > 10 periods of the first bending
    // mode, so the test is quasi-static; the thesis's 0.02 m/s needs 10x the steps for the same answer
    const double r = quick ? 0.001 : 0.0005, v = 0.2;
    const VelocityFailure f = velocity_failure(r, v, beam_fibre_rule());
    const Cantilever s = static_cantilever(r, 5000.0, quick ? 1e-5 : 1e-6, beam_fibre_rule());
    CaseResult result{std::fabs(f.reaction - s.strength_load) / s.strength_load, 0.05,
                      "relative error of the reaction at the first break vs sigma_ult b h^2/(6L)", ""};
    char line[600];
    std::snprintf(line, sizeof line,
                  "    R %.2g mm, %d rows, v %.2g m/s, strength for tension along the bonds, beta 1, tau_ult 207 MPa: first "
                  "break after "
                  "%ld steps (t = %.4f s) at x = %.4f m, y = %.4f m, in %s; reaction %.1f N vs %.1f N (%+.2f %%)\n",
                  r * 1e3, s.rows, v, f.steps, f.time, f.x, f.y, f.tension ? "tension" : "shear", f.reaction,
                  s.strength_load, 100 * (f.reaction / s.strength_load - 1));
    result.details = line;
    // The lattice is linear until the first break, so a static solve gives
    // the first-break load of both rules; the thesis's strength is (3 - nu)/4
    // of the along-the-bonds one (scripting/calibration.cpp).
    std::vector<double> radii = {r};
    if (!quick) radii = {0.001, 0.0005, 0.00025};
    for (double ri : radii) {
        const Cantilever c = ri == r ? s : static_cantilever(ri, 5000.0, 1e-6, beam_fibre_rule());
        const double thesis = c.first_break_load_centre * (3.0 - kNu) / 4.0;
        std::snprintf(line, sizeof line,
                      "    static, R %.2g mm, %d rows: first break %.1f N (%+.2f %%) at x = %.4f m, y = %.4f m, in %s "
                      "(first shear break %.1f N); thesis rule (eq. 43, beta 0) %.1f N (%+.2f %%); cpu %.0f s\n",
                      ri * 1e3, c.rows, c.first_break_load, 100 * (c.first_break_load / c.strength_load - 1), c.break_x,
                      c.break_y, c.break_in_tension ? "tension" : "shear", c.first_shear_break_load, thesis,
                      100 * (thesis / c.strength_load - 1), c.cpu_seconds);
        result.details += line;
    }
    // The issue: in tension, on the tension side (the bottom half under an
    // upward load), within two ball diameters of the clamp face.
    const double from_clamp = (f.x - s.clamp_line) / (2 * r);
    std::snprintf(line, sizeof line, "    first break %.2f ball diameters from the clamp face (x = %.4f m; limit 2)\n",
                  from_clamp, s.clamp_line);
    result.details += line;
    if (!quick) {  // the other clamp face: the outer rows reach R further into the span
        const Cantilever o = static_cantilever(r, 5000.0, 1e-6, beam_fibre_rule(), 3.2);
        std::snprintf(line, sizeof line,
                      "    clamp with the outer rows reaching further (centres < 3.2 R fixed), static: first break "
                      "%.1f N (%+.2f %%) at x = %.4f m, y = %.4f m, in %s, %.2f ball diameters from its clamp face "
                      "(x = %.4f m)\n",
                      o.first_break_load, 100 * (o.first_break_load / o.strength_load - 1), o.break_x, o.break_y,
                      o.break_in_tension ? "tension" : "shear", (o.break_x - o.clamp_line) / (2 * r), o.clamp_line);
        result.details += line;
    }
    if (!f.tension || f.y > 0.5 * s.height || from_clamp > 2.0) result.error = kInf;
    return result;
});

} // namespace
