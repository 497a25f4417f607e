// The `sph` contact model: weakly compressible SPH (WCSPH) written as an
// "indirect contact" between two fluid balls within the kernel support, as
// in the thesis §2.2 (Wu 2017, PFC2D plug-in). For each pair it adds
//   * the continuity-equation term (thesis eq. 7) to dρ/dt of both ends,
//   * the symmetric pressure + viscous pair force (thesis eqs. 14–16) as the
//     contact force on end 2; the host applies its opposite to end 1, so
//     linear momentum is conserved to round-off.
// Viscosity: Morris laminar (thesis eq. 14) or Monaghan artificial
// (Islam eqs. 8–9). Optional anti-clump term R_ij (thesis eq. 17) and
// δ-SPH density diffusion (Islam eq. 6). No-slip walls (Adami et al. 2012):
// the viscous terms see a boundary ball moving at its extrapolated wall
// velocity, its own velocity plus the field sph_wall_velocity_correction
// that the sph_wall_pressure pass sets (zero for fluid balls).
// The continuity sum is accumulated in the host's rates stage; the passes
// `sph_density_integration`, `sph_eos` and `sph_wall_pressure` (phase
// RATES_DONE) turn it into density and pressure before the force stage.
//
// Conventions: n is the unit normal from end 1 to end 2, x_2 - x_1 = r n,
// v_rel = v_2 - v_1; dW/dr <= 0 and ∇_2 W_21 = dW/dr n = -∇_1 W_12.
#include "sph_kernels.hpp"

#include <plab/contact_model.hpp>

#include <algorithm>
#include <cmath>

namespace {

using plab::Contact;
using plab::Vec3;
using plab::sph::Kernel;
using plab::sph::KernelKind;

constexpr double inf = std::numeric_limits<double>::infinity();

struct Sph {
    static constexpr const char* name = "sph";
    static constexpr const char* doc =
        "Weakly compressible SPH pair interaction (thesis eqs. 7, 11-17; Islam eqs. 5, 8-9): continuity term "
        "into sph_drho_dt of both ends, symmetric pressure + viscous force m1 m2 (p1/rho1^2 + p2/rho2^2 + Pi) grad W. "
        "Use with the sph_density_integration and sph_eos passes; fluid balls must have their rotation fixed "
        "(the laminar viscous force is not central).";
    static constexpr const char* timestep_rule =
        "per pair: CFL 0.25 h/(c0 + |v_rel|); laminar viscosity also 0.125 h^2 rho0/mu";
    static constexpr uint32_t range_kind = PLAB_RANGE_DISTANCE;
    // particles interact through their centres: the host skips spin, moments,
    // stiffness and energies for the ball–ball rows (abi.h, ABI 4)
    static constexpr uint32_t flags = PLAB_MODEL_FORCE_AT_CENTRES;
    // reads the two masses (not the effective mass or radius, the radii or
    // the spin) and writes a step limit (abi.h, ABI 5)
    static constexpr uint32_t io = PLAB_IO_MASSES | PLAB_IO_DT_LIMIT;

