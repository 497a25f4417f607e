// Fluid–particle drag and buoyancy of one solid particle in the locally
// averaged fluid (thesis §4.1, eqs. 69–75). Header-only and free of host
// types, part of the SDK (<plab/coupling/drag_law.hpp>): the plug-in and the
// tests share it.
//
// Readings of the thesis text taken here:
//  * eq. 69 names the drag F_p^b (the buoyancy's symbol); it is the drag
//    F_p^d = β/(1-ε) (ū_f - v_p) V_p of eq. 57.
//  * eq. 70's Wen–Yu branch prints 7.5 C_d; the thesis code (Appendix 2)
//    and Wen & Yu (1966) have 0.75 = 3/4 — taken.
//  * eq. 72 switches on Re_p but evaluates Re_f; there is one Reynolds
//    number, eq. 73's Re = ε ρ_f |ū_f - v_p| d_p / μ_f, which the thesis code
//    also uses for both.
//  * eq. 75 writes the buoyancy along the unit vector "parallel to gravity":
//    it acts against gravity, F_b = -ε ρ_f V_p g (here optional: by default
//    the buoyancy is -V_p ∇p of the SPH pressure field, which also carries
//    the dynamic pressure).
//
// In 2D a "disc" is a cylinder of unit length. Two readings (`drag_2d`):
//  * cylinder (default): the Wen–Yu drag written with the projected area,
//    F = ½ C_d ρ_f A ε^-1.65 |w| w with A = d (per unit length) and the
//    cylinder's C_d(Re) of Sucker & Brauer (1975); the Ergun branch is a
//    volumetric law and keeps V_p = π r² per unit length. In 3D the same
//    form with A = π d²/4 and Schiller–Naumann's C_d is exactly eq. 70.
//  * thesis: eq. 70 verbatim with V_p = π r² (PFC2D's disc volume) and the
//    sphere's C_d, i.e. a sphere's drag coefficient on a disc.
#ifndef PLAB_COUPLING_DRAG_LAW_HPP
#define PLAB_COUPLING_DRAG_LAW_HPP

#include <algorithm>
#include <cmath>

namespace plab::coupling {

enum class Drag2d : int { cylinder = 0, thesis = 1 };

// Solid volume (area × unit thickness in 2D) of a ball of radius r.
inline double solid_volume(int dim, double r) { return dim == 2 ? M_PI * r * r : 4.0 / 3.0 * M_PI * r * r * r; }

// eq. 73: particle Reynolds number with the local voidage.
inline double reynolds(double voidage, double rho_f, double slip_speed, double d, double mu) {
    return voidage * rho_f * slip_speed * d / mu;
}

// eq. 72: sphere, Schiller–Naumann below Re = 1000, Newton's 0.44 above.
inline double sphere_drag_coefficient(double re) {
    return re <= 1000 ? 24.0 / re * (1 + 0.15 * std::pow(re, 0.687)) : 0.44;
}

// Cylinder in cross-flow, Sucker & Brauer (1975), 1e-4 < Re < 2e5 (White,
// Viscous Fluid Flow, eq. 3-225); within ~10 % of Tritton's data at Re ~ 10.
inline double cylinder_drag_coefficient(double re) {
    return 1.18 + 6.8 / std::pow(re, 0.89) + 1.96 / std::sqrt(re) - 4e-4 * re / (1 + 3.64e-7 * re * re);
}

struct DragInput {
    int dim = 2;
    Drag2d law_2d = Drag2d::cylinder;
    double voidage = 1;   // ε_p, Shepard-interpolated (eq. 68)
    double rho_f = 1000;  // reference fluid density, kg/m3
    double mu = 1e-3;     // dynamic viscosity, Pa s
    double d = 1e-3;      // particle diameter, m
};

// Drag coefficient K (N s/m, per unit length in 2D) with F_d = K (ū_f - v_p):
// eqs. 69–70, K = β V_p / (1 - ε). At zero slip K takes its limit (Stokes
// for the sphere: C_d |w| stays finite), so a particle at rest is not a
// special case.
inline double drag_coefficient(const DragInput& in, double slip) {
    const double slip_speed = std::max(slip, 1e-12 * in.mu / (in.rho_f * in.d));
    const double eps = std::clamp(in.voidage, 1e-3, 1.0);
    const double vol = in.dim == 2 ? M_PI * in.d * in.d / 4 : M_PI * in.d * in.d * in.d / 6;
    if (eps <= 0.8) {  // Ergun (1952): β/(1-ε) = 150 (1-ε) μ/(ε d²) + 1.75 ρ |w|/d
        return (150 * (1 - eps) * in.mu / (eps * in.d * in.d) + 1.75 * in.rho_f * slip_speed / in.d) * vol;
    }
    const double re = reynolds(eps, in.rho_f, slip_speed, in.d, in.mu);
    const double hindrance = std::pow(eps, -1.65);  // Wen–Yu's ε^-2.65 times the ε of β/(1-ε)
    if (in.dim == 2 && in.law_2d == Drag2d::cylinder) {
        const double area = in.d;  // projected area per unit length
        return 0.5 * cylinder_drag_coefficient(re) * in.rho_f * area * slip_speed * hindrance;
    }
    // eq. 70, Wen–Yu: β/(1-ε) V_p = 0.75 C_d ε ρ |w| ε^-2.65 V_p / d
    return 0.75 * sphere_drag_coefficient(re) * eps * in.rho_f * slip_speed * std::pow(eps, -2.65) * vol / in.d;
}

} // namespace plab::coupling

#endif // PLAB_COUPLING_DRAG_LAW_HPP
