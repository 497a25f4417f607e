// The `sph_solid` contact model: the pair interaction of a hypoelastic SPH
// solid (Islam 2023 §3; Gray, Monaghan & Swegle 2001), between two solid
// particles within the kernel support. Two stages a cycle (rates_stage):
//   rates  — at the new positions and half-step velocities, each pair adds
//            to both ends the continuity term (Islam eq. 14), its term of
//            the velocity-gradient sum (Islam eq. 19, raw kernel gradients)
//            and of the correction matrix A_i (Islam eq. 20). The pass
//            sph_solid_stress (RATES_DONE) turns them into ρ, B_i = A_i^-1,
//            l_i = G_i B_i, S (Jaumann rate, eq. 17) and σ = S - p I.
//   forces — the momentum equation (Islam eq. 15) in the form that conserves
//            linear momentum with corrected gradients,
//              m_i dv_i/dt = Σ_j m_i m_j (σ_i B_i/ρ_i² + σ_j B_j/ρ_j²
//                                          - Π_ij I + (R_i + R_j) f_ij^n) ∇_i W_ij,
//            Π_ij Monaghan's artificial viscosity (Islam eqs. 8–9) with the
//            solid's wave speed, R the artificial stress of the pass (Monaghan
//            2000, Islam eq. 16), f_ij = W(r)/W(dp). The force on end 2 is
//            the pair's term with ∇_2 W_21 = (dW/dr) n; the host applies its
//            opposite to end 1.
//            With `hourglass` α_HG > 0, a pair penalty on the part of the pair's
//            separation that the two particles' velocity gradients do not
//            predict (hourglass control in the form of Ganzenmüller 2015, "An
//            hourglass control algorithm for Lagrangian SPH", CMAME 286: his
//            error of the pair vector against F X, here in rate form; the
//            paper's equation numbers are not checked here), per pair:
//              dδ/dt = n·(½ (l_1 + l_2) x_21) - n·v_21 = r nᵀ ½(l_1 + l_2) n - v_rel·n,
//              δ integrated in the contact's history from 0 when the pair meets,
//              F_2 = -F_1 = α_HG E V_1 V_2 W(r)/r² δ n       (restoring; antisymmetric)
//            δ stays zero in any linear velocity field (uniform strain, rigid
//            motion), where the corrected l is exact; it grows for the
//            column-to-column zig-zag of nodal integration and for the part of
//            a bending field the first-order corrected l misses at a free
//            surface (physics/sph_solid/README.md, "too soft in bending").
// With `interactions` `pseudo_springs` (Islam §3.2–3.3, Chakraborty & Shaw
// 2013) only the pairs a scene's `bond` command joined interact: the
// immediate neighbours, a pseudo-spring each, with interaction factor
// f_ij = 1 while the spring holds and 0, for good, once its strain
// (r - r0)/r0 exceeds `failure_strain` (a spring fails in tension only).
// The spring is the host's bond (persist slot), so a failure is recorded
// as a bond break with its time and place; the rates stage counts each
// particle's intact springs for the pass's damage D_i.
// Conventions as the `sph` model: n from end 1 to end 2, x_2 - x_1 = r n,
// v_rel = v_2 - v_1, dW/dr <= 0.
#include <plab/sph/law.hpp>
#include <plab/sph_solid/elasticity.hpp>
#include <plab/sph_solid/material.hpp>

#include <plab/contact_model.hpp>

#include <cmath>
#include <limits>

