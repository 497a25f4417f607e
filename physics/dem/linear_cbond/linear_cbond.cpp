// The `linear_cbond` contact model, PFC's linear contact bond (`linearcbond`):
// the `linear` law (thesis eqs. 21–29) whose contact, while bonded, is glued
// at a point. The bond carries force only, no moment: the normal spring may
// pull (tension), and the shear spring has no Coulomb limit. It breaks in
// tension when the tensile normal force reaches cb_tenf, else in shear when
// the shear force reaches cb_shearf; from then on the contact is `linear`,
// its shear force kept and capped at fric Fn by the linear law.
#include <plab/dem/linear_law.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace {

using plab::Contact;
using plab::Vec3;

constexpr double inf = std::numeric_limits<double>::infinity();

struct LinearCBond {
    static constexpr const char* name = "linear_cbond";
    static constexpr const char* doc =
        "Linear contact (kn, ks, fric, dashpots) with a contact bond (PFC linearcbond): while bonded the normal "
        "force may be tensile and the shear force is not limited by friction; the bond breaks in tension when "
        "-Fn >= cb_tenf, else in shear when |Fs| >= cb_shearf, and the contact is linear from then on. "
        "Force only: a bond carries no moment (linear_pbond does).";
    static constexpr const char* timestep_rule = "per ball sqrt(m / sum k) over its contacts, k = max(kn, ks)";
    static constexpr uint32_t range_kind = PLAB_RANGE_GAP;
    static constexpr uint32_t io = PLAB_IO_EFF_MASS | PLAB_IO_BREAK_ENERGY;
    using material = plab::linear_law::Material;

    enum Prop : int { kn, ks, fric, dp_nratio, dp_sratio, dp_mode, rgap, cb_tenf, cb_shearf, prop_count };
    static constexpr plab_property_desc properties[] = {
        plab::linear_law::kn,        plab::linear_law::ks,      plab::linear_law::fric, plab::linear_law::dp_nratio,
        plab::linear_law::dp_sratio, plab::linear_law::dp_mode, plab::linear_law::rgap,
        plab::prop::number("cb_tenf", "bond tensile strength", "N", inf, 0.0, inf, PLAB_MIN_EXCLUSIVE,
                           "the tensile normal force that breaks the bond; inf: never in tension"),
        plab::prop::number("cb_shearf", "bond shear strength", "N", inf, 0.0, inf, PLAB_MIN_EXCLUSIVE,
                           "the shear force that breaks the bond; inf: never in shear"),
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");

    enum Slot : int { shear_force_x, shear_force_y, shear_force_z, bond_state, slot_count };
    static constexpr plab_history_desc history[] = {
        plab::linear_law::shear_force_x,
        plab::linear_law::shear_force_y,
        plab::linear_law::shear_force_z,
        plab::history_desc("bond_state", 0.0, PLAB_SWAP_KEEP, "1 bonded, 0 unbonded or broken"),
    };
    static constexpr int persist_slot = bond_state;

    static double activity_range(const double* p) { return p[rgap]; }

    explicit LinearCBond(const double* p)
        : law_{p[kn], p[ks], p[fric], p[dp_nratio], p[dp_sratio], int(p[dp_mode]), p[rgap]},
          tensile_strength_(p[cb_tenf]), shear_strength_(p[cb_shearf]) {}

    void law(const Contact& c) const {
        double strain = 0;
        const Vec3 force = c.history(bond_state) > 0 ? bonded(c, strain) : plab::linear_law::apply(law_, c, shear_force_x, strain);
        c.set_force(force);
        c.set_strain_energy(strain);
        c.set_stiffness(std::max(law_.kn, law_.ks));
    }

private:
    Vec3 bonded(const Contact& c, double& strain) const;

    plab::linear_law::Params law_;
    double tensile_strength_, shear_strength_;
};

// The bonded contact: the linear springs without the no-tension and Coulomb
// limits (the glued point), the dashpots as the linear law's full mode
// (eqs. 27–28). The strength checks use the springs' forces; a bond that
// breaks this step releases its elastic energy and the contact takes the
// linear law at once.
Vec3 LinearCBond::bonded(const Contact& c, double& strain) const {
    const Vec3 n = c.normal();
    const Vec3 v = c.rel_velocity();
    const double vn = plab::dot(v, n);
    const Vec3 vs = v - vn * n;
    const double fn = law_.kn * (law_.rgap - c.gap());           // eq. 22, negative in tension
    const Vec3 fs = c.history_vec(shear_force_x) - law_.ks * c.dt() * vs;  // eqs. 23–25, no cap
    const double energy = 0.5 * fn * fn * law_.inv_kn + 0.5 * plab::dot(fs, fs) * law_.inv_ks;
    const int broke = -fn >= tensile_strength_ ? PLAB_BREAK_TENSION
                      : plab::norm(fs) >= shear_strength_ ? PLAB_BREAK_SHEAR : 0;
    if (broke) {
        c.history(bond_state) = -broke;  // the host records the break and leaves the contact unbonded
        c.add_break_energy(energy);
        c.set_history_vec(shear_force_x, fs);
        return plab::linear_law::apply(law_, c, shear_force_x, strain);
    }
    const double sqrt_m = std::sqrt(c.eff_mass());
    const double fn_d = -law_.cn * sqrt_m * vn;
    const Vec3 fs_d = -law_.cs * sqrt_m * vs;
    c.set_history_vec(shear_force_x, fs);
    c.add_dashpot_energy(-(fn_d * vn + plab::dot(fs_d, vs)) * c.dt());
    strain += energy;
    return (fn + fn_d) * n + fs + fs_d;
}

} // namespace

PLAB_PLUGIN(plab::add_contact_model<LinearCBond>(r))
