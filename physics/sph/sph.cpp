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
// The force stage is pair_force() of <plab/sph/law.hpp>, a function of
// values that law() calls for one contact and law_rows() in a vectorised
// loop over a batch (the host's packed batches).
//
// Conventions: n is the unit normal from end 1 to end 2, x_2 - x_1 = r n,
// v_rel = v_2 - v_1; dW/dr <= 0 and ∇_2 W_21 = dW/dr n = -∇_1 W_12.
#include <plab/sph/law.hpp>
#include <plab/sph/material.hpp>

#include <plab/contact_model.hpp>

#include <algorithm>
#include <cmath>

namespace {

using plab::Contact;
using plab::Vec3;
using plab::sph::KernelKind;
using plab::sph::PairForce;
using plab::sph::Viscosity;

constexpr double inf = std::numeric_limits<double>::infinity();
// the `viscosity` property's values, by index (0 laminar, 1 artificial)
constexpr const char* viscosity_names[] = {"laminar", "artificial"};

// The body fields the model reads (Sph::fields_read, in this order).
enum Field : int { density, pressure, wall_dvx, wall_dvy, wall_dvz };

// pair_force() on rows [k0, k1) of a batch of ball–ball pairs in the force
// stage: one loop over the rows' columns, the fields of both ends gathered by
// body index. Without NoSlip the wall velocity corrections are at their
// default, zero, at every body (no sph_wall_pressure pass: the host says so,
// body_fields_at_default), and the loop takes zero instead of gathering six
// values per pair (-10 % time on the dam break); the bits are the same.
// (restrict parameters, not locals: GCC proves the columns apart only so;
// the fields are only read, so they may share storage.)
template <KernelKind K, Viscosity V, bool Anticlump, bool NoSlip>
[[gnu::always_inline]] inline void pair_forces(const plab::sph::LawParams& p, int dim3, std::size_t k0, std::size_t k1,
                                               const int32_t* __restrict end1, const int32_t* __restrict end2,
                                               const double* __restrict normal, const double* __restrict rel_velocity,
                                               const double* __restrict distance, const double* __restrict mass1,
                                               const double* __restrict mass2, const double* __restrict rho,
                                               const double* __restrict pressure, const double* __restrict dvx,
                                               const double* __restrict dvy, const double* __restrict dvz,
                                               double* __restrict force, double* __restrict dt_limit) {
    for (std::size_t k = k0; k < k1; ++k) {
        const int32_t i = end1[k], j = end2[k];
        const Vec3 dv1 = NoSlip ? Vec3{dvx[i], dvy[i], dvz[i]} : Vec3{};
        const Vec3 dv2 = NoSlip ? Vec3{dvx[j], dvy[j], dvz[j]} : Vec3{};
        const plab::sph::Pair s{{normal[3 * k], normal[3 * k + 1], normal[3 * k + 2]},
                                {rel_velocity[3 * k], rel_velocity[3 * k + 1], rel_velocity[3 * k + 2]},
                                dv1, dv2,
                                distance[k], mass1[k], mass2[k], rho[i], rho[j], pressure[i], pressure[j]};
        const PairForce f = plab::sph::pair_force<K, V, Anticlump>(p, dim3, s);
        force[3 * k] = f.force.x; force[3 * k + 1] = f.force.y; force[3 * k + 2] = f.force.z;
        dt_limit[k] = f.dt_limit;
    }
}

// The batch loop built three times, for SSE2, AVX2 and AVX-512 (picked once
// at load time): four or eight pairs per instruction where the CPU has
// them (AVX-512: -4 % time on the dam break). No FMA in any, so all give
// the bits of law().
// (flattened: the choices of with_choices() and the law inlined into each
// clone, else the loops are built for SSE2 only; clang builds one, see
// PLAB_TARGET_CLONES_FLAT)
PLAB_TARGET_CLONES_FLAT("avx512f", "avx2", "default") void sph_rows(const plab::sph::LawParams& p,
                                                                    const plab_contact_batch& b, std::size_t k0,
                                                                    std::size_t k1) {
    const int dim3 = b.dim == 3;
    const double* const* f = b.body_fields;
    constexpr uint64_t no_wall_dv = (1u << wall_dvx) | (1u << wall_dvy) | (1u << wall_dvz);
    const bool no_slip = (b.body_fields_at_default & no_wall_dv) != no_wall_dv;
    plab::sph::with_choices(p, [&](auto k, auto v, auto a) {
        const auto rows = [&](auto slip) {
            pair_forces<decltype(k)::value, decltype(v)::value, decltype(a)::value, decltype(slip)::value>(
                p, dim3, k0, k1, b.end1, b.end2, b.normal, b.rel_velocity, b.distance, b.mass1, b.mass2, f[density],
                f[pressure], f[wall_dvx], f[wall_dvy], f[wall_dvz], b.force, b.dt_limit);
        };
        no_slip ? rows(std::true_type{}) : rows(std::false_type{});
    });
}

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
    // stiffness and energies for the ball–ball rows (abi.h, PLAB_MODEL_FORCE_AT_CENTRES)
    static constexpr uint32_t flags = PLAB_MODEL_FORCE_AT_CENTRES;
    // reads the two masses (not the effective mass or radius, the radii or
    // the spin) and writes a step limit (abi.h, io)
    static constexpr uint32_t io = PLAB_IO_MASSES | PLAB_IO_DT_LIMIT;
    // h, the kernel, rho0 and c0 are the fluid's: a scene material of its groups gives them
    using material = plab::sph::FluidMaterial;

