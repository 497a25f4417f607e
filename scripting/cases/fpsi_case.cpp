// Validation case `fpsi` — fluid, particles and a structure (thesis §7.5,
// Figs. 30–31): the two-phase dam break (two_phase_dam_break_case.cpp:
// water 0.05 × 0.1 m, a bed of 180 grains) with the lifted gate replaced by
// a bottom-fixed breakable plate, the elastic gate's rubber (E 12 MPa,
// ν 0.33, ρ 1100; §7.5 gives only its density, 1100) 0.079 m tall and
// 0.005 m thick at x = a, clamped by its two bottom rows.
//
// Interactions: fluid × structure `sph` with structure_sph_state (mode 2,
// gate_fracture_case.cpp says why); fluid × grains the unresolved coupling;
// grains × structure and grains × walls `linear` (thesis §7.5: "same linear
// contact model ... used in particle-particle interaction"); grains × grains
// `linear_lubrication`; structure × walls a stiff `linear` (thesis §7.4).
//
// Strength: "the tensile strength of parallel bonds is set as 4.0e4 Pa and
// 2.0e4 Pa in Case I and II". The thesis names no shear strength; both
// pb_ten and pb_coh take the stated value (with the hexagonal calibration's
// eq. 44 the shear strength would be 0.6 % of it at ν 0.33 and every bond at
// the clamp would shear at once). The bond stress is Fn/A (pb_mcf = β̄ = 0),
// as the thesis sets it (§3.3.3, under eq. 50). Stiffness: the hexagonal
// calibration of the rubber (eqs. 36-42); its bond normal stiffness
// A k̄n = Kn/1.01 = 1.024e7 N/m is the thesis's "1.024e7" (its "1.021e9" fits
// no radius of this plate).
//
// Why the first bond breaks at 5-17 ms, not at 0.1 s (docs/coupling.md has
// the measurements): the plate holds the 0.1 m column from t = 0. Its static
// clamp bending stress, 6 M / t² with M = ρ g (H L²/2 - L³/3), is 348 kPa,
// 9 and 17 times the strengths; the step load builds the clamp moment within
// milliseconds, and a crack opens at the clamp's upstream face (tension) as
// soon as Fn/A passes the strength. Not noise, vibration, gravity (0.85 kPa)
// or a hinge lattice: the stress rises smoothly, the same with three and four
// balls across and in pressure modes 0 and 2. The thesis reports no
// first-break time, only frames at 0.05 s (both plates deform) and 0.1 s (case
// II has failed, case I has cracks near the bottom); case II parts from its
// clamp at 0.042 s at full resolution (reported, not judged: the plate's size
// is the elastic gate's, as the thesis's Fig. 30 is not in its text). Its own
// coupling (p = 0 on structure balls, mode 0) pushes with about half the
// pressure, and with it the weak plate is still one piece at 0.1 s. With
// β̄ = 1 the clamp row parts within 4-12 ms and the plate stands loose on it.
//
// The thesis: case II "breaks into more small pieces"; case I "has more
// cracks near the bottom end" and the fluid overpasses it. The case asserts
// the first: more fragments (pieces joined by intact bonds) in case II than
// in case I, and that both break and nothing crosses a wall.
#include "coupling_cases.hpp"

#include "../simulation.hpp"
#include "../validation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace plab::cases {

namespace {
constexpr double a = 0.05, gate_t = 0.005, gate_l = 0.079, tank_l = 0.2;
constexpr double rubber_rho = 1100.0, rubber_E = 12e6, rubber_nu = 0.33;
constexpr int gate_group = 2, grain_group = 3;  // the order the bodies name them (fluid 0, boundary 1)
}