namespace {

using plab::Contact;
using plab::Vec3;
using plab::sph::KernelKind;
using plab::sph::SymTensor;
namespace solid = plab::sph_solid::solid;
namespace field = plab::sph_solid::field;

constexpr double inf = std::numeric_limits<double>::infinity();
// the `interactions` property's values, by index
constexpr const char* interaction_names[] = {"kernel_support", "pseudo_springs"};

// SymTensor from six consecutive fields starting at `first`, of end 1 or 2
SymTensor sym_field(const Contact& c, int first, bool end2) {
    double v[6];
    for (int k = 0; k < 6; ++k) v[k] = end2 ? c.field2(first + k) : c.field1(first + k);
    return {v[0], v[1], v[2], v[3], v[4], v[5]};
}

// T g for the particle's σ B/ρ² (nine fields from `first`) of end 1 or 2
Vec3 stress_term_times(const Contact& c, int first, bool end2, const Vec3& g) {
    double t[9];
    for (int k = 0; k < 9; ++k) t[k] = end2 ? c.field2(first + k) : c.field1(first + k);
    return {t[0] * g.x + t[1] * g.y + t[2] * g.z, t[3] * g.x + t[4] * g.y + t[5] * g.z, t[6] * g.x + t[7] * g.y + t[8] * g.z};
}

// R g for a symmetric R
Vec3 times(const SymTensor& r, const Vec3& g) {
    return {r.xx * g.x + r.xy * g.y + r.zx * g.z, r.xy * g.x + r.yy * g.y + r.yz * g.z, r.zx * g.x + r.yz * g.y + r.zz * g.z};
}

struct SphSolid {
    static constexpr const char* name = "sph_solid";
    static constexpr const char* doc =
        "Hypoelastic SPH solid pair interaction (Islam 2023 eqs. 8-9, 12-20; Gray, Monaghan & Swegle 2001): "
        "continuity, velocity-gradient and correction-matrix sums in the rates stage, then the momentum equation "
        "with corrected gradients, Monaghan artificial viscosity and artificial stress. Use with the "
        "sph_solid_stress pass; solid particles must have their rotation fixed.";
    static constexpr const char* timestep_rule = "per pair: CFL 0.25 h/(c + |v_rel|), c = sqrt((K + 4G/3)/rho0)";
    static constexpr uint32_t range_kind = PLAB_RANGE_DISTANCE;
    static constexpr uint32_t flags = PLAB_MODEL_FORCE_AT_CENTRES;
    static constexpr uint32_t io = PLAB_IO_MASSES | PLAB_IO_DT_LIMIT;
    using material = plab::sph_solid::SolidMaterial;

