// Measurements behind the bonded-structure validation cases (issue: parallel
// bonds): the thesis cantilever (§6.2) and a plate hit by a fast ball.
#pragma once

#include <string>

namespace plab::cases {

struct Cantilever {
    double radius = 0;        // ball radius, m
    int rows = 0;
    long balls = 0, steps = 0;
    double height = 0;        // lattice envelope height 2R + (rows-1)√3 R, m
    double deflection = 0;    // tip deflection at equilibrium, m
    double analytical = 0;    // P L³ / (3 E I), I = h³/12, nominal L = 0.201 m and envelope h
    // The continuum the lattice represents: the calibration (eq. 36) gives E
    // per hexagonal cell of area 2√3 R², so the beam's height is rows·√3 R,
    // and its free length runs from the clamp line to the loaded ball centre.
    double equivalent_height = 0, equivalent_length = 0;
    double clamp_line = 0;  // where the clamped balls' material ends (mean over the rows), m
    double analytical_equivalent = 0;
    double strength_load_equivalent = 0;  // σ_ult h² / (6 L) with the equivalent beam
    // σ11 of the top and bottom rows between 20 % and 80 % of the length
    // against -M y / I (ball stress rescaled from πR² to the hexagonal cell
    // 2√3 R²): RMS of the difference over the RMS of the beam-theory stress
    double fibre_stress_error = 0;
    double fibre_stress_scale = 0;  // RMS of -M y / I over those balls, Pa
    double first_break_load = 0;  // by linearity: P σc / max σ over bonds (eq. 49 with the scene's β̄), N
    double first_break_load_centre = 0;  // the same with β̄ = 0: the stress at the bond's centre line, N
    double first_tension_break_load = 0;  // P σc / max σ over bonds (eq. 49), N
    double first_shear_break_load = 0;    // P τc / max τ over bonds (eq. 50), N
    double break_x = 0, break_y = 0;  // where the first bond to break is, m
    bool break_in_tension = false;    // false: it breaks in shear
    double strength_load = 0;  // σ_ult h² / (6 L), N
    // the load at which the equivalent beam's stress at the bottom row's
    // centre, where the first bond sits, reaches σ_ult: a lattice calibrated
    // for tension along its bonds breaks there
    double row_strength_load = 0;
    double cpu_seconds = 0;
};

// How the beam's bond strengths are set (scripting/calibration.cpp,
// docs/bonded-structures.md).
struct StrengthRule {
    std::string tension = "across_bonds";  // "across_bonds" (thesis eq. 43) or "along_bonds"
    double moment_factor = 0.0;            // β̄ of eq. 49 (the thesis sets it to 0)
    double tau_ult = 0.0;                  // material shear strength, Pa; 0: eq. 44's √3/4 σ_ult
};
// The rule the cantilever_failure case judges: the fibres are rows of bonds
// along the tension, β̄ = 1 puts σ at the bond's outer edge (for the outer
// row the beam's surface), and the shear strength is the aluminium's own
// (6061-T6: 207 MPa for σ_ult 310 MPa).
inline StrengthRule beam_fibre_rule() { return {"along_bonds", 1.0, 207e6}; }

// Static tip load P on the bottom-right ball, left end clamped, solved with
// viscous damping to an unbalanced-force ratio. L = 0.201 m, E = 70 GPa,
// ν = 0.33, σ_ult = 310 MPa (thesis Table 4); rows chosen so the height is
// closest to 6.196 mm.
// The clamp: ball centres within clamp_depth·R of the left end are fixed.
// 2.2 fixes one ball per row, and the odd rows (centres at 2R) reach R
// further into the span than the outer, even rows; 3.2 fixes two balls of
// the even rows, and the outer rows reach R further than the odd ones
// (docs/bonded-structures.md: where the first bond breaks depends on it).
constexpr double kClampDepth = 2.2;
Cantilever static_cantilever(double radius, double load, double ratio, const StrengthRule& rule = {},
                             double clamp_depth = kClampDepth);

struct VelocityFailure {
    double reaction = 0;     // force on the driven ball when the first bond broke, N
    double x = 0, y = 0;     // where it broke
    bool tension = false;
    double time = 0;
    long steps = 0;
};
// The thesis failure test: the bottom-right ball driven upward at `velocity`
// with local damping until the first bond breaks.
VelocityFailure velocity_failure(double radius, double velocity, const StrengthRule& rule = {});

struct Impact {
    double input_energy = 0;      // kinetic energy of the projectile, J
    double balance_error = 0;     // |energy balance drift| / input energy
    double max_speed = 0;         // fastest ball at the end, m/s
    long broken = 0, bonds = 0;
    double farthest_break = 0;    // largest horizontal distance of a break from the impact point, m
    bool finite = true;
};
// A steel ball at `speed` hits a brittle bonded 2D plate (rock-like:
// E 30 GPa, ν 0.2, σ_ult 30 MPa, 80 × 19.5 mm) clamped at both ends; energy balance over the run.
Impact plate_impact(double speed, double duration);

} // namespace plab::cases