json fpsi_scene(const FpsiSpec& s) {
    if (6 * s.gate_radius > gate_t + 1e-12)
        throw std::invalid_argument("fpsi: structure radius " + std::to_string(s.gate_radius) +
                                    " m leaves fewer than three balls across the 5 mm plate; use R <= 5/6 mm");
    TwoPhaseDamBreakSpec d;
    d.spacing = s.spacing;
    d.end_time = s.end_time;
    json scene = two_phase_dam_break_scene(d);
    const double R = s.gate_radius, dp = s.spacing, h = 1.25 * dp;
    // bodies: fluid, three wall blocks, (the gate block: dropped), the plate, then the grains
    json bodies = json::array();
    for (int k = 0; k < 4; ++k) bodies.push_back(scene["bodies"][k]);
    bodies.push_back({{"type", "lattice"}, {"group", "structure"}, {"packing", "hexagonal"},
                      {"box", {{"min", {a, 0}}, {"max", {a + gate_t, gate_l}}}}, {"radius", R},
                      {"density", rubber_rho * 2 * std::sqrt(3.0) / M_PI}});  // each hexagonal cell carries 1100 kg/m3
    for (std::size_t k = 5; k < scene["bodies"].size(); ++k) bodies.push_back(scene["bodies"][k]);
    scene["bodies"] = bodies;
    scene["description"] =
        "Fluid-particle-structure (thesis 7.5): the two-phase dam break with the gate replaced by a bottom-fixed "
        "breakable rubber plate 0.079 x 0.005 m (bond strength 4e4 Pa case I, 2e4 Pa case II); grains meet the "
        "plate through linear contacts. plab validate fpsi.";
    scene["plugins"].push_back("linear_pbond");
    scene["plugins"].push_back("coupling_fluid_structure");
    json& rules = scene["contact_models"];
    const json sph = rules[1]["properties"];  // the fluid x wall settings, without δ-SPH
    const json grain_contact = rules[4]["properties"];
    rules.push_back({{"groups", {"fluid", "structure"}}, {"model", "sph"}, {"properties", sph}});
    rules.push_back({{"groups", {"structure", "structure"}}, {"model", "linear_pbond"},
                     {"calibrate", {{"method", "hexagonal_2d"}, {"E", rubber_E}, {"nu", rubber_nu}, {"sigma_ult", 1e9}, {"radius", R}}},
                     {"properties", {{"pb_ten", s.bond_strength}, {"pb_coh", s.bond_strength}, {"pb_mcf", s.moment_factor}}}});
    rules.push_back({{"groups", {"grains", "structure"}}, {"model", "linear"}, {"properties", grain_contact}});
    rules.push_back({{"groups", {"structure", "boundary"}}, {"model", "linear"},
                     {"properties", {{"kn", 1e5}, {"ks", 1e5}, {"fric", 0.3}, {"dp_nratio", 0.5}}}});
    for (json& pass : scene["passes"])
        if (pass["name"] == "fluid_particle_drag") pass["properties"]["solid_group"] = grain_group;
    json state = {{"rest_density", 1000.0}, {"speed_of_sound", sph["speed_of_sound"]}, {"gamma", 7.0},
                  {"smoothing_length", h}, {"kernel", 0}, {"structure_group", gate_group}, {"fluid_group", 0},
                  {"pressure_mode", s.pressure_mode}, {"gravity_y", -9.81}};
    scene["passes"].push_back({{"name", "structure_sph_state"}, {"properties", state}});
    scene["histories"]["record"].push_back({{"name", "broken"}, {"quantity", "bonds.broken"}});
    if (s.density_band > 0)
        for (json& pass : scene["passes"])
            if (pass["name"] == "sph_eos") pass["properties"]["density_band"] = s.density_band;
    // clamp: the two bottom rows (centres at R and R + √3 R)
    scene["commands"] = {{{"bond", {{"groups", {"structure", "structure"}}, {"gap", 1e-9}}}},
                         {{"set", {{"region", {{"min", {a, -R}}, {"max", {a + gate_t, 2.8 * R}}}}, {"fix", {"all"}}}}},
                         {{"solve", {{"time", s.end_time}}}}};
    return scene;
}

namespace {

// Pieces of the structure joined by intact bonds (union-find over the bonded
// contacts of `linear_pbond`): the count and the largest piece's size.
std::pair<int, int> fragments(const World& w, int group) {
    std::vector<std::size_t> parent(w.bodies.size());
    std::iota(parent.begin(), parent.end(), 0);
    std::function<std::size_t(std::size_t)> root = [&](std::size_t i) {
        return parent[i] == i ? i : parent[i] = root(parent[i]);
    };
    for (const auto& inst : w.instances()) {
        if (inst->model != "linear_pbond" || inst->desc->persist_slot < 0) continue;
        const ContactSet& c = inst->balls;
        for (std::size_t k = 0; k < c.size(); ++k)
            if (c.history[k * inst->stride + inst->desc->persist_slot] > 0)
                parent[root(std::size_t(c.end1[k]))] = root(std::size_t(c.end2[k]));
    }
    std::vector<int> size(w.bodies.size(), 0);
    int pieces = 0, largest = 0;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        if (w.bodies.group[i] != group) continue;
        if (size[root(i)]++ == 0) ++pieces;
        largest = std::max(largest, size[root(i)]);
    }
    return {pieces, largest};
}

