// Validation case `elastic_gate` (thesis §7.3, Table 7; Antoci, Gallati &
// Sibilla 2007): a water column 0.1 m wide and 0.14 m high held by a rubber
// gate 0.079 m long and 0.005 m thick, clamped at its top; the free lower end
// opens under the water. Reference: the experiment's free-end displacement,
// validation/reference/antoci_2007_gate_tip.csv.
//
// Coupling (plug-in `coupling_fluid_structure`): the gate is a hexagonal
// packing of bonded balls (`linear_pbond`, hexagonal_2d calibration) that
// joins the SPH sums through the `sph` model assigned to fluid × gate, with
// its SPH pressure extrapolated from the fluid (`structure_sph_state`, mode 2:
// from the fluid's pressure and gravity, without the balls' own acceleration,
// which is their bond vibration and blew the full gate up in mode 1).
//
// Material: E = 12 MPa, rho = 1100 kg/m3 (Table 7) as the mass of the
// lattice's cells (ball density rho 2√3/π); nu = 0.33, the thesis's value and
// the largest the hexagonal calibration allows (nu < 1/3; Antoci's rubber is
// near 0.4-0.49). A 2D plate bends with E/(1 - nu²) in plane strain:
// 1.12 E at 0.33 against 1.19-1.31 E at 0.4-0.49, so the lattice gate is
// 6-15 % too soft in plane strain — the calibration is plane stress, as the
// thesis's.
#include "coupling_cases.hpp"
#include "sph_cases.hpp"

#include "../simulation.hpp"
#include "../validation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace plab::cases {

namespace {
constexpr double g = 9.81, rho_f = 1000.0, gamma_tait = 7.0;
constexpr double water_w = 0.1, water_h = 0.14, gate_l = 0.079, gate_t = 0.005, tank_l = 0.5, tank_h = 0.16;
constexpr double rubber_rho = 1100.0, rubber_E = 12e6, rubber_nu = 0.33;
constexpr int fluid_group = 0, boundary_group = 1, gate_group = 2;  // order of first naming

double sound_speed() { return 10.0 * std::sqrt(2 * g * water_h); }  // 10 v_max, v_max = sqrt(2 g H)

// Gate lattice rows: hexagonal packing, rows √3 R apart from y = R; the
// clamp is the rows whose centres lie above the gate length.
double gate_top(double R) { return gate_l + 3 * std::sqrt(3.0) * R; }

struct RefPoint { double t, value; };

std::vector<RefPoint> antoci(const std::string& component) {
    std::vector<RefPoint> out;  // columns: source, component, t_s, displacement_m
    for (const auto& c : reference_rows("antoci_2007_gate_tip.csv"))
        if (c.size() >= 4 && c[0] == "fsi_etvf" && c[1] == component) out.push_back({std::stod(c[2]), std::stod(c[3])});
    return out;
}


} // namespace