    enum Prop : int {
        smoothing_length, kernel, rest_density, speed_of_sound, viscosity, mu, alpha, beta,
        anticlump, anticlump_spacing, density_diffusion, prop_count
    };
    static constexpr plab_property_desc properties[] = {
        plab::sph::fluid::smoothing_length, plab::sph::fluid::kernel, plab::sph::fluid::rest_density,
        plab::sph::fluid::speed_of_sound,
        plab::prop::choice("viscosity", "viscosity model", viscosity_names, 1,
         "laminar: Morris, with dynamic viscosity mu (eq. 14); artificial: Monaghan, with alpha, beta (Islam eq. 8)"),
        plab::prop::number("mu", "dynamic viscosity", "Pa s", 8.9e-4, 0.0, inf, PLAB_MAX_EXCLUSIVE, "laminar model (viscosity laminar)"),
        plab::prop::number("alpha", "artificial viscosity alpha", "1", 0.02, 0.0, inf, PLAB_MAX_EXCLUSIVE,
         "linear term of the Monaghan viscosity (viscosity artificial)"),
        plab::prop::number("beta", "artificial viscosity beta", "1", 0.0, 0.0, inf, PLAB_MAX_EXCLUSIVE,
         "quadratic term of the Monaghan viscosity (viscosity artificial)"),
        plab::prop::number("anticlump", "anti-clump coefficient (v_max/c0)^2", "1", 0.0, 0.0, inf, PLAB_MAX_EXCLUSIVE,
         "R_ij of eq. 17; 0 switches it off, the thesis uses 0.01"),
        plab::prop::number("anticlump_spacing", "initial particle spacing for W(dp)", "m", 0.0, 0.0, inf, PLAB_MAX_EXCLUSIVE,
         "dp in (W_ij / W(dp))^4 of eq. 17; 0: dp = h; a dp outside the kernel support switches R_ij off"),
        plab::prop::number("density_diffusion", "delta-SPH coefficient delta", "1", 0.0, 0.0, 1.0, 0,
         "density diffusion delta h c0 sum 2 m_j/rho_j (rho_i - rho_j) x_ij.grad W/(r^2 + 0.01h^2) (Islam eq. 6); "
         "0 off, Islam uses 0.1; set it on the fluid-fluid rule"),
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");

    // density and pressure first: other plug-ins (SPH-DEM coupling) name them so
    static constexpr plab_field_desc fields_read[] = {
        plab::field_desc("sph_density", "kg/m3", 1000.0), plab::field_desc("sph_pressure", "Pa", 0.0),
        plab::field_desc("sph_wall_velocity_correction_x", "m/s", 0.0), plab::field_desc("sph_wall_velocity_correction_y", "m/s", 0.0),
        plab::field_desc("sph_wall_velocity_correction_z", "m/s", 0.0)};
    enum Acc : int { drho_dt };
    static constexpr plab_field_desc fields_accumulated[] = {plab::field_desc("sph_drho_dt", "kg/(m3 s)", 0.0)};

    static double activity_range(const double* p) {
        return plab::sph::support_factor(KernelKind(int(p[kernel]))) * p[smoothing_length];
    }

    explicit Sph(const double* p) : law_(law_params(p)), delta_(p[density_diffusion]) {}

    // The host calls the law twice per cycle (rates_stage): first for the
    // continuity sum, which the passes turn into density and pressure at the
    // new positions, then for the pair force with those pressures.
    static constexpr bool rates_stage = true;

    void law(const Contact& c) const {
        if (c.rates_stage()) {
            continuity(c);
            return;
        }
        if (c.with_wall()) {  // walls carry no SPH state: use boundary balls (docs/sph.md); a step limit only
            c.set_dt_limit(wall_step_limit(plab::norm(c.rel_velocity())));
            return;
        }
        const plab::sph::Pair s = pair(c);
        const int dim3 = c.dim() == 3;
        const PairForce f = plab::sph::with_choices(law_, [&](auto k, auto v, auto a) {
            return plab::sph::pair_force<decltype(k)::value, decltype(v)::value, decltype(a)::value>(law_, dim3, s);
        });
        c.set_force(f.force);
        c.set_dt_limit(f.dt_limit);
    }
    // law() on every row of a batch of active rows: the force stage of
    // ball–ball pairs as one loop GCC vectorises (sph_rows); other batches
    // row by row. A loop of its own rather than the adapter's over law():
    // the kernel, the viscosity form, the anti-clump term and whether to
    // gather the wall corrections are chosen once per batch, as template
    // arguments of the loop, where law() chooses them per contact.
    void law_rows(const plab_contact_batch& b, std::size_t k0, std::size_t k1) const {
        if (b.stage == PLAB_STAGE_RATES || b.end2_is_wall) {
            for (std::size_t k = k0; k < k1; ++k) law(Contact(b, uint32_t(k)));
            return;
        }
        sph_rows(law_, b, k0, k1);
    }

private:
    // The pair's inputs as pair_force() takes them.
    static plab::sph::Pair pair(const Contact& c) {
        return {c.normal(), c.rel_velocity(),
                {c.field1(wall_dvx), c.field1(wall_dvy), c.field1(wall_dvz)},
                {c.field2(wall_dvx), c.field2(wall_dvy), c.field2(wall_dvz)},
                c.distance(), c.mass1(), c.mass2(), c.field1(density), c.field2(density), c.field1(pressure),
                c.field2(pressure)};
    }
    double wall_step_limit(double speed) const {
        return law_.viscosity == Viscosity::morris ? plab::sph::step_limit<Viscosity::morris>(law_, speed)
                                                   : plab::sph::step_limit<Viscosity::none>(law_, speed);
    }
    // eq. 7: dρ_i/dt = Σ m_j v_ij·∇_i W_ij; both ends get m_other dW/dr (v_rel·n).
    // Islam eq. 6 adds δ h c0 Σ 2 (m_j/ρ_j)(ρ_i - ρ_j) x_ij·∇_i W_ij/(r² + 0.01h²),
    // x_ij·∇_i W_ij = r dW/dr for both ends: it diffuses density from the denser end.
    void continuity(const Contact& c) const {
        if (c.with_wall()) return;
        const double r = c.distance();
        if (r >= law_.support) return;
        const double h = law_.h;
        const double dW = law_.derivative_scale[c.dim() == 3] * plab::sph::detail::shape_derivative(law_.kind, r / h);
        const double m1 = c.mass1(), m2 = c.mass2();
        const double v_n = plab::dot(c.rel_velocity(), c.normal());  // < 0 while approaching
        c.accumulate1(drho_dt, m2 * dW * v_n);
        c.accumulate2(drho_dt, m1 * dW * v_n);
        if (delta_ <= 0) return;
        const double rho1 = plab::sph::rho_or_rest(c.field1(density), law_.rho0);
        const double rho2 = plab::sph::rho_or_rest(c.field2(density), law_.rho0);
        const double d = delta_ * h * law_.c0 * 2 * (rho1 - rho2) * r * dW / (r * r + law_.eta2);
        c.accumulate1(drho_dt, d * m2 / rho2);
        c.accumulate2(drho_dt, -d * m1 / rho1);
    }

    static plab::sph::LawParams law_params(const double* p) {
        plab::sph::LawParams l{};
        l.kind = KernelKind(int(p[kernel]));
        const bool laminar = int(p[viscosity]) == 0;
        l.viscosity = !laminar ? Viscosity::monaghan : p[mu] > 0 ? Viscosity::morris : Viscosity::none;
        l.h = p[smoothing_length];
        l.inv_h = 1.0 / l.h;
        l.rho0 = p[rest_density];
        l.c0 = p[speed_of_sound];
        l.mu = p[mu];
        l.alpha = p[alpha];
        l.beta = p[beta];
        l.support = plab::sph::support_factor(l.kind) * l.h;
        l.eta2 = 0.01 * l.h * l.h;
        l.cfl_length = 0.25 * l.h;
        l.viscous_dt = 0.125 * l.h * l.h * l.rho0 / l.mu;  // (used with mu > 0 only)
        // W(dp) must be positive for eq. 17: a spacing outside the support switches the term off
        const double dp = p[anticlump_spacing] > 0 ? p[anticlump_spacing] : l.h;
        l.anticlump = dp < l.support ? p[anticlump] : 0.0;
        for (int d : {2, 3}) {
            l.value_scale[d == 3] = plab::sph::normalisation(l.kind, d, l.h);
            l.derivative_scale[d == 3] = l.value_scale[d == 3] / l.h;
            l.w_dp[d == 3] = plab::sph::Kernel{l.kind, d, l.h}.value(dp);
        }
        return l;
    }

    plab::sph::LawParams law_;
    double delta_;
};

} // namespace

// plab_sph, the SPH package's library: the model and the passes
// (sph_passes.cpp) in one plab_plugin_init.
namespace plab::sph {
int register_passes(const plab_registrar* r);
}

PLAB_PLUGIN(plab::add_contact_model<Sph>(r) != 0 ? 1 : plab::sph::register_passes(r))