    enum Prop : int {
        smoothing_length, kernel, rest_density, speed_of_sound, viscosity, mu, alpha, beta,
        anticlump, anticlump_spacing, density_diffusion, prop_count
    };
    static constexpr plab_property_desc properties[] = {
        {"smoothing_length", "smoothing length h", "m", 0.005, 0.0, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
         "kernel support is 2h (Wendland C2, cubic spline) or 3h (quintic)"},
        // defaults 1 (not 0): the contract suite moves a zero default into the
        // range (0 -> 0.6), which is not a whole number (docs/sph.md)
        {"kernel", "kernel function", "1", 1.0, 0.0, 2.0, PLAB_INTEGER,
         "0 Wendland C2 (eq. 12, the thesis' choice), 1 cubic spline (eq. 11), 2 quintic spline"},
        {"rest_density", "reference density rho0", "kg/m3", 1000.0, 0.0, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
         "used for the viscous step limit and for a body whose density field is not set"},
        {"speed_of_sound", "numerical speed of sound c0", "m/s", 20.0, 0.0, inf,
         PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE, "CFL limit and Monaghan viscosity; about 10 x the largest flow speed"},
        {"viscosity", "viscosity model", "1", 1.0, 0.0, 1.0, PLAB_INTEGER,
         "0 Morris laminar with dynamic viscosity mu (eq. 14); 1 Monaghan artificial with alpha, beta (Islam eq. 8)"},
        {"mu", "dynamic viscosity", "Pa s", 8.9e-4, 0.0, inf, PLAB_MAX_EXCLUSIVE, "laminar model (viscosity 0)"},
        {"alpha", "artificial viscosity alpha", "1", 0.02, 0.0, inf, PLAB_MAX_EXCLUSIVE,
         "linear term of the Monaghan viscosity (viscosity 1)"},
        {"beta", "artificial viscosity beta", "1", 0.0, 0.0, inf, PLAB_MAX_EXCLUSIVE,
         "quadratic term of the Monaghan viscosity (viscosity 1)"},
        {"anticlump", "anti-clump coefficient (v_max/c0)^2", "1", 0.0, 0.0, inf, PLAB_MAX_EXCLUSIVE,
         "R_ij of eq. 17; 0 switches it off, the thesis uses 0.01"},
        {"anticlump_spacing", "initial particle spacing for W(dp)", "m", 0.0, 0.0, inf, PLAB_MAX_EXCLUSIVE,
         "dp in (W_ij / W(dp))^4 of eq. 17; 0: dp = h; a dp outside the kernel support switches R_ij off"},
        {"density_diffusion", "delta-SPH coefficient delta", "1", 0.0, 0.0, 1.0, 0,
         "density diffusion delta h c0 sum 2 m_j/rho_j (rho_i - rho_j) x_ij.grad W/(r^2 + 0.01h^2) (Islam eq. 6); "
         "0 off, Islam uses 0.1; set it on the fluid-fluid rule"},
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");

    // density and pressure first: other plug-ins (SPH-DEM coupling) name them so
    enum Field : int { density, pressure, wall_dvx, wall_dvy, wall_dvz };
    static constexpr plab_field_desc fields_read[] = {
        {"sph_density", "kg/m3", 1000.0}, {"sph_pressure", "Pa", 0.0},
        {"sph_wall_velocity_correction_x", "m/s", 0.0}, {"sph_wall_velocity_correction_y", "m/s", 0.0},
        {"sph_wall_velocity_correction_z", "m/s", 0.0}};
    enum Acc : int { drho_dt };
    static constexpr plab_field_desc fields_accumulated[] = {{"sph_drho_dt", "kg/(m3 s)", 0.0}};

    static double activity_range(const double* p) {
        return plab::sph::support_factor(KernelKind(int(p[kernel]))) * p[smoothing_length];
    }

    explicit Sph(const double* p)
        : kind_(KernelKind(int(p[kernel]))), h_(p[smoothing_length]), rho0_(p[rest_density]),
          c0_(p[speed_of_sound]), laminar_(int(p[viscosity]) == 0), mu_(p[mu]), alpha_(p[alpha]), beta_(p[beta]),
          anticlump_(p[anticlump]), dp_(p[anticlump_spacing] > 0 ? p[anticlump_spacing] : p[smoothing_length]),
          delta_(p[density_diffusion]) {
        // W(dp) must be positive for eq. 17: a spacing outside the support switches the term off
        if (dp_ >= plab::sph::support_factor(kind_) * h_) anticlump_ = 0;
        for (int d : {2, 3}) derivative_scale_[d == 3] = plab::sph::normalisation(kind_, d, h_) / h_;
    }

    // The host calls the law twice per cycle (rates_stage): first for the
    // continuity sum, which the passes turn into density and pressure at the
    // new positions, then for the pair force with those pressures.
    static constexpr bool rates_stage = true;

    void law(const Contact& c) const {
        const Vec3 v_rel = c.rel_velocity();
        // the force stage's outputs are the ones kept (the host clears them
        // before each stage): the step limit only there
        if (!c.rates_stage()) c.set_dt_limit(step_limit(plab::norm(v_rel)));
        if (c.with_wall()) return;  // walls carry no SPH state: use boundary balls (docs/sph.md)
        const double r = c.distance();
        if (r >= support_) return;
        const Vec3 n = c.normal();
        const double dW = derivative_scale_[c.dim() == 3] * plab::sph::detail::shape_derivative(kind_, r / h_);  // <= 0
        const double m1 = c.mass1(), m2 = c.mass2();
        const double v_n = plab::dot(v_rel, n);  // < 0 while approaching

        if (c.rates_stage()) {
            continuity(c, r, dW, v_n, m1, m2);
            return;
        }
        const double rho1 = density_or_rest(c.field1(density)), rho2 = density_or_rest(c.field2(density));

        // eqs. 15–16: m_2 dv_2/dt = -m_1 m_2 (p1/ρ1² + p2/ρ2² + Π + R) ∇_2 W_21
        const double p_term = c.field1(pressure) / (rho1 * rho1) + c.field2(pressure) / (rho2 * rho2);
        double scalar = p_term + anticlump_term(r, c.dim(), p_term);
        // the viscous terms see a no-slip wall ball at its extrapolated velocity (Adami 2012)
        const Vec3 v_visc = v_rel + wall_correction(c, 2) - wall_correction(c, 1);
        if (!laminar_) scalar += monaghan(r, plab::dot(v_visc, n), rho1, rho2);
        Vec3 f2 = (-m1 * m2 * scalar * dW) * n;
        if (laminar_ && mu_ > 0) {
            // eq. 14 (Morris): Σ m_j (μ_i+μ_j) x_ij·∇_i W_ij / (ρ_i ρ_j (r² + 0.01h²)) v_ij, x_ij·∇_i W_ij = r dW/dr
            f2 += (m1 * m2 * 2 * mu_ * r * dW / (rho1 * rho2 * (r * r + 0.01 * h_ * h_))) * v_visc;
        }
        c.set_force(f2);
        c.set_stiffness(0);
    }

private:
    // CFL on the sound speed plus the pair's relative speed; the viscous
    // diffusion limit 0.125 h²/ν for the laminar model.
    double step_limit(double speed) const {
        double dt = 0.25 * h_ / (c0_ + speed);
        if (laminar_ && mu_ > 0) dt = std::min(dt, 0.125 * h_ * h_ * rho0_ / mu_);
        return dt;
    }
    // eq. 7: dρ_i/dt = Σ m_j v_ij·∇_i W_ij; both ends get m_other dW/dr (v_rel·n).
    // Islam eq. 6 adds δ h c0 Σ 2 (m_j/ρ_j)(ρ_i - ρ_j) x_ij·∇_i W_ij/(r² + 0.01h²),
    // x_ij·∇_i W_ij = r dW/dr for both ends: it diffuses density from the denser end.
    void continuity(const Contact& c, double r, double dW, double v_n, double m1, double m2) const {
        c.accumulate1(drho_dt, m2 * dW * v_n);
        c.accumulate2(drho_dt, m1 * dW * v_n);
        if (delta_ <= 0) return;
        const double rho1 = density_or_rest(c.field1(density)), rho2 = density_or_rest(c.field2(density));
        const double d = delta_ * h_ * c0_ * 2 * (rho1 - rho2) * r * dW / (r * r + 0.01 * h_ * h_);
        c.accumulate1(drho_dt, d * m2 / rho2);
        c.accumulate2(drho_dt, -d * m1 / rho1);
    }
    Vec3 wall_correction(const Contact& c, int end) const {
        if (end == 1) return {c.field1(wall_dvx), c.field1(wall_dvy), c.field1(wall_dvz)};
        return {c.field2(wall_dvx), c.field2(wall_dvy), c.field2(wall_dvz)};
    }

    // The host's nominal-timestep probe passes zero fields: fall back to ρ0.
    double density_or_rest(double rho) const { return rho > 0 ? rho : rho0_; }

    // eq. 17: R_ij = (v_max/c0)² |p_i/ρ_i² + p_j/ρ_j²| (W_ij / W(dp))⁴
    double anticlump_term(double r, int dim, double p_term) const {
        if (anticlump_ <= 0) return 0;
        const Kernel W{kind_, dim, h_};
        const double ratio = W.value(r) / W.value(dp_);  // finite: dp_ lies inside the support (constructor)
        return anticlump_ * std::fabs(p_term) * ratio * ratio * ratio * ratio;
    }

    // Islam eqs. 8–9: Π = (-α c̄ μ_ij + β μ_ij²)/ρ̄ while approaching,
    // μ_ij = h v_ij·x_ij/(r² + 0.01h²) with v_ij·x_ij = r (v_rel·n).
    double monaghan(double r, double v_n, double rho1, double rho2) const {
        if (v_n >= 0) return 0;
        const double mu_ij = h_ * r * v_n / (r * r + 0.01 * h_ * h_);
        return (-alpha_ * c0_ * mu_ij + beta_ * mu_ij * mu_ij) / (0.5 * (rho1 + rho2));
    }

    KernelKind kind_;
    double h_, rho0_, c0_;
    bool laminar_;
    double mu_, alpha_, beta_, anticlump_, dp_, delta_;
    // kernel constants, once per instance rather than per pair: dW/dr = scale[dim 3] f'(r/h)
    double support_ = plab::sph::support_factor(kind_) * h_;
    double derivative_scale_[2] = {0, 0};
};

} // namespace

PLAB_PLUGIN(plab::add_contact_model<Sph>(r))
