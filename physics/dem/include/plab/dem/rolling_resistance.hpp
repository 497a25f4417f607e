// Rolling resistance: an elastic–plastic spring with a dashpot between the
// two ends' rotations, PFC's `rrlinear` rolling term with the viscous damping
// of Ai et al. (2011) model type C. Part of the SDK
// (<plab/dem/rolling_resistance.hpp>), for `rrlinear` and any law that adds
// the same rolling term to its own normal force (Hertz).
//
//   k_r = k_s R̄²                         rolling stiffness (PFC rrlinear)
//   M_r ← M_r − k_r Δθ_b                 Δθ_b: the bending part of (ω2 − ω1) dt
//   |M_r| ≤ M* = μ_r R̄ F_n               the limit moment (Ai eq. 17, PFC)
//   M_d = −2 η_r sqrt(I_r k_r) ω_b       Ai eqs. 14–16, zero while |M_r| = M*
//   |M_r + M_d| ≤ M*                     the dashpot adds no more than the limit leaves
//   1/I_r = Σ 1/(I_i + m_i r_i²)          the ends' inertia about the contact point (Ai eq. 15)
//
// The last line is not Ai's: without it a contact that begins while the
// balls roll, its spring not yet loaded, takes a dashpot moment far above
// the limit for a step (and at the host's force evaluation with dt = 0,
// for every rolling contact of a scene as it loads).
//
// R̄ is the effective radius r1 r2 / (r1 + r2) (the ball's radius against a
// wall), F_n the elastic normal force of the law it is added to, and I_i the
// inertia of a solid ball about its centre: 2/5 m r² in 3D, 1/2 m r² for the
// 2D disc.
#pragma once

#include <plab/contact_model.hpp>

#include <cmath>
#include <limits>

namespace plab::rolling_resistance {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

inline constexpr plab_property_desc rr_fric =
    plab::prop::number("rr_fric", "rolling resistance coefficient", "1", 0.0, 0.0, kInfinity, PLAB_MAX_EXCLUSIVE,
                       "mu_r: the rolling moment is at most mu_r Rbar Fn (PFC rrlinear)", PLAB_MIX_MIN);
inline constexpr plab_property_desc rr_dpratio =
    plab::prop::number("rr_dpratio", "rolling critical damping ratio", "1", 0.0, 0.0, 1.0, 0,
                       "rolling dashpot 2 eta_r sqrt(I_r k_r), off while the rolling spring is at its limit "
                       "(Ai et al. 2011, type C)", PLAB_MIX_ARITHMETIC);

// the rolling moment on end 2, three slots (x, y, z), in the contact plane
inline constexpr plab_history_desc rolling_moment_x = plab::history_desc(
    "rolling_moment_x", 0.0, PLAB_SWAP_NEGATE, "rolling resistance moment on end 2, global x, N m", PLAB_HISTORY_TANGENTIAL);
inline constexpr plab_history_desc rolling_moment_y =
    plab::history_desc("rolling_moment_y", 0.0, PLAB_SWAP_NEGATE, "rolling resistance moment on end 2, global y, N m");
inline constexpr plab_history_desc rolling_moment_z =
    plab::history_desc("rolling_moment_z", 0.0, PLAB_SWAP_NEGATE, "rolling resistance moment on end 2, global z, N m");

// the inputs it reads and the outputs it writes (a model adds them to its `io`)
inline constexpr uint32_t io = PLAB_IO_REL_ANGULAR_VELOCITY | PLAB_IO_RADII | PLAB_IO_MASSES | PLAB_IO_EFF_RADIUS |
                               PLAB_IO_MOMENTS | PLAB_IO_STIFFNESS_ROTATIONAL;

struct Params {
    double fric, beta;  // mu_r, eta_r
};

// A ball's inertia about the contact point, I + m r² (Ai eq. 15).
inline double inertia_at_contact(int dim, double mass, double radius) {
    const double about_centre = (dim == 2 ? 0.5 : 0.4) * mass * radius * radius;
    return about_centre + mass * radius * radius;
}

inline double equivalent_inertia(const Contact& c) {
    const double i1 = inertia_at_contact(c.dim(), c.mass1(), c.radius1());
    if (c.with_wall()) return i1;
    const double i2 = inertia_at_contact(c.dim(), c.mass2(), c.radius2());
    return i1 * i2 / (i1 + i2);
}

struct Result {
    Vec3 moment;        // on end 2 (end 1 takes its negative)
    double stiffness;   // k_r (0 when mu_r is), for the rotational stable step
    double strain, slip, dashpot;
};

// The rolling term of a contact whose elastic normal force is `fn` (>= 0;
// 0 when the contact is not touching, which forgets the stored moment) and
// whose shear stiffness is `ks`; the stored moment in history slots
// [slot, slot + 3), already turned into the contact plane by the host.
inline Result apply(const Params& p, double ks, double fn, const Contact& c, int slot) {
    const Vec3 n = c.normal();
    const double rbar = c.eff_radius();
    const double k_r = ks * rbar * rbar;
    const Vec3 w = c.rel_angular_velocity();
    const Vec3 w_bend = w - dot(w, n) * n;
    const Vec3 m_old = c.history_vec(slot);
    const Vec3 m_trial = m_old - k_r * c.dt() * w_bend;
    const double m_max = p.fric * rbar * fn;
    const double mag = norm(m_trial);
    const bool at_limit = mag > m_max;
    const Vec3 m_spring = at_limit ? m_trial * (m_max / mag) : m_trial;
    const double c_r = 2.0 * p.beta * std::sqrt(equivalent_inertia(c) * k_r);
    const Vec3 m_viscous = at_limit || !(fn > 0.0) ? Vec3{} : -c_r * w_bend;
    const Vec3 m_total = m_spring + m_viscous;
    const double total = norm(m_total);
    const Vec3 m_capped = total > m_max ? m_total * (m_max / total) : m_total;
    const Vec3 m_damp = m_capped - m_spring;
    c.set_history_vec(slot, m_spring);

    Result r;
    r.moment = m_capped;
    r.stiffness = p.fric > 0.0 ? k_r : 0.0;  // a spring capped at zero holds nothing
    const double inv_kr = k_r > 0.0 ? 1.0 / k_r : 0.0;
    r.strain = 0.5 * dot(m_spring, m_spring) * inv_kr;
    // the plastic rotation (m_trial - m_spring)/k_r at the mean moment
    r.slip = at_limit ? std::fabs(dot(0.5 * (m_spring + m_old), (m_trial - m_spring) * inv_kr)) : 0.0;
    r.dashpot = -dot(m_damp, w_bend) * c.dt();
    return r;
}

} // namespace plab::rolling_resistance
