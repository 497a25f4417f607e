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

// Thesis §7.2: a 0.05 × 0.1 m column of water with a bed of immersed grains
// (d 2.4 mm, ρ 2500) behind a gate lifted at 0.68 m/s; grains interact
// through `linear_lubrication` (linear + thesis eq. 76), with the fluid
// through the unresolved coupling. Front z* = x/a against t* = t √(2g/a)
// (eqs. 86–87).
struct TwoPhaseDamBreakSpec {
    double spacing = 0.0025;        // fluid spacing dp, m (thesis 2.4 mm; must divide 0.05 and 0.1); h = 1.25 dp
    double grain_spacing = 0.0027;  // initial centre spacing of the grain bed, m (the experiment's mean bead size)
    int grain_rows = 10;            // rows of 18 grains: 180 discs, a bed ~27 mm deep
    double lubrication_mu = 8.9e-4; // eq. 76's viscosity, Pa s; 0: plain linear contacts between grains
    double coupling_length = 0.006; // coupling kernel h_c, m (as sedimentation)
    double gate_speed = 0.68;       // m/s
    double end_time = 0.2;          // s (thesis)
};

struct TwoPhaseDamBreakResult {
    std::vector<double> t_star, z_star, grain_z_star;  // fluid front and grain front, normalised (eqs. 86-87)
    double mean_error = 0;   // mean |z* - Z_MM| / Z_MM at the Martin & Moyce points inside the run
    double max_lead = 0;     // largest (z* - Z_MM) / Z_MM there: how far the mixture runs ahead of pure water
    int grains = 0, fluid = 0, lost = 0;  // lost: grains whose centre left the tank
    long steps = 0;
    double cpu_seconds = 0;
};

nlohmann::json two_phase_dam_break_scene(const TwoPhaseDamBreakSpec& s);
TwoPhaseDamBreakResult two_phase_dam_break(const TwoPhaseDamBreakSpec& s);

// Thesis §7.5: the two-phase dam break with the gate replaced by a
// bottom-fixed breakable structure (the elastic gate's rubber plate,
// 0.079 × 0.005 m at x = a); case I bond strength 4e4 Pa, case II 2e4 Pa.
struct FpsiSpec {
    double spacing = 0.0025, gate_radius = 0.000625;  // fluid dp and structure ball radius, m (>= 3 balls across)
    double bond_strength = 4e4;  // pb_ten = pb_coh, Pa (case I 4e4, case II 2e4)
    double end_time = 0.2;       // s
    int pressure_mode = 2;       // structure_sph_state (gate_fracture_case.cpp says why 2)
    // pb_mcf, β̄ in the bond stress (eq. 49). The thesis sets 0 (§3.3.3, under eq. 50): the strengths of
    // eqs. 43-46 are derived from the bond forces alone. With 1 the clamp row detaches within 4-12 ms
    // and the plate stands loose on it (docs/coupling.md)
    double moment_factor = 0.0;
    double probe_interval = 0;   // s between bond-stress samples (FpsiResult::probes); 0: none
    double density_band = 0;     // sph_eos density band; 0: its default (5 %)
};

// The most loaded bonds of the structure at one time (a study probe).
struct BondStressSample {
    double t = 0;
    double sigma_axial = 0;  // largest Fn/A over the bonds (eq. 49 with β̄ = 0), Pa
    double sigma = 0;        // largest Fn/A + |Mb| R/I (β̄ = 1), Pa
    double tau = 0;          // largest |Fs|/A (eq. 50, 2D), Pa
    double x = 0, y = 0;     // midpoint of the bond with the largest sigma, m
    double tip_dx = 0;       // displacement of the structure's top centre ball, m
    long broken = 0;         // bonds broken so far
    int fragments = 0, largest_fragment = 0;  // pieces joined by intact bonds, balls in the largest
};

struct FpsiResult {
    long bonds = 0, broken = 0, steps = 0;
    int fragments = 0;        // connected pieces of the structure through intact bonds (1: whole)
    int largest_fragment = 0; // balls in the largest piece
    double first_break_time = -1;  // first bond to break, s (the thesis does not report it)
    // the plate falls apart: the first time its balls form two or more pieces joined by intact bonds, s
    // (thesis: case II "fails around 0.1 s"); -1 if it stays one piece
    double failure_time = -1;
    double first_break_x = -1, first_break_y = -1;  // m
    int first_break_mode = 0;                        // PLAB_BREAK_TENSION / PLAB_BREAK_SHEAR
    std::vector<BondStressSample> probes;            // every FpsiSpec::probe_interval
    int structure = 0, grains = 0, grains_lost = 0;
    bool penetrated = false;  // a structure ball's centre crossed a wall surface
    double cpu_seconds = 0;
};

nlohmann::json fpsi_scene(const FpsiSpec& s);
FpsiResult fpsi(const FpsiSpec& s);

} // namespace plab::cases
