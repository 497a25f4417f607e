// The `linear` contact model — thesis §3.1.1 and §3.2.1, eqs. 21–29, like
// PFC's `linear`: linear normal and shear springs in parallel with normal and
// shear dashpots; Coulomb-limited incremental shear force; no tension in the
// linear part. Works unchanged for ball–ball and ball–wall contacts (a wall
// has infinite mass, so the host passes eff_mass = m_ball).
#include <plab/contact_model.hpp>

#include <algorithm>
#include <cmath>

namespace {

using plab::Contact;
using plab::Vec3;

constexpr double inf = std::numeric_limits<double>::infinity();

struct Linear {
    static constexpr const char* name = "linear";
    static constexpr const char* doc =
        "Linear spring-dashpot contact with Coulomb friction (thesis eqs. 21-29; PFC linear). "
        "Normal force kn*overlap (no tension), incremental shear force -ks*vs*dt rotated into the "
        "current contact plane and capped at fric*Fn, dashpots 2*beta*sqrt(m*k).";
    static constexpr const char* timestep_rule =
        "per ball sqrt(m / sum k) over its contacts (translation) and sqrt(I / sum k r^2) (rotation), k = max(kn, ks)";
    static constexpr uint32_t range_kind = PLAB_RANGE_GAP;

    enum Prop : int { kn, ks, fric, dp_nratio, dp_sratio, dp_mode, rgap, prop_count };
    static constexpr plab_property_desc properties[] = {
        {"kn", "normal stiffness", "N/m", 1e6, 0.0, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
         "linear normal spring (eq. 22)"},
        {"ks", "shear stiffness", "N/m", 1e6, 0.0, inf, PLAB_MAX_EXCLUSIVE, "linear shear spring (eq. 24)"},
        {"fric", "friction coefficient", "1", 0.0, 0.0, inf, PLAB_MAX_EXCLUSIVE, "Coulomb limit (eq. 26)"},
        {"dp_nratio", "normal critical damping ratio", "1", 0.0, 0.0, 1.0, PLAB_MAX_EXCLUSIVE,
         "normal dashpot 2*beta_n*sqrt(m*kn) (eq. 27)"},
        {"dp_sratio", "shear critical damping ratio", "1", 0.0, 0.0, 1.0, PLAB_MAX_EXCLUSIVE,
         "shear dashpot 2*beta_s*sqrt(m*ks) (eq. 28)"},
        {"dp_mode", "dashpot mode", "1", 0.0, 0.0, 3.0, PLAB_INTEGER,
         "0 full; 1 shear dashpot off while sliding; 2 total normal force >= 0 (no tension); 3 = 1 and 2"},
        {"rgap", "reference gap", "m", 0.0, -inf, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
         "contact is active while surface gap <= rgap"},
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");

    enum Slot : int { shear_force_x, shear_force_y, shear_force_z, slot_count };
    static constexpr plab_history_desc history[] = {
        {"shear_force_x", 0.0, PLAB_SWAP_NEGATE, "linear shear force on end 2, global x, N"},
        {"shear_force_y", 0.0, PLAB_SWAP_NEGATE, "linear shear force on end 2, global y, N"},
        {"shear_force_z", 0.0, PLAB_SWAP_NEGATE, "linear shear force on end 2, global z, N"},
    };

    static double activity_range(const double* p) { return p[rgap]; }

    explicit Linear(const double* p)
        : kn_(p[kn]), ks_(p[ks]), fric_(p[fric]), beta_n_(p[dp_nratio]), beta_s_(p[dp_sratio]),
          mode_(int(p[dp_mode])), rgap_(p[rgap]) {}

    void law(const Contact& c) const;

private:
    double kn_, ks_, fric_, beta_n_, beta_s_;
    int mode_;
    double rgap_;
};

// Keeps the stored shear force in the current contact plane: project out the
// normal component and restore the magnitude (PFC's rotation of the shear
// force with the contact plane).
inline Vec3 rotate_into_plane(const Vec3& fs, const Vec3& n) {
    const double mag = plab::norm(fs);
    if (mag == 0.0) return fs;
    Vec3 t = fs - plab::dot(fs, n) * n;
    const double tmag = plab::norm(t);
    return tmag > 0.0 ? t * (mag / tmag) : Vec3{};
}

void Linear::law(const Contact& c) const {
    const Vec3 n = c.normal();
    const double overlap = rgap_ - c.gap();  // surface gap relative to the reference gap
    const Vec3 v = c.rel_velocity();
    const double vn = plab::dot(v, n);
    const Vec3 vs = v - vn * n;
    const double dt = c.dt();

    const double fn_lin = kn_ * overlap;  // eq. 22, >= 0 while active

    const Vec3 fs_old = rotate_into_plane(c.history_vec(shear_force_x), n);
    Vec3 fs = fs_old - ks_ * dt * vs;  // eqs. 23–25
    const double fs_max = fric_ * fn_lin;  // eq. 26
    const double fs_mag = plab::norm(fs);
    bool sliding = false;
    double slip = 0.0;
    if (fs_mag > fs_max) {
        const Vec3 capped = fs_mag > 0.0 ? fs * (fs_max / fs_mag) : Vec3{};
        // energy dissipated by the slip displacement (fs - capped)/ks at mean force
        if (ks_ > 0.0) slip = plab::dot(0.5 * (capped + fs_old), (fs - capped) / ks_);
        fs = capped;
        sliding = true;
    }
    c.set_history_vec(shear_force_x, fs);

    const double m = c.eff_mass();
    double fn_d = -2.0 * beta_n_ * std::sqrt(m * kn_) * vn;  // eq. 27, on end 2
    const bool shear_dashpot = !((mode_ == 1 || mode_ == 3) && sliding);
    const Vec3 fs_d = shear_dashpot ? -2.0 * beta_s_ * std::sqrt(m * ks_) * vs : Vec3{};  // eq. 28
    if ((mode_ == 2 || mode_ == 3) && fn_lin + fn_d < 0.0) fn_d = -fn_lin;  // no tension in total

    c.set_force((fn_lin + fn_d) * n + fs + fs_d);
    c.set_strain_energy(0.5 * fn_lin * fn_lin / kn_ + (ks_ > 0.0 ? 0.5 * plab::dot(fs, fs) / ks_ : 0.0));
    c.add_slip_energy(std::fabs(slip));
    c.add_dashpot_energy(-(fn_d * vn + plab::dot(fs_d, vs)) * dt);
    c.set_stiffness(std::max(kn_, ks_));
}

} // namespace

PLAB_PLUGIN(plab::add_contact_model<Linear>(r))
