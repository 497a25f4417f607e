// Measurements behind the SPH–DEM coupling validation cases (plug-in
// `coupling_fluid_particle`). tests/physics/coupling_test.cpp calls the same
// functions and asserts the physics with stated tolerances.
#pragma once

#include <nlohmann/json.hpp>

#include <vector>

namespace plab::cases {

// Thesis §7.3, Table 7 (Antoci et al. 2007): elastic gate under a dam break.
struct ElasticGateSpec {
    double spacing = 0.0025;       // fluid particle spacing dp, m (Table 7: 1.75 mm); h = 1.25 dp (Table 7)
    double gate_radius = 0.000625; // gate ball radius, m (Table 7: size 1.25 mm)
    double clearance = 0.0;        // gap between the floor and the gate's lattice box, m
    // structure_sph_state: 0 thesis (p = 0), 1 extrapolated with the balls' acceleration, 2 without it.
    // 2: with 1 the full gate's extrapolated density falls below 0.95 rho0 at 0.023 s (its balls'
    // bond vibration, as gate_fracture); with 2 it runs and peaks at 0.133 s (docs/coupling.md)
    int pressure_mode = 2;
    double end_time = 0.4;         // s
};

struct ElasticGateResult {
    std::vector<double> t, dx, dy;   // free-end displacement, m
    // water levels of thesis Fig. 27, m: the free surface just behind the
    // gate (fluid in 0.09 <= x < 0.1) and 5 cm from it (0.045 <= x < 0.055),
    // the highest fluid centre in the strip plus dp/2, sampled with t
    std::vector<double> level_gate, level_5cm;
    double rms_x_rel = 0, rms_y_rel = 0;  // RMS against the experiment / its peak
    double peak_x = 0, peak_time = 0, peak_x_ref = 0, peak_time_ref = 0;
    long bonds = 0, broken = 0, steps = 0;
    int fluid = 0, gate = 0;
    double cpu_seconds = 0;
};

nlohmann::json elastic_gate_scene(const ElasticGateSpec& s);
ElasticGateResult elastic_gate(const ElasticGateSpec& s);

// Thesis §7.4: the gate clamped at the bottom with a lowered strength.
struct GateFractureSpec {
    double spacing = 0.0025, gate_radius = 0.000625;  // as ElasticGateSpec; R 1.25 mm (2-1-2 rows) is a hinge chain: refused (< 3 balls across)
    // structure_sph_state: 2, extrapolated without the balls' vibration (1 blows up a free-standing gate)
    int pressure_mode = 2;
    // sigma_ult of the hexagonal calibration, Pa: its shear strength (eq. 44, 0.0037 sigma_ult at nu 0.33,
    // 5.2 kPa) just below the peak clamp shear stress of an unbreakable gate (5.5-6 kPa at 0.11-0.14 s)
    double strength = 1.4e6;
    double density_band = 0;  // sph_eos density band; 0: its default (5 %)
    double end_time = 0.2;   // s
};

struct GateFractureResult {
    long bonds = 0, broken = 0, steps = 0;
    double first_break_time = -1, first_break_y = -1;  // s, m
    int first_break_mode = 0;                           // PLAB_BREAK_TENSION / PLAB_BREAK_SHEAR
    double min_x = 0, max_x = 0, min_y = 0;             // extent of the gate balls' centres over the run, m
    bool penetrated = false;                            // a centre crossed a wall surface
    double cpu_seconds = 0;
};

nlohmann::json gate_fracture_scene(const GateFractureSpec& s);
GateFractureResult gate_fracture(const GateFractureSpec& s);

} // namespace plab::cases
