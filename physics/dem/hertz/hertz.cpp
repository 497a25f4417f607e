// The `hertz` contact model — Hertz–Mindlin (no slip) with Tsuji damping,
// LIGGGHTS's default and PFC's `hertz`: Hertz's normal force 4/3 E* sqrt(R*)
// d^(3/2), Mindlin–Deresiewicz's no-slip tangential stiffness 8 G* sqrt(R* d)
// with a Coulomb limit, dashpots from a coefficient of restitution; in 2D
// the cylinder (line) contact pi/4 E* L d. The law is
// plab::hertz_law::law (<plab/dem/hertz_law.hpp>); equations and sources in
// README.md here. Ball–ball and ball–wall alike: a wall end has infinite
// mass and radius, so the host passes m* = m_ball and R* = R_ball.
#include <plab/dem/cohesion.hpp>
#include <plab/dem/hertz_law.hpp>
#include <plab/dem/rolling_resistance.hpp>

#include <algorithm>

namespace {

using plab::Contact;
namespace rolling = plab::rolling_resistance;
namespace cohesion = plab::cohesion;

struct Hertz {
    static constexpr const char* name = "hertz";
    static constexpr const char* doc =
        "Hertz-Mindlin (no-slip) contact of elastic spheres: F_n = 4/3 E* sqrt(R*) d^1.5, tangential stiffness "
        "8 G* sqrt(R* d) on an incremental shear force capped at fric*F_n, Tsuji dashpots 2 sqrt(5/6) beta "
        "sqrt(S m*) from the restitution e; 2D: the cylinder contact pi/4 E* L d (L = 1 m). E, nu, fric from the "
        "groups' material dem_elastic. physics/dem/hertz/README.md.";
    static constexpr const char* timestep_rule =
        "min of 0.2 x the Rayleigh time pi R sqrt(rho/G)/(0.1631 nu + 0.8766) of the smaller ball and, per ball, "
        "sqrt(m / sum k) with k = max(S_n, S_t) the tangent normal (2 E* sqrt(R* d)) and tangential stiffness";
    static constexpr uint32_t range_kind = PLAB_RANGE_GAP;
    // reads radii and masses (the Rayleigh time of the smaller ball), the
    // effective mass and radius, and for the rolling resistance the spins
    // (the cohesion's contact area takes the radii);
    // writes a step limit and the rolling moments and stiffness besides
    // force, energies and translational stiffness
    static constexpr uint32_t io =
        PLAB_IO_RADII | PLAB_IO_MASSES | PLAB_IO_EFF_MASS | PLAB_IO_EFF_RADIUS | PLAB_IO_DT_LIMIT | rolling::io;
    // a scene material of its groups gives E, nu and fric; the rule gives e and dp_mode
    using material = plab::hertz_law::Material;

    enum Prop : int { youngs_modulus, poisson_ratio, restitution, fric, dp_mode, rr_fric, rr_dpratio, k_c, prop_count };
    static constexpr plab_property_desc properties[] = {
        plab::hertz_law::youngs_modulus, plab::hertz_law::poisson_ratio, plab::hertz_law::restitution,
        plab::hertz_law::fric,           plab::hertz_law::dp_mode,       rolling::rr_fric,
        rolling::rr_dpratio,             cohesion::cohesion_energy_density,
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");

    enum Slot : int { shear_force_x, shear_force_y, shear_force_z, rolling_moment_x, rolling_moment_y,
                      rolling_moment_z, cohesion_overlap, cohesion_energy, slot_count };
    static constexpr plab_history_desc history[] = {
        plab::hertz_law::shear_force_x, plab::hertz_law::shear_force_y, plab::hertz_law::shear_force_z,
        rolling::rolling_moment_x,      rolling::rolling_moment_y,      rolling::rolling_moment_z,
        cohesion::cohesion_overlap,     cohesion::cohesion_energy,
    };

    // only touching balls interact (Hertz: no force at a gap)
    static double activity_range(const double*) { return 0.0; }

    explicit Hertz(const double* p)
        : law_{p[youngs_modulus], p[poisson_ratio], p[restitution], p[fric], int(p[dp_mode])},
          rolling_{p[rr_fric], p[rr_dpratio]}, cohesion_energy_density_(p[k_c]) {}

    void law(const Contact& c) const {
        const plab::hertz_law::Result r = plab::hertz_law::apply(law_, c, shear_force_x);
        // rolling resistance (rrlinear's term, <plab/dem/rolling_resistance.hpp>) on the elastic
        // normal force, its spring the tangent tangential stiffness times Rbar^2; none with rr_fric 0
        const double fn = plab::hertz_law::elastic(law_, std::max(0.0, c.overlap()), c.eff_radius(), c.dim() == 2).force;
        const rolling::Result roll = rolling::apply(rolling_, r.tangential_stiffness, fn, c, rolling_moment_x);
        // simplified JKR cohesion (<plab/dem/cohesion.hpp>), attractive, on the contact area; none with k_c 0
        const cohesion::Result glue = cohesion::apply(cohesion_energy_density_, c, cohesion_overlap);
        c.set_force(r.force + glue.force);
        c.set_moment2(roll.moment);
        c.set_moment1(-roll.moment);
        c.set_strain_energy(r.strain + roll.strain + glue.strain);
        c.add_slip_energy(roll.slip);
        c.add_dashpot_energy(roll.dashpot);
        c.set_stiffness(std::max(r.normal_stiffness, r.tangential_stiffness), roll.stiffness);  // for the stable step
        c.set_dt_limit(kRayleighFraction * plab::hertz_law::rayleigh_time(law_, c));
    }

private:
    // the fraction of the Rayleigh time DEM takes as its step (0.1-0.3 in
    // the literature; EDEM's guidance 0.2, Li, Xu & Thornton 2005 0.2-0.4)
    static constexpr double kRayleighFraction = 0.2;
    plab::hertz_law::Params law_;
    rolling::Params rolling_;
    double cohesion_energy_density_;
};

} // namespace

PLAB_PLUGIN(plab::add_contact_model<Hertz>(r))