    enum Prop : int {
        smoothing_length, kernel, rest_density, youngs_modulus, poissons_ratio, particle_spacing, alpha, beta,
        exponent, hourglass, interactions, failure_strain, prop_count
    };
    static constexpr plab_property_desc properties[] = {
        solid::smoothing_length, solid::kernel, solid::rest_density, solid::youngs_modulus, solid::poissons_ratio,
        solid::particle_spacing,
        plab::prop::number("alpha", "artificial viscosity alpha", "1", 1.0, 0.0, inf, PLAB_MAX_EXCLUSIVE,
         "linear term of Monaghan's viscosity (Islam eq. 8, beta_1), with the solid's wave speed"),
        plab::prop::number("beta", "artificial viscosity beta", "1", 0.0, 0.0, inf, PLAB_MAX_EXCLUSIVE,
         "quadratic term of Monaghan's viscosity (Islam eq. 8, beta_2)"),
        plab::prop::number("artificial_stress_exponent", "artificial stress exponent n", "1", 4.0, 0.0, 64.0, 0,
         "n of (W(r)/W(dp))^n (Monaghan 2000: 4; see physics/sph_solid/README.md on Islam eq. 16); the "
         "coefficient epsilon is the sph_solid_stress pass's"),
        plab::prop::number("hourglass", "hourglass control coefficient alpha_HG", "1", 0.0, 0.0, 1000.0, 0,
         "pair penalty alpha_HG E V_i V_j W/r^2 delta on the pair separation delta that the mean velocity gradient "
         "does not predict (Ganzenmueller 2015, rate form; physics/sph_solid/README.md); 0 off"),
        plab::prop::choice("interactions", "interacting pairs", interaction_names, 0,
         "kernel_support: every pair within the kernel support; pseudo_springs: only the pairs a bond command "
         "joined (the immediate neighbours: gap <= about 0.5 dp on a square or hexagonal lattice), each until its "
         "spring fails (Islam sec. 3.2-3.3)"),
        plab::prop::number("failure_strain", "pseudo-spring failure strain eps_f", "1", inf, 0.0, inf, PLAB_MIN_EXCLUSIVE,
         "a spring fails for good when (r - r0)/r0 > eps_f, r0 its length when bonded (Islam sec. 3.3, sec. 5.5: "
         "0.05); with pseudo_springs only"),
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");

    // Read: the density, σ B/ρ² (nine components, the pass's), R (six) and
    // the corrected velocity gradient l (nine, the pass's; hourglass control
    // only); the host passes at most 32.
    enum Field : int { density, stress_term = 1, artificial = 10, velocity_gradient = 16 };
    static constexpr plab_field_desc fields_read[] = {
        field::density,
        field::stress_term[0], field::stress_term[1], field::stress_term[2], field::stress_term[3], field::stress_term[4],
        field::stress_term[5], field::stress_term[6], field::stress_term[7], field::stress_term[8],
        field::artificial_stress[0], field::artificial_stress[1], field::artificial_stress[2],
        field::artificial_stress[3], field::artificial_stress[4], field::artificial_stress[5],
        field::velocity_gradient[0], field::velocity_gradient[1], field::velocity_gradient[2],
        field::velocity_gradient[3], field::velocity_gradient[4], field::velocity_gradient[5],
        field::velocity_gradient[6], field::velocity_gradient[7], field::velocity_gradient[8]};
    // Accumulated in the rates stage: dρ/dt, A (six), the raw velocity-gradient
    // sum (nine), the intact springs.
    enum Acc : int { drho_dt, moment = 1, gradient = 7, springs = 16 };
    static constexpr plab_field_desc fields_accumulated[] = {
        field::drho_dt,
        field::moment_matrix[0], field::moment_matrix[1], field::moment_matrix[2], field::moment_matrix[3],
        field::moment_matrix[4], field::moment_matrix[5],
        field::velocity_gradient[0], field::velocity_gradient[1], field::velocity_gradient[2],
        field::velocity_gradient[3], field::velocity_gradient[4], field::velocity_gradient[5],
        field::velocity_gradient[6], field::velocity_gradient[7], field::velocity_gradient[8],
        field::intact_springs};

    static constexpr bool rates_stage = true;

    // The pseudo-spring of a bonded pair (interactions pseudo_springs), and
    // the hourglass control's δ of the pair (m), zero when the pair meets,
    // symmetric in the ends (n and v_rel both turn).
    enum Slot : int { spring_state, rest_length, hourglass_error, slot_count };
    static constexpr plab_history_desc history[] = {
        plab::history_desc("spring_state", 0.0, PLAB_SWAP_KEEP, "1 an intact pseudo-spring, 0 none or failed"),
        plab::history_desc("rest_length", 0.0, PLAB_SWAP_KEEP, "the spring's length r0 when bonded, m (0: not yet)"),
        plab::history_desc("hourglass_error", 0.0, PLAB_SWAP_KEEP,
                           "delta of the hourglass control: the pair's separation predicted by the mean velocity "
                           "gradient less the actual one, integrated (m)"),
    };
    static constexpr int persist_slot = spring_state;

    static double activity_range(const double* p) {
        return plab::sph::support_factor(KernelKind(int(p[kernel]))) * p[smoothing_length];
    }

    explicit SphSolid(const double* p)
        : kind_(KernelKind(int(p[kernel]))), h_(p[smoothing_length]), rho0_(p[rest_density]),
          support_(activity_range(p)), exponent_(p[exponent]), dp_(p[particle_spacing]),
          hourglass_(p[hourglass] * p[youngs_modulus]), failure_strain_(p[failure_strain]),
          springs_only_(int(p[interactions]) == 1) {
        if (exponent_ == std::floor(exponent_)) whole_exponent_ = int(exponent_);
        const auto m = plab::sph_solid::moduli(p[youngs_modulus], p[poissons_ratio], rho0_);
        wave_speed_ = m.wave_speed;
        viscosity_ = plab::sph::LawParams{};
        viscosity_.h = h_;
        viscosity_.c0 = wave_speed_;
        viscosity_.alpha = p[alpha];
        viscosity_.beta = p[beta];
        viscosity_.eta2 = 0.01 * h_ * h_;
    }

    void law(const Contact& c) const {
        if (c.with_wall()) {  // walls carry no solid state: a step limit only
            if (!c.rates_stage()) c.set_dt_limit(step_limit(plab::norm(c.rel_velocity())));
            return;
        }
        if (c.rates_stage()) rates(c);
        else forces(c);
    }

private:
    double rho(double field_value) const { return plab::sph::rho_or_rest(field_value, rho0_); }
    double step_limit(double speed) const { return 0.25 * h_ / (wave_speed_ + speed); }
    double dw_dr(int dim, double r) const { return plab::sph::Kernel{kind_, dim, h_}.derivative(r); }

    // Islam eqs. 14, 19, 20: both ends' terms of dρ/dt, Σ V_j (v_j - v_i) ⊗ ∇_i W_ij
    // (= -V_other (dW/dr) v_rel ⊗ n for either end) and A_i.
    void rates(const Contact& c) const {
        const double r = c.distance();
        if (springs_only_ && !spring_holds(c, r)) return;
        if (r >= support_) return;
        const double dW = dw_dr(c.dim(), r);
        const Vec3 n = c.normal(), v = c.rel_velocity();
        const double m1 = c.mass1(), m2 = c.mass2();
        const double vol1 = m1 / rho(c.field1(density)), vol2 = m2 / rho(c.field2(density));
        const double v_n = plab::dot(v, n);
        c.accumulate1(drho_dt, m2 * dW * v_n);
        c.accumulate2(drho_dt, m1 * dW * v_n);
        const double va[3] = {v.x, v.y, v.z}, na[3] = {n.x, n.y, n.z};
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) {
                c.accumulate1(gradient + 3 * a + b, -vol2 * dW * va[a] * na[b]);
                c.accumulate2(gradient + 3 * a + b, -vol1 * dW * va[a] * na[b]);
            }
        const SymTensor a1 = plab::sph::moment_term(vol2, r, dW, n), a2 = plab::sph::moment_term(vol1, r, dW, n);
        const double t1[6] = {a1.xx, a1.yy, a1.zz, a1.xy, a1.yz, a1.zx}, t2[6] = {a2.xx, a2.yy, a2.zz, a2.xy, a2.yz, a2.zx};
        for (int k = 0; k < 6; ++k) {
            c.accumulate1(moment + k, t1[k]);
            c.accumulate2(moment + k, t2[k]);
        }
    }

