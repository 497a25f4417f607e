// Validation case `gate_fracture` (thesis §7.4, Figs. 28–29): the elastic
// gate's set-up with the gate clamped at the bottom, its top free, no rigid
// plate, and a lowered strength, so that the water's bending moment breaks it
// near the clamp (thesis: at about 0.12 s) and the pieces travel with the flow.
// No reference data: the case checks what the thesis reports — the gate
// breaks first near the clamp, at about 0.12 s, and nothing passes through
// the walls.
//
// Why it broke at 0.001 s before (docs/coupling.md has the measurements):
//  * the quick gate (R 1.25 mm) had rows of 2-1-2 balls across its 5 mm: a
//    chain of triangles joined at single balls, a hinge at the clamp that
//    only the (ν = 0.33: 1 %) shear springs hold; it sheared within 1 ms.
//    A gate needs three balls across (R <= 5/6 mm) — refused otherwise;
//  * structure_sph_state mode 1 puts each ball's F/m — its bond vibration,
//    ~1e4 m/s² — into the gate's pressure: the free-standing gate's balls fell
//    below 0.75 ρ0 within 20 ms with unbreakable bonds. Mode 2 leaves it out;
//  * with both fixed, the clamp's bond stresses grow smoothly as the water
//    bends the gate, to a peak at 0.11–0.14 s (the same with R 0.625 and
//    0.83 mm): the break time is the time that load reaches the strength.
//    The thesis gives no strength; it says it was lowered so that the water
//    breaks the gate. Here sigma_ult = 1.4e6 Pa puts the calibrated bond shear
//    strength (eq. 44, 0.0037 sigma_ult at ν 0.33 = 5.2 kPa) just below that
//    peak: the flow's peak load breaks the gate, its earlier load does not.
//
// Walls for broken pieces (thesis §7.4 gives DEM balls a stronger repulsion
// from the boundary particles than fluid balls get): here the boundary
// balls meet the gate's balls through a `linear` contact (kn 1e5 N/m, far
// stiffer than the SPH boundary force), assigned to gate × boundary.
#include "coupling_cases.hpp"

#include "../simulation.hpp"
#include "../validation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <stdexcept>
#include <string>

namespace plab::cases {

namespace {
constexpr double gate_x0 = 0.1, gate_x1 = 0.105, gate_l = 0.079, tank_l = 0.5;
}

json gate_fracture_scene(const GateFractureSpec& s) {
    ElasticGateSpec e;
    e.spacing = s.spacing;
    e.gate_radius = s.gate_radius;
    e.end_time = s.end_time;
    e.pressure_mode = s.pressure_mode;
    if (6 * s.gate_radius > gate_x1 - gate_x0 + 1e-12)
        throw std::invalid_argument("gate_fracture: gate radius " + std::to_string(s.gate_radius) +
                                    " m leaves fewer than three balls across the 5 mm gate (a hinge chain); use R <= 5/6 mm");
    json scene = elastic_gate_scene(e);
    const double R = s.gate_radius;
    scene["description"] =
        "Gate fracture (thesis 7.4, Fig. 28): the elastic gate set-up with the gate clamped at the bottom, free at the "
        "top, no rigid plate, strength lowered so that the water breaks it near the clamp; gate balls meet the "
        "boundary balls through a stiff linear contact so pieces cannot pass through the walls. plab validate "
        "gate_fracture.";
    json bodies = json::array();
    for (const json& b : scene["bodies"]) {
        const bool rigid_plate = b["group"] == "boundary" && b["box"]["min"][0].get<double>() == gate_x0;
        if (rigid_plate) continue;
        bodies.push_back(b);
    }
    bodies.back()["box"]["max"][1] = gate_l;  // the gate: free top at 0.079 m
    scene["bodies"] = bodies;
    for (json& rule : scene["contact_models"])
        if (rule["model"] == "linear_pbond") rule["calibrate"]["sigma_ult"] = s.strength;
    scene["contact_models"].push_back({{"groups", {"gate", "boundary"}},
                                       {"model", "linear"},
                                       {"properties", {{"kn", 1e5}, {"ks", 1e5}, {"fric", 0.3}, {"dp_nratio", 0.5}}}});
    scene["plugins"].push_back("linear");
    // clamp: the two bottom rows (centres at R and R + √3 R)
    scene["commands"][1]["set"]["region"] = {{"min", {gate_x0, -R}}, {"max", {gate_x1, 2.8 * R}}};
    scene["histories"]["record"].push_back({{"name", "broken"}, {"quantity", "bonds.broken"}});
    if (s.density_band > 0)
        for (json& pass : scene["passes"])
            if (pass["name"] == "sph_eos") pass["properties"]["density_band"] = s.density_band;
    return scene;
}

GateFractureResult gate_fracture(const GateFractureSpec& s) {
    json scene = gate_fracture_scene(s);
    scene.erase("commands");
    scene.erase("histories");
    scene.erase("output");
    Simulation sim(scene);
    sim.set_quiet(true);
    World& w = sim.world();
    const int gate = w.find_group("gate");
    const double R = s.gate_radius;
    for (std::size_t i = 0; i < w.bodies.size(); ++i)
        if (w.bodies.group[i] == gate && w.bodies.position[i].y() < 2.8 * R) w.bodies.fixity[i] = 63;
    GateFractureResult r;
    r.bonds = long(w.bond(gate, gate, 1e-9));
    const std::clock_t c_start = std::clock();
    r.min_x = r.min_y = 1e300;
    r.max_x = -1e300;
    while (w.time < s.end_time) {
        w.step();
        for (std::size_t i = 0; i < w.bodies.size(); ++i) {
            if (w.bodies.group[i] != gate) continue;
            const Vec& x = w.bodies.position[i];
            r.min_x = std::min(r.min_x, x.x());
            r.max_x = std::max(r.max_x, x.x());
            r.min_y = std::min(r.min_y, x.y());
        }
    }
    r.cpu_seconds = double(std::clock() - c_start) / CLOCKS_PER_SEC;
    r.steps = long(w.step_count);
    r.broken = long(w.bond_breaks.size());
    if (!w.bond_breaks.empty()) {
        r.first_break_time = w.bond_breaks.front().time;
        r.first_break_y = w.bond_breaks.front().point.y();
        r.first_break_mode = w.bond_breaks.front().mode;
    }
    r.penetrated = r.min_x < 0 || r.min_y < 0 || r.max_x > tank_l;
    return r;
}

} // namespace plab::cases

