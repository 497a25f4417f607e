// The SPH solid package's material, "sph_solid" (abi.h plab_material_desc):
// the constants of a hypoelastic SPH solid that the `sph_solid` pair law
// and the `sph_solid_stress` pass share, stated once per solid in a scene:
//
//   "materials": {"plate": {"groups": ["plate"], "rest_density": 1000, "youngs_modulus": 2e6,
//                           "poissons_ratio": 0.3975, "smoothing_length": 0.0026,
//                           "particle_spacing": 0.002, "kernel": "wendland_c2"}}
//
// and the per-body fields the two exchange. Part of the SDK
// (<plab/sph_solid/material.hpp>).
#ifndef PLAB_SPH_SOLID_MATERIAL_HPP
#define PLAB_SPH_SOLID_MATERIAL_HPP

#include <plab/contact_model.hpp>
#include <plab/sph/kernels.hpp>

#include <limits>

namespace plab::sph_solid {

namespace solid {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

inline constexpr plab_property_desc rest_density = plab::prop::number(
    "rest_density", "reference density rho0", "kg/m3", 1000.0, 0.0, kInfinity, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
    "rho0 of p = K (rho/rho0 - 1); the density of a particle before its first step");
inline constexpr plab_property_desc youngs_modulus = plab::prop::number(
    "youngs_modulus", "Young's modulus E", "Pa", 1e6, 0.0, kInfinity, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
    "with nu: bulk modulus K = E/(3(1 - 2 nu)), shear modulus G = E/(2(1 + nu))");
inline constexpr plab_property_desc poissons_ratio = plab::prop::number(
    "poissons_ratio", "Poisson's ratio nu", "1", 0.3, -1.0, 0.5, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
    "-1 < nu < 0.5: K and G finite and positive; 2D is plane strain");
inline constexpr plab_property_desc smoothing_length = plab::prop::number(
    "smoothing_length", "smoothing length h", "m", 0.005, 0.0, kInfinity, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
    "kernel support is 2h (Wendland C2, cubic spline) or 3h (quintic); about 1.3 x particle_spacing");
inline constexpr plab_property_desc kernel = plab::prop::choice(
    "kernel", "kernel function", plab::sph::kernel_names, 0,
    "wendland_c2: Wendland C2 (Islam eq. 5); cubic: cubic spline; quintic: quintic spline");
inline constexpr plab_property_desc particle_spacing = plab::prop::number(
    "particle_spacing", "initial particle spacing dp", "m", 0.004, 0.0, kInfinity, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
    "dp of the artificial stress' f = W(r)/W(dp) (Islam eq. 16); must lie inside the kernel support");

} // namespace solid

struct SolidMaterial {
    static constexpr const char* name = "sph_solid";
    static constexpr const char* doc =
        "a hypoelastic SPH solid (Islam 2023 sec. 3): rest density, Young's modulus, Poisson's ratio, smoothing "
        "length, kernel and initial particle spacing (physics/sph_solid/README.md)";
    static constexpr plab_property_desc properties[] = {
        solid::rest_density, solid::youngs_modulus, solid::poissons_ratio,
        solid::smoothing_length, solid::kernel, solid::particle_spacing,
    };
};

// The per-body fields of an SPH solid particle. Tensors by component:
// symmetric ones xx, yy, zz, xy, yz, zx; the raw velocity-gradient sum row
// by row (xx, xy, xz, yx, ...: component ab is Σ V_j (v_j - v_i)_a (∇_i W_ij)_b).
namespace field {
inline constexpr plab_field_desc density = plab::field_desc("sph_solid_density", "kg/m3", 0.0);  // 0: rho0
inline constexpr plab_field_desc drho_dt = plab::field_desc("sph_solid_drho_dt", "kg/(m3 s)", 0.0);
inline constexpr plab_field_desc pressure = plab::field_desc("sph_solid_pressure", "Pa", 0.0);
#define PLAB_SPH_SOLID_SYM(prefix, unit, diagonal)                                                               \
    plab::field_desc(prefix "_xx", unit, diagonal), plab::field_desc(prefix "_yy", unit, diagonal),              \
        plab::field_desc(prefix "_zz", unit, diagonal), plab::field_desc(prefix "_xy", unit, 0.0),               \
        plab::field_desc(prefix "_yz", unit, 0.0), plab::field_desc(prefix "_zx", unit, 0.0)
inline constexpr plab_field_desc stress[6] = {PLAB_SPH_SOLID_SYM("sph_solid_stress", "Pa", 0.0)};
inline constexpr plab_field_desc deviatoric_stress[6] = {PLAB_SPH_SOLID_SYM("sph_solid_deviatoric_stress", "Pa", 0.0)};
inline constexpr plab_field_desc artificial_stress[6] = {PLAB_SPH_SOLID_SYM("sph_solid_artificial_stress", "m5/(kg s2)", 0.0)};
// A_i of Islam eq. 20 (summed by the law) and B_i = A_i^-1 (the pass)
inline constexpr plab_field_desc moment_matrix[6] = {PLAB_SPH_SOLID_SYM("sph_solid_moment_matrix", "1", 0.0)};
inline constexpr plab_field_desc correction[6] = {PLAB_SPH_SOLID_SYM("sph_solid_correction", "1", 1.0)};
#undef PLAB_SPH_SOLID_SYM
inline constexpr plab_field_desc velocity_gradient[9] = {
    plab::field_desc("sph_solid_velocity_gradient_xx", "1/s", 0.0), plab::field_desc("sph_solid_velocity_gradient_xy", "1/s", 0.0),
    plab::field_desc("sph_solid_velocity_gradient_xz", "1/s", 0.0), plab::field_desc("sph_solid_velocity_gradient_yx", "1/s", 0.0),
    plab::field_desc("sph_solid_velocity_gradient_yy", "1/s", 0.0), plab::field_desc("sph_solid_velocity_gradient_yz", "1/s", 0.0),
    plab::field_desc("sph_solid_velocity_gradient_zx", "1/s", 0.0), plab::field_desc("sph_solid_velocity_gradient_zy", "1/s", 0.0),
    plab::field_desc("sph_solid_velocity_gradient_zz", "1/s", 0.0)};
// σ_i B_i/ρ_i², the particle's factor in the momentum equation (Islam eq. 15 with
// corrected gradients), row by row as the velocity gradient: the pass
// computes it once per particle, the law reads it (fewer fields than σ, B, ρ)
inline constexpr plab_field_desc stress_term[9] = {
    plab::field_desc("sph_solid_stress_term_xx", "m5/(kg s2)", 0.0), plab::field_desc("sph_solid_stress_term_xy", "m5/(kg s2)", 0.0),
    plab::field_desc("sph_solid_stress_term_xz", "m5/(kg s2)", 0.0), plab::field_desc("sph_solid_stress_term_yx", "m5/(kg s2)", 0.0),
    plab::field_desc("sph_solid_stress_term_yy", "m5/(kg s2)", 0.0), plab::field_desc("sph_solid_stress_term_yz", "m5/(kg s2)", 0.0),
    plab::field_desc("sph_solid_stress_term_zx", "m5/(kg s2)", 0.0), plab::field_desc("sph_solid_stress_term_zy", "m5/(kg s2)", 0.0),
    plab::field_desc("sph_solid_stress_term_zz", "m5/(kg s2)", 0.0)};
// Pseudo-springs (Islam §3.3): the intact springs of a particle, counted by
// the law in the rates stage; the most it has had (its springs when
// bonded) and its damage D = 1 - intact/initial, kept by the pass.
inline constexpr plab_field_desc intact_springs = plab::field_desc("sph_solid_intact_springs", "1", 0.0);
inline constexpr plab_field_desc initial_springs = plab::field_desc("sph_solid_initial_springs", "1", 0.0);
inline constexpr plab_field_desc damage = plab::field_desc("sph_solid_damage", "1", 0.0);
} // namespace field

} // namespace plab::sph_solid

#endif // PLAB_SPH_SOLID_MATERIAL_HPP