// The largest bond stresses of the intact bonds now (eqs. 49-50 in 2D, from
// the bond force and moment the model keeps in its history).
BondStressSample bond_stress(const World& w) {
    BondStressSample b;
    b.t = w.time;
    for (const auto& inst : w.instances()) {
        if (inst->model != "linear_pbond") continue;
        const double rmul = inst->property("pb_rmul");
        const int fn_slot = inst->history_slot("bond_normal_force"), fs_slot = inst->history_slot("bond_shear_force_x"),
                  m_slot = inst->history_slot("bond_moment_x");
        const ContactSet& c = inst->balls;
        for (std::size_t k = 0; k < c.size(); ++k) {
            const double* h = &c.history[k * inst->stride];
            if (h[inst->desc->persist_slot] <= 0) continue;
            const std::size_t i = std::size_t(c.end1[k]), j = std::size_t(c.end2[k]);
            const double r = rmul * std::min(w.bodies.radius[i], w.bodies.radius[j]);
            const double area = 2 * r, inertia = 2 * r * r * r / 3;  // 2D, unit thickness (eq. 39)
            const double axial = h[fn_slot] / area;
            const double moment = std::sqrt(h[m_slot] * h[m_slot] + h[m_slot + 1] * h[m_slot + 1] + h[m_slot + 2] * h[m_slot + 2]);
            const double shear = std::sqrt(h[fs_slot] * h[fs_slot] + h[fs_slot + 1] * h[fs_slot + 1] + h[fs_slot + 2] * h[fs_slot + 2]);
            b.sigma_axial = std::max(b.sigma_axial, axial);
            b.tau = std::max(b.tau, shear / area);
            if (axial + moment * r / inertia > b.sigma) {
                b.sigma = axial + moment * r / inertia;
                b.x = 0.5 * (w.bodies.position[i].x() + w.bodies.position[j].x());
                b.y = 0.5 * (w.bodies.position[i].y() + w.bodies.position[j].y());
            }
        }
    }
    return b;
}

} // namespace

FpsiResult fpsi(const FpsiSpec& s) {
    json scene = fpsi_scene(s);
    scene.erase("commands");
    scene.erase("histories");
    scene.erase("output");
    Simulation sim(scene);
    sim.set_quiet(true);
    World& w = sim.world();
    const int plate = w.find_group("structure"), grains = w.find_group("grains");
    if (plate != gate_group || grains != grain_group) throw std::logic_error("fpsi: group order changed");
    FpsiResult r;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        r.structure += w.bodies.group[i] == plate;
        r.grains += w.bodies.group[i] == grains;
        if (w.bodies.group[i] == plate && w.bodies.position[i].y() < 2.8 * s.gate_radius) w.bodies.fixity[i] = 63;
    }
    r.bonds = long(w.bond(plate, plate, 1e-9));
    std::size_t tip = 0;  // the top ball nearest the plate's mid-line
    for (std::size_t i = 0; i < w.bodies.size(); ++i)
        if (w.bodies.group[i] == plate && (w.bodies.group[tip] != plate || w.bodies.position[i].y() > w.bodies.position[tip].y() + 1e-9 ||
                                           (w.bodies.position[i].y() > w.bodies.position[tip].y() - 1e-9 &&
                                            std::fabs(w.bodies.position[i].x() - a - 0.5 * gate_t) <
                                                std::fabs(w.bodies.position[tip].x() - a - 0.5 * gate_t))))
            tip = i;
    const double tip_x0 = w.bodies.position[tip].x();
    double next_probe = 0;
    std::size_t breaks_seen = 0;
    const std::clock_t c_start = std::clock();
    while (w.time < s.end_time) {
        w.step();
        if (r.failure_time < 0 && w.bond_breaks.size() > breaks_seen) {  // pieces change only when a bond breaks
            breaks_seen = w.bond_breaks.size();
            if (fragments(w, plate).first > 1) r.failure_time = w.time;
        }
        if (s.probe_interval > 0 && w.time >= next_probe) {
            r.probes.push_back(bond_stress(w));
            r.probes.back().tip_dx = w.bodies.position[tip].x() - tip_x0;
            r.probes.back().broken = long(w.bond_breaks.size());
            std::tie(r.probes.back().fragments, r.probes.back().largest_fragment) = fragments(w, plate);
            next_probe += s.probe_interval;
        }
        for (std::size_t i = 0; i < w.bodies.size(); ++i) {
            if (w.bodies.group[i] != plate) continue;
            const Vec& x = w.bodies.position[i];
            r.penetrated = r.penetrated || x.x() < 0 || x.y() < 0 || x.x() > tank_l;
        }
    }
    r.cpu_seconds = double(std::clock() - c_start) / CLOCKS_PER_SEC;
    r.steps = long(w.step_count);
    r.broken = long(w.bond_breaks.size());
    if (!w.bond_breaks.empty()) {
        r.first_break_time = w.bond_breaks.front().time;
        r.first_break_x = w.bond_breaks.front().point.x();
        r.first_break_y = w.bond_breaks.front().point.y();
        r.first_break_mode = w.bond_breaks.front().mode;
    }
    std::tie(r.fragments, r.largest_fragment) = fragments(w, plate);
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        if (w.bodies.group[i] != grains) continue;
        const Vec& x = w.bodies.position[i];
        r.grains_lost += x.x() < 0 || x.x() > tank_l || x.y() < 0;
    }
    return r;
}

} // namespace plab::cases

