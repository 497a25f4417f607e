// The `linear` contact model — thesis §3.1.1 and §3.2.1, eqs. 21–29, like
// PFC's `linear`: linear normal and shear springs in parallel with normal and
// shear dashpots; Coulomb-limited incremental shear force; no tension in the
// linear part. Works unchanged for ball–ball and ball–wall contacts (a wall
// has infinite mass, so the host passes eff_mass = m_ball).
#include <plab/dem/linear_law.hpp>

#include <algorithm>
#include <cmath>

namespace {

using plab::Contact;

struct Linear {
    static constexpr const char* name = "linear";
    static constexpr const char* doc =
        "Linear spring-dashpot contact with Coulomb friction (thesis eqs. 21-29; PFC linear). "
        "Normal force kn*overlap (no tension), incremental shear force -ks*vs*dt rotated into the "
        "current contact plane and capped at fric*Fn, dashpots 2*beta*sqrt(m*k).";
    static constexpr const char* timestep_rule =
        "per ball sqrt(m / sum k) over its contacts (translation) and sqrt(I / sum k r^2) (rotation), k = max(kn, ks)";
    static constexpr uint32_t range_kind = PLAB_RANGE_GAP;
    // reads the effective mass (dashpots) besides normal, gap and relative
    // velocity; writes no pure moment, rotational stiffness or step limit
    static constexpr uint32_t io = PLAB_IO_EFF_MASS;
    // a scene material of its groups gives the linear law's properties (kn, ..., rgap)
    using material = plab::linear_law::Material;

    enum Prop : int { kn, ks, fric, dp_nratio, dp_sratio, dp_mode, rgap, prop_count };
    static constexpr plab_property_desc properties[] = {
        plab::linear_law::kn,        plab::linear_law::ks,      plab::linear_law::fric, plab::linear_law::dp_nratio,
        plab::linear_law::dp_sratio, plab::linear_law::dp_mode, plab::linear_law::rgap,
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");

    enum Slot : int { shear_force_x, shear_force_y, shear_force_z, slot_count };
    static constexpr plab_history_desc history[] = {
        plab::linear_law::shear_force_x,
        plab::linear_law::shear_force_y,
        plab::linear_law::shear_force_z,
    };

    static double activity_range(const double* p) { return p[rgap]; }

    explicit Linear(const double* p)
        : law_{p[kn], p[ks], p[fric], p[dp_nratio], p[dp_sratio], int(p[dp_mode]), p[rgap]} {}

    void law(const Contact& c) const {
        double strain = 0;
        c.set_force(plab::linear_law::apply(law_, c, shear_force_x, strain));
        c.set_strain_energy(strain);
        c.set_stiffness(stiffness());
    }

private:
    double stiffness() const { return std::max(law_.kn, law_.ks); }  // for the stable step (timestep_rule)
    plab::linear_law::Params law_;
};

} // namespace

PLAB_PLUGIN(plab::add_contact_model<Linear>(r))