json elastic_gate_scene(const ElasticGateSpec& s) {
    const double dp = s.spacing, db = dp / 2, h = 1.25 * dp, c0 = sound_speed(), R = s.gate_radius;
    const double t = std::ceil(2 * h / db) * db;
    const double gate_x0 = water_w, gate_x1 = water_w + gate_t, top = gate_top(R);
    const json sph = {{"smoothing_length", h}, {"kernel", 0}, {"rest_density", rho_f}, {"speed_of_sound", c0},
                      {"viscosity", 1}, {"alpha", 0.1}};
    const json eos = {{"rest_density", rho_f}, {"speed_of_sound", c0}, {"gamma", gamma_tait}};
    json eos_pass = eos, wall_pass = eos, gate_pass = eos;
    eos_pass.update({{"boundary_group", boundary_group}, {"hydrostatic_gravity", g}, {"surface_level", water_h}});
    wall_pass.update({{"smoothing_length", h}, {"kernel", 0}, {"boundary_group", boundary_group}, {"gravity_y", -g}});
    gate_pass.update({{"smoothing_length", h}, {"kernel", 0}, {"structure_group", gate_group},
                      {"fluid_group", fluid_group}, {"pressure_mode", s.pressure_mode}, {"gravity_y", -g}});
    const double ball_density = rubber_rho * 2 * std::sqrt(3.0) / M_PI;  // cell mass 2√3 R² ρ on a disc π R²
    return {
        {"description",
         "Dam break through an elastic rubber gate (thesis 7.3, Table 7; Antoci et al. 2007): water 0.1 x 0.14 m, gate "
         "0.079 x 0.005 m of bonded balls (E 12 MPa, nu 0.33, rho 1100) clamped at the top, free at the bottom; the "
         "gate joins the SPH sums (sph model on fluid x gate, structure_sph_state pass). Compare the free-end "
         "displacement with the experiment: plab validate elastic_gate."},
        {"dimension", 2},
        {"gravity", {0, -g}},
        {"plugins", {"sph", "sph_passes", "linear_pbond", "coupling_fluid_structure"}},
        {"bodies",
         {{{"type", "lattice"}, {"group", "fluid"}, {"packing", "square"},
           {"box", {{"min", {0, 0}}, {"max", {water_w, water_h}}}}, {"radius", dp / 2}, {"spacing", dp},
           {"mass", rho_f * dp * dp}, {"fix", {"rotation"}}},
          boundary_block(-t, -t, tank_l + t, 0, db), boundary_block(-t, 0, 0, tank_h, db),
          boundary_block(tank_l, 0, tank_l + t, tank_h, db),
          // the rigid plate above the gate (thesis Fig. 25)
          boundary_block(gate_x0, top, gate_x1, tank_h, db),
          {{"type", "lattice"}, {"group", "gate"}, {"packing", "hexagonal"},
           {"box", {{"min", {gate_x0, s.clearance}}, {"max", {gate_x1, top}}}}, {"radius", R},
           {"density", ball_density}}}},
        {"contact_models",
         {{{"groups", {"fluid", "fluid"}}, {"model", "sph"}, {"properties", sph}},
          {{"groups", {"fluid", "boundary"}}, {"model", "sph"}, {"properties", sph}},
          {{"groups", {"fluid", "gate"}}, {"model", "sph"}, {"properties", sph}},
          {{"groups", {"gate", "gate"}}, {"model", "linear_pbond"},
           {"calibrate", {{"method", "hexagonal_2d"}, {"E", rubber_E}, {"nu", rubber_nu}, {"sigma_ult", 1e9}, {"radius", R}}}}}},
        {"passes",
         {{{"name", "sph_density_integration"}, {"properties", {{"boundary_group", boundary_group}}}},
          {{"name", "sph_eos"}, {"properties", eos_pass}},
          {{"name", "sph_wall_pressure"}, {"properties", wall_pass}},
          {{"name", "structure_sph_state"}, {"properties", gate_pass}}}},
        {"histories",
         {{"every", 250},
          {"record",
           {{{"quantity", "time"}},
            {{"name", "gate_min_y"}, {"quantity", "group.min.position.y"}, {"group", "gate"}},
            {{"name", "gate_max_x"}, {"quantity", "group.max.position.x"}, {"group", "gate"}}}}}},
        {"output", {{"vtk_interval", 0.02}}},
        {"commands",
         {{{"bond", {{"groups", {"gate", "gate"}}, {"gap", 1e-9}}}},
          {{"set", {{"region", {{"min", {gate_x0, gate_l}}, {"max", {gate_x1, top + R}}}}, {"fix", {"all"}}}}},
          {{"solve", {{"time", s.end_time}}}}}}};
}

