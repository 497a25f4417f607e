// The force stage of the `sph` pair interaction (thesis eqs. 14–17; Islam
// eqs. 8–9) between two balls, as a function of values: the pair's inputs
// in, the force on end 2 and the step limit out. Every pair takes the same
// operations and the branches are choices between values, so that a loop
// over a batch of pairs can be vectorised (sph.cpp, law_rows); the model's
// law() for one Contact calls the same function, so both give the same bits.
// The kernel and the viscosity model are template parameters (one loop per
// scene's choice, no test of either per pair).
// Header-only and free of host types, part of the SDK (<plab/sph/law.hpp>).
#pragma once

#include <plab/sph/kernels.hpp>

#include <plab/vec3.hpp>

#include <algorithm>
#include <cmath>

namespace plab::sph {

// Which viscous term the force carries (property `viscosity`, `mu`).
enum class Viscosity : int { none = 0, morris = 1, monaghan = 2 };

// The model's constants, derived once per instance.
struct LawParams {
    KernelKind kind;
    Viscosity viscosity;
    double h, inv_h, rho0, c0, mu, alpha, beta;
    double anticlump;          // (v_max/c0)^2 of eq. 17; 0: off
    double support;            // kernel support, m
    double eta2;               // 0.01 h^2 of the viscous terms, m^2
    double cfl_length;         // 0.25 h of the CFL limit, m
    double viscous_dt;         // 0.125 h^2 rho0/mu (Morris), s
    double derivative_scale[2];  // dW/dr = scale[dim 3] f'(r/h)
    double value_scale[2];       // W = scale[dim 3] f(r/h)
    double w_dp[2];              // W(dp) of eq. 17, 2D and 3D
};

// One pair's inputs: unit normal from end 1 to end 2, v_rel = v2 - v1,
// centre distance, masses, densities (the field as read: rho_or_rest()
// takes rho0 for a non-positive one), pressures and the no-slip wall
// velocity corrections of both ends.
struct Pair {
    Vec3 normal, rel_velocity, wall_dv1, wall_dv2;
    double r, m1, m2, rho1, rho2, p1, p2;
};
struct PairForce {
    Vec3 force;       // on end 2, N
    double dt_limit;  // s
};

// The host's nominal-timestep probe passes zero fields: fall back to rho0.
inline double rho_or_rest(double rho, double rho0) { return rho > 0 ? rho : rho0; }

// CFL on the sound speed plus the pair's relative speed; the viscous
// diffusion limit 0.125 h^2/nu for the laminar model.
template <Viscosity V> [[gnu::always_inline]] inline double step_limit(const LawParams& p, double speed) {
    const double dt = p.cfl_length / (p.c0 + speed);
    return V == Viscosity::morris ? std::min(dt, p.viscous_dt) : dt;
}

// eq. 17: R_ij = (v_max/c0)^2 |p_i/rho_i^2 + p_j/rho_j^2| (W_ij / W(dp))^4
template <KernelKind K> [[gnu::always_inline]] inline double anticlump_term(const LawParams& p, int dim3, double r, double p_term) {
    const double ratio = p.value_scale[dim3] * detail::shape(K, r * p.inv_h) / p.w_dp[dim3];
    return p.anticlump * std::fabs(p_term) * ratio * ratio * ratio * ratio;
}

// Islam eqs. 8–9: Pi = (-alpha c0 mu_ij + beta mu_ij^2)/rho_bar while
// approaching (v_ij.x_ij < 0), mu_ij = h v_ij.x_ij/(r^2 + 0.01h^2) with
// v_ij.x_ij = r (v_rel.n); zero while separating (v_n >= 0; NaN passes on).
[[gnu::always_inline]] inline double monaghan(const LawParams& p, double r, double v_n, double rho1, double rho2) {
    const double mu_ij = p.h * r * v_n / (r * r + p.eta2);
    const double pi = (-p.alpha * p.c0 * mu_ij + p.beta * mu_ij * mu_ij) / (0.5 * (rho1 + rho2));
    return !(v_n >= 0) ? pi : 0.0;
}

// eqs. 15–16: m2 dv2/dt = -m1 m2 (p1/rho1^2 + p2/rho2^2 + Pi + R) grad_2 W_21,
// grad_2 W_21 = dW/dr n; with Morris viscosity (eq. 14) also
// m1 m2 2 mu r dW/dr / (rho1 rho2 (r^2 + 0.01h^2)) v_visc. The viscous terms
// see a no-slip wall ball at its extrapolated velocity (Adami 2012). Zero
// force beyond the support; the step limit always.
// (always inlined: the batch loop vectorises only with the law inside it)
template <KernelKind K, Viscosity V, bool Anticlump>
[[gnu::always_inline]] inline PairForce pair_force(const LawParams& p, int dim3, const Pair& s) {
    const Vec3& n = s.normal;
    const double r = s.r;
    // q = r/h as r (1/h): the divider is what bounds the vectorised loop
    const double dW = p.derivative_scale[dim3] * detail::shape_derivative(K, r * p.inv_h);  // <= 0
    const double rho1 = rho_or_rest(s.rho1, p.rho0), rho2 = rho_or_rest(s.rho2, p.rho0);
    const double p_term = s.p1 / (rho1 * rho1) + s.p2 / (rho2 * rho2);
    double scalar = p_term;
    if (Anticlump) scalar += anticlump_term<K>(p, dim3, r, p_term);
    const Vec3 v_visc = s.rel_velocity + s.wall_dv2 - s.wall_dv1;
    if (V == Viscosity::monaghan) scalar += monaghan(p, r, dot(v_visc, n), rho1, rho2);
    Vec3 f2 = (-s.m1 * s.m2 * scalar * dW) * n;
    if (V == Viscosity::morris) f2 += (s.m1 * s.m2 * 2 * p.mu * r * dW / (rho1 * rho2 * (r * r + p.eta2))) * v_visc;
    const bool inside = r < p.support;
    PairForce out;
    out.force = {inside ? f2.x : 0.0, inside ? f2.y : 0.0, inside ? f2.z : 0.0};
    out.dt_limit = step_limit<V>(p, norm(s.rel_velocity));
    return out;
}

// Calls f(kernel, viscosity, anticlump) with the three as compile-time
// constants (std::integral_constant), for the instance's choices.
template <class F> decltype(auto) with_choices(const LawParams& p, F&& f) {
    using KK = KernelKind;
    using VV = Viscosity;
    const auto by_viscosity = [&](auto k, auto a) -> decltype(auto) {
        switch (p.viscosity) {
        case VV::none: return f(k, std::integral_constant<VV, VV::none>{}, a);
        case VV::morris: return f(k, std::integral_constant<VV, VV::morris>{}, a);
        case VV::monaghan: break;
        }
        return f(k, std::integral_constant<VV, VV::monaghan>{}, a);
    };
    const auto by_kernel = [&](auto a) -> decltype(auto) {
        switch (p.kind) {
        case KK::wendland_c2: return by_viscosity(std::integral_constant<KK, KK::wendland_c2>{}, a);
        case KK::quintic_spline: return by_viscosity(std::integral_constant<KK, KK::quintic_spline>{}, a);
        case KK::cubic_spline: break;
        }
        return by_viscosity(std::integral_constant<KK, KK::cubic_spline>{}, a);
    };
    if (p.anticlump > 0) return by_kernel(std::true_type{});
    return by_kernel(std::false_type{});
}

} // namespace plab::sph
