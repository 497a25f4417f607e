// Measurements behind the SPH–DEM coupling validation cases (plug-in
// `coupling_fluid_particle`). tests/physics/coupling_test.cpp calls the same
// functions and asserts the physics with stated tolerances.
#pragma once

#include <nlohmann/json.hpp>

#include <vector>

namespace plab::cases {

// Thesis §7.1: one disc (ρ_s = 1250, r = 1.25 mm) settling from 0.04 m in a
// closed 0.02 × 0.06 m box of fluid (ρ_f = 1000, μ = 0.01 Pa s), unresolved
// coupling (the disc is one DEM ball; the fluid particles overlap it).
struct SedimentationSpec {
    double spacing = 0.00125;     // fluid particle spacing dp, m (must divide 0.02 and 0.06)
    double h_over_dp = 2.0;       // thesis: h = 3 mm at dp = 1.5 mm
    double speed_of_sound = 0;    // m/s; 0: 10 sqrt(g H)
    int drag_2d = 0;              // 0 cylinder, 1 thesis (sphere Cd on the disc), drag_law.hpp
    int buoyancy = 0;             // 0 -V grad p, 1 thesis eq. 75
    // smoothing length of the coupling's voidage / Shepard kernel, m; 0: the
    // fluid's h (the thesis). 6 mm ≈ 2.4 d: with it the terminal velocity
    // converges with dp (+7.7, +5.0, +3.3 % at d/dp 1, 1.25, 2); with the
    // fluid's kernel it swings between +14 and -23 % (docs/coupling.md)
    double coupling_length = 0.006;
    double end_time = 0.8;        // s
};

struct SedimentationResult {
    std::vector<double> t, y, v;       // disc centre height (m) and vertical velocity (m/s)
    std::vector<double> voidage, fluid_force_y, drag_coefficient;  // ε_p, fluid force (N/m), K (N s/m²) at the disc
    double terminal_velocity = 0;      // mean v over 0.35 <= t <= 0.66 s (the reference's plateau window), m/s
    double velocity_rms = 0;           // RMS of v - v_ref over the Glowinski points with t <= end, m/s
    double height_rms = 0;             // RMS of y - y_ref over Zhang's points with t <= end, m
    double cpu_seconds = 0;
    long steps = 0;
    int fluid = 0, boundary = 0;
};

nlohmann::json sedimentation_scene(const SedimentationSpec& s);
SedimentationResult sedimentation(const SedimentationSpec& s);

// Thesis §7.3, Table 7 (Antoci et al. 2007): elastic gate under a dam break.
struct ElasticGateSpec {
    double spacing = 0.0025;       // fluid particle spacing dp, m (Table 7: 1.75 mm); h = 1.25 dp (Table 7)
    double gate_radius = 0.000625; // gate ball radius, m (Table 7: size 1.25 mm)
    double clearance = 0.0;        // gap between the floor and the gate's lattice box, m
    int pressure_mode = 1;         // structure_sph_state: 0 thesis (p = 0), 1 extrapolated
    double end_time = 0.4;         // s
};

struct ElasticGateResult {
    std::vector<double> t, dx, dy;   // free-end displacement, m
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
    double spacing = 0.0025, gate_radius = 0.000625;  // as ElasticGateSpec
    double strength = 1.5e5; // sigma_ult of the hexagonal calibration, Pa (the hydrostatic bending stress at the clamp is ~1.3e5)
    double end_time = 0.3;   // s
};

struct GateFractureResult {
    long bonds = 0, broken = 0, steps = 0;
    double first_break_time = -1, first_break_y = -1;  // s, m
    double min_x = 0, max_x = 0, min_y = 0;             // extent of the gate balls' centres over the run, m
    bool penetrated = false;                            // a centre crossed a wall surface
    double cpu_seconds = 0;
};

nlohmann::json gate_fracture_scene(const GateFractureSpec& s);
GateFractureResult gate_fracture(const GateFractureSpec& s);

// The reference's terminal velocity (Glowinski et al. 2001), m/s.
constexpr double glowinski_terminal_velocity = 0.0555;

} // namespace plab::cases