namespace {

using namespace plab;
using namespace plab::cases;

// Pass: the first bond breaks within 0.02 m of the clamp at 0.12 ± 0.05 s
// (thesis: "at time around 0.12 s"), and no gate ball's centre crosses a
// wall surface. The error figure is |t_break - 0.12 s| in s (tolerance
// 0.05 s), 1 when nothing broke, not at the clamp, or a piece crossed a wall.
// Full: dp 2.5 mm, R 0.625 mm (thesis: four balls across), 0.2 s; quick:
// dp 5 mm, R 0.83 mm (three across), 0.12 s.
PLAB_VALIDATION_CASE("gate_fracture",
                     "SPH-DEM fluid-structure with fracture (thesis 7.4): bottom-clamped gate breaks near the clamp at "
                     "~0.12 s, pieces stay inside the walls",
                     [](bool quick) {
    GateFractureSpec s;
    if (quick) { s.spacing = 0.005; s.gate_radius = 0.005 / 6; s.end_time = 0.12; }
    // full: the break releases the clamp's stored energy and throws water at
    // 4.3 m/s (2.6 sqrt(2gH), c0 only 3.8 times that): a ball reaches
    // 1.05 rho0 at 0.1197 s, 0.7 ms after the first break; (v/c0)^2 = 0.07
    else s.density_band = 0.1;
    const GateFractureResult t = gate_fracture(s);
    const bool at_clamp = t.broken > 0 && t.first_break_y < 0.02;
    CaseResult r{at_clamp && !t.penetrated ? std::fabs(t.first_break_time - 0.12) : 1.0, 0.05,
                 "|first break time - 0.12 s| (thesis), s; 1 when it does not break at the clamp or a piece crosses a wall",
                 ""};
    char buf[600];
    std::snprintf(buf, sizeof buf,
                  "    dp %.4g m, gate R %.4g m, strength %.3g Pa, pressure_mode %d, density band %.2f, t = %.2f s, %ld steps, "
                  "%.1f s CPU\n"
                  "    %ld of %ld bonds broke; first at t = %.3f s (thesis ~0.12 s), y = %.4f m, in %s; gate balls x in "
                  "[%.4f, %.4f] m, lowest y %.4f m (walls at x = 0, %.1f m, floor y = 0)\n",
                  s.spacing, s.gate_radius, s.strength, s.pressure_mode, s.density_band > 0 ? s.density_band : 0.05,
                  s.end_time, t.steps, t.cpu_seconds, t.broken,
                  t.bonds, t.first_break_time, t.first_break_y, t.first_break_mode == 2 ? "shear" : "tension", t.min_x,
                  t.max_x, t.min_y, 0.5);
    r.details = buf;
    return r;
});

} // namespace
