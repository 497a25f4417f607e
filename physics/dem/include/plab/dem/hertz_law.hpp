// The Hertz–Mindlin contact law (no-slip Mindlin–Deresiewicz tangential
// stiffness, Tsuji damping from a coefficient of restitution), shared by
// `hertz` and by any model built on it (a rolling-resistance option, a
// cohesive variant). Part of the SDK (<plab/dem/hertz_law.hpp>). The
// equations and their sources: physics/dem/hertz/README.md.
//
//   3D (spheres, Hertz 1882; Johnson 1985 §4.2, §7.2):
//     a = sqrt(R* d)                       contact radius
//     F_n = 4/3 E* sqrt(R*) d^(3/2)        normal force          (H1)
//     S_n = dF_n/dd = 2 E* a               normal stiffness      (H2)
//     S_t = 8 G* a                         Mindlin no-slip       (H3)
//   2D (discs as cylinders of length L = 1 m, the thickness of a 2D scene):
//     F_n = pi/4 E* L d,  S_n = pi/4 E* L,  S_t = pi G* L       (H1'-H3')
//   both:
//     dF_t = -S_t v_t dt (incremental), |F_t| <= mu F_n         (H4, H5)
//     F_d = -gamma v,  gamma = 2 c beta sqrt(S m*)              (H6)
//       beta = -ln e / sqrt(ln^2 e + pi^2); c = sqrt(5/6) in 3D
//       (Tsuji et al. 1992's form with the LIGGGHTS/EDEM coefficients),
//       c = 1 in 2D (the damped linear oscillator's, exact for a linear spring)
//   E*, G* of the two ends: 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,
//   1/G* = (2 - nu1)/G1 + (2 - nu2)/G2, G = E/(2 (1 + nu)). The host mixes
//   two materials' E harmonically and requires one nu (below), which gives
//   these exactly: E* = E_mix/(2 (1 - nu^2)), G* = G_mix/(2 (2 - nu)).
#pragma once

#include <plab/contact_model.hpp>

#include <cmath>
#include <limits>

