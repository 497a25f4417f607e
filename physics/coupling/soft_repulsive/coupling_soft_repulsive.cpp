// `coupling_soft_repulsive`: Islam's soft repulsive particle contact between
// fluid and structure particles (Islam eqs. 21–24, after Zhang et al. 2018),
// the second selectable fluid–structure law beside the `sph` pair force
// (thesis §4.2). A finite, distance-dependent repulsion along the line of
// centres; the fluid and the structure see each other only through it:
//   a_ij = 0.01 c² ζ f(η) x_ij / r²                       (eq. 21)
//   η = r / (0.75 h)                                        (eq. 22)
//   ζ = 1 - r/Δp, 0 < r < Δp                                (eq. 23; the
//       text's Δd is read as the particle spacing Δp of its range)
//   f(η) = 2/3 (η ≤ 2/3); 2η - 1.5η² (≤ 1); 0.5 (2 - η)² (≤ 2); 0   (eq. 24;
//       the printed 0.5(2 - η²) turns negative past η = √2 and is not zero
//       at η = 2; the spline form 0.5(2 - η)² of Monaghan & Kajtar's
//       boundary force, which Zhang 2018 uses, is — taken. Both agree at
//       η = 1, and with h ≈ 1.25 dp the range r < dp keeps η below 1.07)
// eq. 21 is an acceleration. To keep the pair force equal and opposite it
// is applied with the pair's mass 2 m1 m2 / (m1 + m2) (= m for equal masses).
#include <plab/contact_model.hpp>
#include <plab/sph/material.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace {

using plab::Vec3;

constexpr double inf = std::numeric_limits<double>::infinity();

struct SoftRepulsive {
    static constexpr const char* name = "coupling_soft_repulsive";
    static constexpr const char* doc =
        "Soft repulsive fluid-structure contact (Islam eqs. 21-24): force 2 m1 m2/(m1+m2) 0.01 c^2 zeta f(eta) / r "
        "along the line of centres, active for r < min(dp, 1.5 h). Assign to fluid x structure instead of sph.";
    static constexpr const char* timestep_rule = "per pair: 0.25 h/(c + |v_rel|), the SPH CFL limit";
    static constexpr uint32_t range_kind = PLAB_RANGE_DISTANCE;
    static constexpr uint32_t io = PLAB_IO_MASSES | PLAB_IO_DT_LIMIT;
    // c and h are the fluid's (the SPH package's material): the strength
    // scales with c^2, eta = r/(0.75 h) (eq. 22)
    using material = plab::sph::FluidMaterial;

    enum Prop : int { speed_of_sound, smoothing_length, spacing, prop_count };
    static constexpr plab_property_desc properties[] = {
        plab::sph::fluid::speed_of_sound,
        plab::sph::fluid::smoothing_length,
        plab::prop::number("spacing", "particle spacing dp", "m", 0.005, 0.0, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
         "zeta = 1 - r/dp, eq. 23: the contact acts inside one spacing"),
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");

    static double activity_range(const double* p) { return std::min(p[spacing], 1.5 * p[smoothing_length]); }

    explicit SoftRepulsive(const double* p) : c_(p[speed_of_sound]), h_(p[smoothing_length]), dp_(p[spacing]) {}

    void law(const plab::Contact& c) const {
        c.set_dt_limit(0.25 * h_ / (c_ + plab::norm(c.rel_velocity())));
        if (c.with_wall()) return;  // walls: the host's ball–wall models
        const double r = c.distance();
        if (!(r > 0) || r >= dp_) return;
        const double zeta = 1 - r / dp_;
        const double f = shape(r / (0.75 * h_));
        const double pair_mass = 2 * c.mass1() * c.mass2() / (c.mass1() + c.mass2());
        // x_ij / r² = n / r along the line from the other end: end 2 is pushed along +n
        c.set_force(c.normal() * (pair_mass * 0.01 * c_ * c_ * zeta * f / r));
        c.set_stiffness(0);
    }

private:
    // eq. 24 with the continuous (2 - η)² branch
    static double shape(double eta) {
        if (eta <= 2.0 / 3.0) return 2.0 / 3.0;
        if (eta <= 1.0) return 2 * eta - 1.5 * eta * eta;
        if (eta <= 2.0) return 0.5 * (2 - eta) * (2 - eta);
        return 0;
    }

    double c_, h_, dp_;
};

} // namespace

PLAB_PLUGIN(plab::add_contact_model<SoftRepulsive>(r))