namespace {

using namespace plab;
using namespace plab::cases;

// Pass (the criteria): both plates break, case II (2e4 Pa) ends in
// more pieces than case I (4e4 Pa), and no structure ball or grain leaves
// the tank; the error is 0, else 1. Reported, not judged: when case II
// falls apart (its balls first form two pieces joined by intact bonds: the
// plate parts from its two clamp rows) against the thesis's "fails around
// 0.1 s". That time depends on the plate's size, which the thesis gives only
// in its Fig. 30 (not in the text); this case takes the elastic gate's plate,
// which holds the 0.1 m head from t = 0 at 9-17 times its strengths and
// parts from its clamp at 0.042 s (full), 0.050 s (quick); docs/coupling.md.
// Full: dp 2.5 mm, R 0.625 mm (four balls across), 0.2 s (thesis). Quick
// (CI): dp 5 mm, R 0.83 mm (three across), 0.1 s.
PLAB_VALIDATION_CASE("fpsi",
                     "SPH-DEM fluid-particle-structure (thesis 7.5): two-phase dam break against a bottom-fixed breakable "
                     "plate; the weaker plate (case II) breaks into more pieces",
                     [](bool quick) {
    FpsiResult out[2];
    CaseResult r{0, 0.5,
                 "0 when both plates break, case II ends in more pieces than case I and nothing leaves the tank, else 1 "
                 "(the time case II falls apart is reported against the thesis's ~0.1 s)",
                 ""};
    const double strengths[2] = {4e4, 2e4};
    for (int k = 0; k < 2; ++k) {
        FpsiSpec s;
        s.bond_strength = strengths[k];
        if (quick) { s.spacing = 0.005; s.gate_radius = 0.005 / 6; s.end_time = 0.1; }
        // full, case II: the pieces throw water at 1.6 m/s (c0 = 8.75 times that), a ball reaches
        // 1.05 rho0 at 0.199 s; as gate_fracture's full run, a 10 % band
        else s.density_band = 0.1;
        out[k] = fpsi(s);
        const FpsiResult& t = out[k];
        char buf[600];
        std::snprintf(buf, sizeof buf,
                      "    case %s (strength %.1e Pa, pb_mcf %.0f): dp %.4g m, R %.4g m, t = %.2f s: %ld of %ld bonds broke "
                      "(first at %.4f s, x %.4f y %.4f m, in %s), fell apart at %.4f s (thesis case II ~0.1 s), %d pieces "
                      "(largest %d of %d balls); %d of %d grains left the tank; %ld steps, %.1f s CPU\n",
                      k == 0 ? "I" : "II", s.bond_strength, s.moment_factor, s.spacing, s.gate_radius, s.end_time, t.broken,
                      t.bonds, t.first_break_time, t.first_break_x, t.first_break_y,
                      t.first_break_mode == PLAB_BREAK_SHEAR ? "shear" : "tension", t.failure_time, t.fragments, t.largest_fragment,
                      t.structure, t.grains_lost, t.grains, t.steps, t.cpu_seconds);
        r.details += buf;
    }
    for (const FpsiResult& t : out)
        if (t.broken == 0 || t.penetrated || t.grains_lost > 0) r.error = 1;
    if (out[1].fragments <= out[0].fragments || out[1].failure_time < 0) r.error = 1;
    return r;
});

} // namespace
