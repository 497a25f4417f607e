// The linear contact law (thesis eqs. 21–29), shared by `linear` and by the
// linear components of `linear_pbond` and `linear_lubrication`: one law,
// written once. Part of the SDK (<plab/dem/linear_law.hpp>), for a model
// of its own built on the same spring-dashpot.
#pragma once

#include <plab/contact_model.hpp>

#include <cmath>
#include <limits>

namespace plab::linear_law {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Property descriptions of the linear law, for every model built on it.
inline constexpr plab_property_desc kn = plab::prop::number("kn", "normal stiffness", "N/m", 1e6, 0.0, kInfinity,
                                          PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE, "linear normal spring (eq. 22)",
                                          PLAB_MIX_HARMONIC);
inline constexpr plab_property_desc ks = plab::prop::number("ks", "shear stiffness", "N/m", 1e6, 0.0, kInfinity, PLAB_MAX_EXCLUSIVE,
                                          "linear shear spring (eq. 24)", PLAB_MIX_HARMONIC);
inline constexpr plab_property_desc fric = plab::prop::number("fric", "friction coefficient", "1", 0.0, 0.0, kInfinity,
                                            PLAB_MAX_EXCLUSIVE, "Coulomb limit (eq. 26)", PLAB_MIX_MIN);
inline constexpr plab_property_desc dp_nratio = plab::prop::number("dp_nratio", "normal critical damping ratio", "1", 0.0, 0.0, 1.0,
                                                 PLAB_MAX_EXCLUSIVE, "normal dashpot 2*beta_n*sqrt(m*kn) (eq. 27)",
                                                 PLAB_MIX_ARITHMETIC);
inline constexpr plab_property_desc dp_sratio = plab::prop::number("dp_sratio", "shear critical damping ratio", "1", 0.0, 0.0, 1.0,
                                                 PLAB_MAX_EXCLUSIVE, "shear dashpot 2*beta_s*sqrt(m*ks) (eq. 28)",
                                                 PLAB_MIX_ARITHMETIC);
// the dashpot modes (PFC's dp_mode 0-3), the law's `dp_mode` in this order
inline constexpr const char* dp_mode_names[] = {"full", "slip_shear", "no_tension", "no_tension_slip_shear"};
inline constexpr plab_property_desc dp_mode = plab::prop::choice(
    "dp_mode", "dashpot mode", dp_mode_names, 0,
    "full: both dashpots always; slip_shear: the shear dashpot off while sliding; no_tension: the total normal "
    "force kept >= 0 (the dashpot never pulls); no_tension_slip_shear: both");
inline constexpr plab_property_desc rgap = plab::prop::number("rgap", "reference gap", "m", 0.0, -kInfinity, kInfinity,
                                            PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
                                            "the linear part is active while surface gap <= rgap");

// The DEM package's material, "dem_linear" (abi.h plab_material_desc): the
// linear law's properties, which a scene may state per group of balls,
//   "materials": {"sand": {"groups": ["sand"], "kn": 1e6, "fric": 0.5}, "glass": {...}},
// and which a contact between groups of two materials mixes by each
// property's rule (kn, ks harmonic; fric the smaller; the damping ratios
// arithmetic; dp_mode and rgap must agree). A model built on the law takes
// them with `using material = plab::linear_law::Material;`.
struct Material {
    static constexpr const char* name = "dem_linear";
    static constexpr const char* doc =
        "the linear spring-dashpot contact of a group of balls: stiffnesses, friction, damping ratios, dashpot mode, "
        "reference gap (thesis eqs. 21-29)";
    static constexpr plab_property_desc properties[] = {kn, ks, fric, dp_nratio, dp_sratio, dp_mode, rgap};
};

// History slots of the linear law's shear spring (three, in this order): a
// vector in the contact plane, which the host turns with the plane before
// the law reads it (abi.h, PLAB_HISTORY_TANGENTIAL).
inline constexpr plab_history_desc shear_force_x = plab::history_desc("shear_force_x", 0.0, PLAB_SWAP_NEGATE,
                                                    "linear shear force on end 2, global x, N", PLAB_HISTORY_TANGENTIAL);
inline constexpr plab_history_desc shear_force_y = plab::history_desc("shear_force_y", 0.0, PLAB_SWAP_NEGATE,
                                                    "linear shear force on end 2, global y, N");
inline constexpr plab_history_desc shear_force_z = plab::history_desc("shear_force_z", 0.0, PLAB_SWAP_NEGATE,
                                                    "linear shear force on end 2, global z, N");

struct Params {
    double kn, ks, fric, beta_n, beta_s;
    int dp_mode;
    double rgap;
    // derived once, not per contact: dashpot coefficients per sqrt(kg)
    // (2 beta sqrt(m k) = c sqrt(m), eqs. 27-28) and inverse stiffnesses
    double cn = 2.0 * beta_n * std::sqrt(kn), cs = 2.0 * beta_s * std::sqrt(ks);
    double inv_kn = 1.0 / kn, inv_ks = ks > 0.0 ? 1.0 / ks : 0.0;
};

// each component of a or of b, as c says (a choice between values, not a branch)
inline Vec3 pick(bool c, const Vec3& a, const Vec3& b) { return {c ? a.x : b.x, c ? a.y : b.y, c ? a.z : b.z}; }

// What the law needs of one contact, and what it gives back.
struct State {
    Vec3 normal, rel_velocity, shear_force;  // shear force: the stored history, in the current contact plane
    double gap, eff_mass, dt;
};
struct Result {
    Vec3 force, shear_force;       // force on end 2; the history to store
    double strain, slip, dashpot;  // strain energy; slip and dashpot energy to add
};

// The law (eqs. 21–29) for one contact, as a function of values: every
// contact takes the same operations and the branches are choices between
// values, so that the adapter's loop over a batch vectorises. Inactive
// (surface gap > rgap): zero force and energies, and the shear history is
// forgotten.
inline Result law(const Params& p, const State& c) {
    const Vec3& n = c.normal;
    const double overlap = p.rgap - c.gap;  // surface gap relative to the reference gap
    const bool active = !(overlap < 0.0);
    const Vec3& v = c.rel_velocity;
    const double vn = dot(v, n);
    const Vec3 vs = v - vn * n;
    const double fn_lin = p.kn * overlap;  // eq. 22

    const Vec3& fs_old = c.shear_force;
    const Vec3 fs_trial = fs_old - p.ks * c.dt * vs;  // eqs. 23–25
    const double fs_max = p.fric * fn_lin;            // eq. 26
    const double fs_mag2 = dot(fs_trial, fs_trial);   // compared squared: most contacts stick
    const bool sliding = fs_mag2 > fs_max * fs_max;
    // (the work of a sliding contact inside the choices: a scalar loop
    // branches around it, a vectorised one takes both sides)
    const double cap = sliding ? fs_max / std::sqrt(fs_mag2) : 1.0;
    const Vec3 fs = fs_trial * cap;  // (x 1: the same bits)

    const double sqrt_m = std::sqrt(c.eff_mass);
    double fn_d = -p.cn * sqrt_m * vn;  // eq. 27, on end 2
    // (& and |, not && and ||: no branch in a vectorised loop)
    const bool shear_dashpot = !(((p.dp_mode == 1) | (p.dp_mode == 3)) & sliding);
    const Vec3 fs_d_on = -p.cs * sqrt_m * vs;  // eq. 28
    const Vec3 fs_d = pick(shear_dashpot, fs_d_on, Vec3{});
    const bool no_tension = ((p.dp_mode == 2) | (p.dp_mode == 3)) & (fn_lin + fn_d < 0.0);
    fn_d = no_tension ? -fn_lin : fn_d;  // no tension in total

    const double strain = 0.5 * fn_lin * fn_lin * p.inv_kn + 0.5 * dot(fs, fs) * p.inv_ks;
    const double dashpot = -(fn_d * vn + dot(fs_d, vs)) * c.dt;
    const Vec3 force = (fn_lin + fn_d) * n + fs + fs_d;
    Result r;
    r.force = pick(active, force, Vec3{});
    r.shear_force = pick(active, fs, Vec3{});
    r.strain = active ? strain : 0.0;
    // energy dissipated by the slip displacement (fs_trial - fs)/ks at mean force
    r.slip = active & sliding & (p.ks > 0.0) ? std::fabs(dot(0.5 * (fs + fs_old), (fs_trial - fs) * p.inv_ks)) : 0.0;
    r.dashpot = active ? dashpot : 0.0;
    return r;
}

// Applies the law to contact c with its shear force stored in history slots
// [shear_slot, shear_slot + 3) (declared tangential). Returns the force on
// end 2; adds the strain, slip and dashpot energies.
inline Vec3 apply(const Params& p, const Contact& c, int shear_slot, double& strain) {
    const Result r = law(p, {c.normal(), c.rel_velocity(), c.history_vec(shear_slot), c.gap(), c.eff_mass(), c.dt()});
    c.set_history_vec(shear_slot, r.shear_force);
    c.add_slip_energy(r.slip);
    c.add_dashpot_energy(r.dashpot);
    strain += r.strain;
    return r.force;
}

} // namespace plab::linear_law