    // Islam eq. 15 with corrected gradients and Monaghan's artificial stress;
    // the force on end 2.
    void forces(const Contact& c) const {
        const double r = c.distance();
        c.set_dt_limit(step_limit(plab::norm(c.rel_velocity())));
        if (springs_only_ && !(c.history(spring_state) > 0)) return;  // f_ij = 0
        if (r >= support_) return;
        const int dim = c.dim();
        const Vec3 n = c.normal();
        const Vec3 g = dw_dr(dim, r) * n;  // ∇_2 W_21
        const double rho1 = rho(c.field1(density)), rho2 = rho(c.field2(density));
        Vec3 f = stress_term_times(c, stress_term, false, g) + stress_term_times(c, stress_term, true, g);
        const double pi = plab::sph::monaghan(viscosity_, r, plab::dot(c.rel_velocity(), n), rho1, rho2);
        f -= pi * g;
        const SymTensor rsum = sym_field(c, artificial, false) + sym_field(c, artificial, true);
        if (rsum.xx != 0 || rsum.yy != 0 || rsum.zz != 0 || rsum.xy != 0 || rsum.yz != 0 || rsum.zx != 0) {
            // (a spacing outside the support, W(dp) = 0, switches the term off)
            const plab::sph::Kernel w{kind_, dim, h_};
            const double w_dp = w.value(dp_);
            const double fn = w_dp > 0 ? power(w.value(r) / w_dp) : 0.0;
            f += fn * times(rsum, g);
        }
        if (dim == 2) f.z = 0;  // (a 2D world's tensors have no xz, yz parts; a harness's may)
        Vec3 force = c.mass1() * c.mass2() * f;
        if (hourglass_ > 0) force += hourglass_force(c, r, n, rho1, rho2);
        c.set_force(force);
    }

