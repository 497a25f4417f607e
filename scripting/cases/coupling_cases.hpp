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

} // namespace plab::cases
