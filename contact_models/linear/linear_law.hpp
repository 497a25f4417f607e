// The linear contact law (thesis eqs. 21–29), shared by `linear` and by the
// linear component of `linear_pbond`: one law, written once.
#pragma once

#include <plab/contact_model.hpp>

#include <cmath>
#include <limits>

namespace plab::linear_law {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Property descriptions of the linear law, for every model built on it.
inline constexpr plab_property_desc kn = {"kn", "normal stiffness", "N/m", 1e6, 0.0, kInfinity,
                                          PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE, "linear normal spring (eq. 22)"};
inline constexpr plab_property_desc ks = {"ks", "shear stiffness", "N/m", 1e6, 0.0, kInfinity, PLAB_MAX_EXCLUSIVE,
                                          "linear shear spring (eq. 24)"};
inline constexpr plab_property_desc fric = {"fric", "friction coefficient", "1", 0.0, 0.0, kInfinity,
                                            PLAB_MAX_EXCLUSIVE, "Coulomb limit (eq. 26)"};
inline constexpr plab_property_desc dp_nratio = {"dp_nratio", "normal critical damping ratio", "1", 0.0, 0.0, 1.0,
                                                 PLAB_MAX_EXCLUSIVE, "normal dashpot 2*beta_n*sqrt(m*kn) (eq. 27)"};
inline constexpr plab_property_desc dp_sratio = {"dp_sratio", "shear critical damping ratio", "1", 0.0, 0.0, 1.0,
                                                 PLAB_MAX_EXCLUSIVE, "shear dashpot 2*beta_s*sqrt(m*ks) (eq. 28)"};
inline constexpr plab_property_desc dp_mode = {
    "dp_mode", "dashpot mode", "1", 0.0, 0.0, 3.0, PLAB_INTEGER,
    "0 full; 1 shear dashpot off while sliding; 2 total normal force >= 0 (no tension); 3 = 1 and 2"};
inline constexpr plab_property_desc rgap = {"rgap", "reference gap", "m", 0.0, -kInfinity, kInfinity,
                                            PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
                                            "the linear part is active while surface gap <= rgap"};

// History slots of the linear law's shear spring (three, in this order).
inline constexpr plab_history_desc shear_force_x = {"shear_force_x", 0.0, PLAB_SWAP_NEGATE,
                                                    "linear shear force on end 2, global x, N"};
inline constexpr plab_history_desc shear_force_y = {"shear_force_y", 0.0, PLAB_SWAP_NEGATE,
                                                    "linear shear force on end 2, global y, N"};
inline constexpr plab_history_desc shear_force_z = {"shear_force_z", 0.0, PLAB_SWAP_NEGATE,
                                                    "linear shear force on end 2, global z, N"};

struct Params {
    double kn, ks, fric, beta_n, beta_s;
    int dp_mode;
    double rgap;
    // derived once, not per contact: dashpot coefficients per sqrt(kg)
    // (2 beta sqrt(m k) = c sqrt(m), eqs. 27-28) and inverse stiffnesses
    double cn = 2.0 * beta_n * std::sqrt(kn), cs = 2.0 * beta_s * std::sqrt(ks);
    double inv_kn = 1.0 / kn, inv_ks = ks > 0.0 ? 1.0 / ks : 0.0;
};

// Keeps a stored vector (shear force, bending moment) in the current contact
// plane: project out the normal component and restore the magnitude (PFC's
// rotation of the shear force with the contact plane).
inline Vec3 rotate_into_plane(const Vec3& v, const Vec3& n) {
    const double mag2 = dot(v, v);
    if (mag2 == 0.0) return v;
    const Vec3 t = v - dot(v, n) * n;
    const double tmag2 = dot(t, t);
    return tmag2 > 0.0 ? t * std::sqrt(mag2 / tmag2) : Vec3{};
}

// Applies the law to contact c with its shear force stored in history slots
// [shear_slot, shear_slot + 3). Returns the force on end 2; adds the strain,
// slip and dashpot energies. Inactive (surface gap > rgap): zero force and
// the shear history is forgotten.
// (always inlined into the batch loop: GCC otherwise calls it once per contact)
[[gnu::always_inline]] inline Vec3 apply(const Params& p, const Contact& c, int shear_slot, double& strain) {
    const Vec3 n = c.normal();
    const double overlap = p.rgap - c.gap();  // surface gap relative to the reference gap
    if (overlap < 0.0) {
        c.set_history_vec(shear_slot, Vec3{});
        return Vec3{};
    }
    const Vec3 v = c.rel_velocity();
    const double vn = dot(v, n);
    const Vec3 vs = v - vn * n;
    const double dt = c.dt();
    const double fn_lin = p.kn * overlap;  // eq. 22

    const Vec3 fs_old = rotate_into_plane(c.history_vec(shear_slot), n);
    Vec3 fs = fs_old - p.ks * dt * vs;  // eqs. 23–25
    const double fs_max = p.fric * fn_lin;  // eq. 26
    const double fs_mag2 = dot(fs, fs);  // compared squared: most contacts stick, and need no sqrt
    bool sliding = false;
    if (fs_mag2 > fs_max * fs_max) {
        const double fs_mag = std::sqrt(fs_mag2);
        const Vec3 capped = fs * (fs_max / fs_mag);
        // energy dissipated by the slip displacement (fs - capped)/ks at mean force
        if (p.ks > 0.0) c.add_slip_energy(std::fabs(dot(0.5 * (capped + fs_old), (fs - capped) * p.inv_ks)));
        fs = capped;
        sliding = true;
    }
    c.set_history_vec(shear_slot, fs);

    const double sqrt_m = std::sqrt(c.eff_mass());
    double fn_d = -p.cn * sqrt_m * vn;  // eq. 27, on end 2
    const bool shear_dashpot = !((p.dp_mode == 1 || p.dp_mode == 3) && sliding);
    const Vec3 fs_d = shear_dashpot ? -p.cs * sqrt_m * vs : Vec3{};  // eq. 28
    if ((p.dp_mode == 2 || p.dp_mode == 3) && fn_lin + fn_d < 0.0) fn_d = -fn_lin;  // no tension in total

    strain += 0.5 * fn_lin * fn_lin * p.inv_kn + 0.5 * dot(fs, fs) * p.inv_ks;
    c.add_dashpot_energy(-(fn_d * vn + dot(fs_d, vs)) * dt);
    return (fn_lin + fn_d) * n + fs + fs_d;
}

} // namespace plab::linear_law