    // The hourglass control's pair force on end 2 (the file header): δ
    // advanced by dt dδ/dt at this step's positions and half-step velocities,
    // as the pass advances the stress, then α_HG E V_1 V_2 W(r)/r² δ n.
    Vec3 hourglass_force(const Contact& c, double r, const Vec3& n, double rho1, double rho2) const {
        const double na[3] = {n.x, n.y, n.z};
        double nln = 0;  // nᵀ ½(l_1 + l_2) n
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b)
                nln += na[a] * 0.5 * (c.field1(velocity_gradient + 3 * a + b) + c.field2(velocity_gradient + 3 * a + b)) * na[b];
        double& delta = c.history(hourglass_error);
        delta += c.dt() * (r * nln - plab::dot(c.rel_velocity(), n));
        const double w = plab::sph::Kernel{kind_, c.dim(), h_}.value(r);
        const double v1 = c.mass1() / rho1, v2 = c.mass2() / rho2;
        return hourglass_ * v1 * v2 * w / (r * r) * delta * n;
    }

    // Islam §3.3: f_ij = 1 while the pair's spring holds. Called once a step
    // (the rates stage, where the host keeps history): sets r0 at the
    // first call after bonding, counts the intact spring at both ends, and
    // marks a spring strained past eps_f broken (-1: the host records the
    // break and clears the state).
    bool spring_holds(const Contact& c, double r) const {
        double& state = c.history(spring_state);
        if (!(state > 0)) return false;
        double& r0 = c.history(rest_length);
        if (r0 == 0) r0 = r;
        if ((r - r0) > failure_strain_ * r0) {
            state = -1;
            return false;
        }
        c.accumulate1(springs, 1.0);
        c.accumulate2(springs, 1.0);
        return true;
    }

    // f^n: a whole n (Monaghan's 4) by multiplication, a tenth of std::pow's cost
    double power(double f) const {
        if (whole_exponent_ < 0) return std::pow(f, exponent_);
        double result = 1;
        for (int k = 0; k < whole_exponent_; ++k) result *= f;
        return result;
    }

    KernelKind kind_;
    double h_, rho0_, support_, exponent_, dp_, hourglass_;  // hourglass_: α_HG E
    double failure_strain_, wave_speed_ = 0;
    bool springs_only_;
    int whole_exponent_ = -1;  // n when it is a whole number, else -1
    plab::sph::LawParams viscosity_;  // the fields monaghan() reads: h, c0 (the wave speed), alpha, beta, eta2
};

} // namespace

// plab_sph_solid, the SPH solid package's library: the model and its pass
// (sph_solid_passes.cpp) in one plab_plugin_init.
namespace plab::sph_solid {
int register_passes(const plab_registrar* r);
}

PLAB_PLUGIN(plab::add_contact_model<SphSolid>(r) != 0 ? 1 : plab::sph_solid::register_passes(r))