ElasticGateResult elastic_gate(const ElasticGateSpec& s) {
    json scene = elastic_gate_scene(s);
    scene.erase("commands");
    scene.erase("histories");
    scene.erase("output");
    Simulation sim(scene);
    sim.set_quiet(true);
    World& w = sim.world();
    const int gate = w.find_group("gate");
    // the free end: the lowest row's ball nearest the gate's mid-plane
    std::size_t tip = 0;
    double best = 1e300;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        if (w.bodies.group[i] != gate) continue;
        const Vec& x = w.bodies.position[i];
        if (x.y() > gate_l) w.bodies.fixity[i] = 63;  // clamp: every degree of freedom
        const double score = x.y() * 1e3 + std::fabs(x.x() - (water_w + gate_t / 2));
        if (score < best) { best = score; tip = i; }
    }
    ElasticGateResult r;
    r.bonds = long(w.bond(gate, gate, 1e-9));
    const Vec x0 = w.bodies.position[tip];
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        r.fluid += w.bodies.group[i] == fluid_group;
        r.gate += w.bodies.group[i] == gate;
    }
    const std::clock_t c_start = std::clock();
    // Fig. 27's water levels: the highest fluid centre in a strip, + dp/2
    auto level = [&](double x_lo, double x_hi) {
        double top = 0;
        for (std::size_t i = 0; i < w.bodies.size(); ++i) {
            const Vec& x = w.bodies.position[i];
            if (w.bodies.group[i] == fluid_group && x.x() >= x_lo && x.x() < x_hi) top = std::max(top, x.y());
        }
        return top + 0.5 * s.spacing;
    };
    auto record = [&]() {
        r.t.push_back(w.time);
        r.dx.push_back(w.bodies.position[tip].x() - x0.x());
        r.dy.push_back(w.bodies.position[tip].y() - x0.y());
        r.level_gate.push_back(level(water_w - 0.01, water_w));
        r.level_5cm.push_back(level(water_w - 0.055, water_w - 0.045));
    };
    record();
    while (w.time < s.end_time) {
        w.step();
        if (w.step_count % 20 == 0) record();
    }
    record();
    r.cpu_seconds = double(std::clock() - c_start) / CLOCKS_PER_SEC;
    r.steps = long(w.step_count);
    r.broken = long(w.bond_breaks.size());
    // RMS against the experiment's points within the run, relative to its peak x
    const std::vector<RefPoint> ref_x = antoci("x"), ref_y = antoci("y");
    double sx = 0, sy = 0, peak_ref = 0, peak_ref_t = 0, peak_y_ref = 0;
    int nx = 0, ny = 0;
    for (const RefPoint& p : ref_x) {
        if (p.value > peak_ref) { peak_ref = p.value; peak_ref_t = p.t; }
        if (p.t > w.time) continue;
        const double d = sample_history(r.t, r.dx, p.t) - p.value;
        sx += d * d;
        ++nx;
    }
    for (const RefPoint& p : ref_y) {
        peak_y_ref = std::max(peak_y_ref, p.value);
        if (p.t > w.time) continue;
        const double d = sample_history(r.t, r.dy, p.t) - p.value;
        sy += d * d;
        ++ny;
    }
    r.rms_x_rel = nx ? std::sqrt(sx / nx) / peak_ref : 0.0;
    r.rms_y_rel = ny ? std::sqrt(sy / ny) / peak_y_ref : 0.0;
    const auto peak = std::max_element(r.dx.begin(), r.dx.end());
    r.peak_x = *peak;
    r.peak_time = r.t[std::size_t(peak - r.dx.begin())];
    r.peak_time_ref = peak_ref_t;
    r.peak_x_ref = peak_ref;
    return r;
}

} // namespace plab::cases

namespace {

using namespace plab;
using namespace plab::cases;

// Full: the thesis's gate (balls R 0.625 mm, four across the thickness) in
// fluid at dp 2.5 mm (Table 7: 1.75 mm, twice the cost), 0.4 s. Quick: dp
// 5 mm, R 1.25 mm (two across), 0.2 s (past the peak at ~0.16 s). The error figure is the RMS of the x
// displacement relative to its peak (quick: 0.2, measured 0.138); the peak
// time is held to 0.03 s too.
PLAB_VALIDATION_CASE("elastic_gate",
                     "SPH-DEM fluid-structure coupling (thesis 7.3, Antoci et al. 2007): rubber gate tip displacement",
                     [](bool quick) {
    ElasticGateSpec s;
    if (quick) { s.spacing = 0.005; s.gate_radius = 0.00125; s.end_time = 0.2; }
    const ElasticGateResult t = elastic_gate(s);
    const double peak_dt = std::fabs(t.peak_time - t.peak_time_ref);
    CaseResult r{t.rms_x_rel, quick ? 0.2 : 0.15,
                 "RMS of the free end's x displacement against Antoci 2007, relative to its peak (0.046 m)", ""};
    char buf[600];
    std::snprintf(buf, sizeof buf,
                  "    %d fluid balls dp %.4g m, %d gate balls R %.4g m (%ld bonds, %ld broken), t = %.2f s, %ld steps, "
                  "%.1f s CPU\n"
                  "    x: RMS %.1f %% of the peak; peak %.4f m at %.3f s (experiment %.4f m at %.3f s, |dt| %.3f s, "
                  "limit 0.03 s); y: RMS %.1f %% of its peak\n",
                  t.fluid, s.spacing, t.gate, s.gate_radius, t.bonds, t.broken, s.end_time, t.steps, t.cpu_seconds,
                  100 * t.rms_x_rel, t.peak_x, t.peak_time, t.peak_x_ref, t.peak_time_ref, peak_dt, 100 * t.rms_y_rel);
    r.details = buf;
    r.details += "    water level (thesis Fig. 27), m: t / behind the gate / 5 cm from it:";
    for (double tt = 0.05; tt <= s.end_time + 1e-9; tt += 0.05) {
        std::snprintf(buf, sizeof buf, " %.2f s %.4f %.4f;", tt, sample_history(t.t, t.level_gate, tt),
                      sample_history(t.t, t.level_5cm, tt));
        r.details += buf;
    }
    r.details += "\n";
    if (peak_dt > 0.03) {
        r.error = std::max(r.error, r.tolerance + peak_dt);
        r.details += "    peak time off by more than 0.03 s\n";
    }
    return r;
});

} // namespace
