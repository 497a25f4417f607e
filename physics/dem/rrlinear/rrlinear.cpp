// The `rrlinear` contact model, PFC's rolling-resistance linear model: the
// `linear` law (thesis eqs. 21–29) and, in parallel, an elastic–plastic
// rolling spring with a dashpot between the two ends' rotations
// (<plab/dem/rolling_resistance.hpp>: PFC rrlinear's k_r = ks Rbar² and limit
// mu_r Rbar Fn, the dashpot of Ai et al. 2011, type C).
#include <plab/dem/linear_law.hpp>
#include <plab/dem/rolling_resistance.hpp>

#include <algorithm>
#include <cmath>

namespace {

using plab::Contact;
using plab::Vec3;
namespace rolling = plab::rolling_resistance;

struct RRLinear {
    static constexpr const char* name = "rrlinear";
    static constexpr const char* doc =
        "Linear spring-dashpot contact with Coulomb friction (PFC linear) and rolling resistance (PFC rrlinear): a "
        "rolling spring ks*Rbar^2 on the relative bending rotation, its moment capped at rr_fric*Rbar*Fn, with a "
        "rolling dashpot while below the cap (Ai et al. 2011 type C).";
    static constexpr const char* timestep_rule =
        "per ball sqrt(m / sum k) with k = max(kn, ks) (translation) and sqrt(I / sum (ks Rbar^2 + k r^2)) (rotation)";
    static constexpr uint32_t range_kind = PLAB_RANGE_GAP;
    static constexpr uint32_t io = PLAB_IO_EFF_MASS | rolling::io;
    using material = plab::linear_law::Material;

    enum Prop : int { kn, ks, fric, dp_nratio, dp_sratio, dp_mode, rgap, rr_fric, rr_dpratio, prop_count };
    static constexpr plab_property_desc properties[] = {
        plab::linear_law::kn,        plab::linear_law::ks,      plab::linear_law::fric, plab::linear_law::dp_nratio,
        plab::linear_law::dp_sratio, plab::linear_law::dp_mode, plab::linear_law::rgap, rolling::rr_fric,
        rolling::rr_dpratio,
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");

    enum Slot : int { shear_force_x, shear_force_y, shear_force_z, rolling_moment_x, rolling_moment_y, rolling_moment_z,
                      slot_count };
    static constexpr plab_history_desc history[] = {
        plab::linear_law::shear_force_x, plab::linear_law::shear_force_y, plab::linear_law::shear_force_z,
        rolling::rolling_moment_x,       rolling::rolling_moment_y,       rolling::rolling_moment_z,
    };

    static double activity_range(const double* p) { return p[rgap]; }

    explicit RRLinear(const double* p)
        : law_{p[kn], p[ks], p[fric], p[dp_nratio], p[dp_sratio], int(p[dp_mode]), p[rgap]},
          rolling_{p[rr_fric], p[rr_dpratio]} {}

    void law(const Contact& c) const {
        double strain = 0;
        c.set_force(plab::linear_law::apply(law_, c, shear_force_x, strain));
        const double fn = std::max(0.0, law_.kn * (law_.rgap - c.gap()));  // the elastic normal force (eq. 22)
        const rolling::Result r = rolling::apply(rolling_, law_.ks, fn, c, rolling_moment_x);
        c.set_moment2(r.moment);
        c.set_moment1(-r.moment);
        c.set_strain_energy(strain + r.strain);
        c.add_slip_energy(r.slip);
        c.add_dashpot_energy(r.dashpot);
        c.set_stiffness(std::max(law_.kn, law_.ks), r.stiffness);
    }

private:
    plab::linear_law::Params law_;
    rolling::Params rolling_;
};

} // namespace

PLAB_PLUGIN(plab::add_contact_model<RRLinear>(r))