namespace plab::hertz_law {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
inline constexpr double kPi = 3.14159265358979323846;

// Property descriptions of the law, for every model built on it.
inline constexpr plab_property_desc youngs_modulus = plab::prop::number(
    "E", "Young's modulus", "Pa", 70e9, 0.0, kInfinity, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
    "of the ends' solid (a wall is taken as this solid too); two materials mix harmonically, which with one "
    "Poisson's ratio is Hertz's 1/E* = (1 - nu^2)(1/E1 + 1/E2)",
    PLAB_MIX_HARMONIC);
inline constexpr plab_property_desc poisson_ratio = plab::prop::number(
    "nu", "Poisson's ratio", "1", 0.25, 0.0, 0.5, PLAB_MAX_EXCLUSIVE,
    "of the ends' solid; two materials must agree (E* and G* are then exact from the mixed E)");
inline constexpr plab_property_desc restitution = plab::prop::number(
    "e", "coefficient of restitution", "1", 1.0, 0.0, 1.0, PLAB_MIN_EXCLUSIVE,
    "normal restitution of the pair; sets the Tsuji damping ratio beta = -ln e / sqrt(ln^2 e + pi^2); 1: no damping");
inline constexpr plab_property_desc fric = plab::prop::number(
    "fric", "friction coefficient", "1", 0.0, 0.0, kInfinity, PLAB_MAX_EXCLUSIVE, "Coulomb limit |F_t| <= fric F_n",
    PLAB_MIX_MIN);
// the dashpot modes, the law's `dp_mode` in this order (as `linear`'s first and third)
inline constexpr const char* dp_mode_names[] = {"full", "no_tension"};
inline constexpr plab_property_desc dp_mode = plab::prop::choice(
    "dp_mode", "dashpot mode", dp_mode_names, 0,
    "full: the normal dashpot acts throughout (the restitution is then e exactly, at every speed); no_tension: "
    "the total normal force kept >= 0 (the dashpot never pulls; the restitution is then above e)");

// The DEM package's elastic solid, "dem_elastic" (abi.h plab_material_desc):
// the properties of one group's solid that a scene may state per group,
//   "materials": {"glass": {"groups": ["beads"], "E": 6.3e10, "nu": 0.22, "fric": 0.4}},
// and which a contact between two materials mixes (E harmonic, fric the
// smaller, nu must agree). The restitution and the dashpot mode belong to
// the pair, not to one solid: the rule gives them. A model built on the
// law takes them with `using material = plab::hertz_law::Material;`.
struct Material {
    static constexpr const char* name = "dem_elastic";
    static constexpr const char* doc =
        "the elastic solid of a group of balls for the Hertz-Mindlin contact: Young's modulus, Poisson's ratio, "
        "friction";
    static constexpr plab_property_desc properties[] = {youngs_modulus, poisson_ratio, fric};
};

// History slots of the tangential spring (three, in this order): the
// tangential force on end 2, a vector in the contact plane, which the host
// turns with the plane before the law reads it (PLAB_HISTORY_TANGENTIAL).
inline constexpr plab_history_desc shear_force_x = plab::history_desc(
    "shear_force_x", 0.0, PLAB_SWAP_NEGATE, "Mindlin tangential force on end 2, global x, N", PLAB_HISTORY_TANGENTIAL);
inline constexpr plab_history_desc shear_force_y =
    plab::history_desc("shear_force_y", 0.0, PLAB_SWAP_NEGATE, "Mindlin tangential force on end 2, global y, N");
inline constexpr plab_history_desc shear_force_z =
    plab::history_desc("shear_force_z", 0.0, PLAB_SWAP_NEGATE, "Mindlin tangential force on end 2, global z, N");

// beta of H6: the damping ratio of a damped linear oscillator whose
// restitution is e (as a magnitude: >= 0, 0 for e = 1).
inline double damping_ratio(double e) {
    const double ln_e = std::log(e);
    return -ln_e / std::sqrt(ln_e * ln_e + kPi * kPi);
}

// The Rayleigh-wave speed factor of Johnson (1985) as DEM uses it (Li, Xu
// & Thornton 2005): T_R = pi R sqrt(rho/G) / (0.1631 nu + 0.8766).
inline double rayleigh_factor(double nu) { return 0.1631 * nu + 0.8766; }

struct Params {
    double E, nu, e, fric;
    int dp_mode;
    // derived once, not per contact
    double G = E / (2.0 * (1.0 + nu));
    double E_eff = E / (2.0 * (1.0 - nu * nu));  // E* of two ends of this solid
    double G_eff = G / (2.0 * (2.0 - nu));       // G*
    double beta = damping_ratio(e);
    double rayleigh_per_radius = kPi / rayleigh_factor(nu) / std::sqrt(G);  // T_R / (R sqrt(rho))
};

// each component of a or of b, as c says (a choice between values, not a branch)
inline Vec3 pick(bool c, const Vec3& a, const Vec3& b) { return {c ? a.x : b.x, c ? a.y : b.y, c ? a.z : b.z}; }

// What the law needs of one contact, and what it gives back.
struct State {
    Vec3 normal, rel_velocity, shear_force;  // shear force: the stored history, in the current contact plane
    double overlap, eff_radius, eff_mass, dt;
    bool planar;  // a 2D batch: the cylinder (line) contact
};
struct Result {
    Vec3 force, shear_force;                       // force on end 2; the history to store
    double strain, slip, dashpot;                  // strain energy; slip and dashpot energy to add
    double normal_stiffness, tangential_stiffness;  // S_n, S_t (H2, H3)
};

// The stiffnesses and elastic normal force at overlap d (H1-H3, H1'-H3').
struct Elastic {
    double force, normal_stiffness, tangential_stiffness, strain;
};
inline Elastic elastic(const Params& p, double d, double eff_radius, bool planar) {
    const double a = std::sqrt(eff_radius * d);  // Hertz contact radius
    // 3D: S_n = 2 E* a, F_n = (2/3) S_n d, strain (2/5) F_n d; 2D: a spring of pi/4 E* L (L = 1 m)
    const double s_n = planar ? 0.25 * kPi * p.E_eff : 2.0 * p.E_eff * a;
    const double s_t = planar ? kPi * p.G_eff : 8.0 * p.G_eff * a;
    const double f_n = planar ? s_n * d : (2.0 / 3.0) * s_n * d;
    return {f_n, s_n, s_t, (planar ? 0.5 : 0.4) * f_n * d};
}

// The law for one touching contact, as a function of values: every contact
// takes the same operations and the branches are choices between values,
// so that the adapter's loop over a batch vectorises.
inline Result law(const Params& p, const State& c) {
    const Vec3& n = c.normal;
    const double d = c.overlap > 0.0 ? c.overlap : 0.0;
    const Elastic el = elastic(p, d, c.eff_radius, c.planar);
    const Vec3& v = c.rel_velocity;
    const double vn = dot(v, n);
    const Vec3 vt = v - vn * n;

    // H6: Tsuji's dashpots, gamma = 2 c beta sqrt(S m*)
    const double c_damp = (c.planar ? 2.0 : 2.0 * std::sqrt(5.0 / 6.0)) * p.beta;
    const double sqrt_m = std::sqrt(c.eff_mass);
    double fn_d = -c_damp * std::sqrt(el.normal_stiffness) * sqrt_m * vn;  // on end 2
    const bool clip = (p.dp_mode == 1) & (el.force + fn_d < 0.0);
    fn_d = clip ? -el.force : fn_d;  // no_tension: no pull in total
    const double fn = el.force + fn_d;

    // H4, H5: the Mindlin spring, incremental on the stored force, capped by
    // Coulomb at mu times the elastic normal force (the dashpot's share of
    // the normal force gives no friction: the cap stays >= 0 in either mode)
    const Vec3& ft_old = c.shear_force;
    const Vec3 ft_trial = ft_old - el.tangential_stiffness * c.dt * vt;
    const double ft_max = p.fric * el.force;
    const double ft_mag2 = dot(ft_trial, ft_trial);  // compared squared: most contacts stick
    const bool sliding = ft_mag2 > ft_max * ft_max;
    const double cap = sliding ? ft_max / std::sqrt(ft_mag2) : 1.0;
    const Vec3 ft = ft_trial * cap;
    // the tangential dashpot acts while the contact sticks (a sliding contact dissipates by friction)
    const Vec3 ft_d_on = -c_damp * std::sqrt(el.tangential_stiffness) * sqrt_m * vt;
    const Vec3 ft_d = pick(sliding, Vec3{}, ft_d_on);

    Result r;
    r.force = fn * n + ft + ft_d;
    r.shear_force = ft;
    const double inv_st = el.tangential_stiffness > 0.0 ? 1.0 / el.tangential_stiffness : 0.0;
    r.strain = el.strain + 0.5 * dot(ft, ft) * inv_st;
    // energy dissipated by the slip displacement (ft_trial - ft)/S_t at mean force
    r.slip = sliding ? std::fabs(dot(0.5 * (ft + ft_old), (ft_trial - ft) * inv_st)) : 0.0;
    r.dashpot = -(fn_d * vn + dot(ft_d, vt)) * c.dt;
    r.normal_stiffness = el.normal_stiffness;
    r.tangential_stiffness = el.tangential_stiffness;
    return r;
}

// The Rayleigh time pi R sqrt(rho/G)/(0.1631 nu + 0.8766) of the smaller
// ball of contact c, the density from its mass and radius (a disc 1 m thick
// in 2D): the step limit of Hertzian DEM (Li, Xu & Thornton 2005), as S_n
// vanishes at first touch and sqrt(m / S_n) alone would allow any step.
inline double rayleigh_time(const Params& p, const Contact& c) {
    const bool second = !c.with_wall() && c.radius2() < c.radius1();
    const double r = second ? c.radius2() : c.radius1(), m = second ? c.mass2() : c.mass1();
    const double volume = c.dim() == 2 ? kPi * r * r : 4.0 / 3.0 * kPi * r * r * r;
    return p.rayleigh_per_radius * r * std::sqrt(m / volume);
}

// Applies the law to contact c with its tangential force stored in history
// slots [shear_slot, shear_slot + 3) (declared tangential). Returns the
// result; adds the slip and dashpot energies (the caller sets the force,
// strain energy, stiffness and step limit, and may add terms of its own).
inline Result apply(const Params& p, const Contact& c, int shear_slot) {
    const Result r = law(p, {c.normal(), c.rel_velocity(), c.history_vec(shear_slot), c.overlap(), c.eff_radius(),
                             c.eff_mass(), c.dt(), c.dim() == 2});
    c.set_history_vec(shear_slot, r.shear_force);
    c.add_slip_energy(r.slip);
    c.add_dashpot_energy(r.dashpot);
    return r;
}

} // namespace plab::hertz_law
