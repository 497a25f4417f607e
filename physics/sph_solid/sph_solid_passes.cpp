// The pass of the SPH solid, `sph_solid_stress` (phase RATES_DONE): after
// the host's rates stage, where the `sph_solid` model summed dρ/dt, the
// raw velocity-gradient sum G_i and the correction matrix A_i at the new
// positions and half-step velocities, and before the force stage, each
// solid particle takes
//   B    = A^-1 (or I without kernel_correction)  (Islam eq. 20, Chen 1999)
//   l    = G B                                     (Islam eq. 19, corrected)
//   ρ   += dt dρ/dt, dρ/dt = -ρ tr(l)              (Islam eq. 12; density_rate
//          velocity_gradient), or the pair sum Σ m_j v_ij·∇W (eq. 14; pair_sum)
//   S   += dt Ṡ(S, l)                              (Islam eqs. 17–18, Jaumann)
//   σ    = S - p I,  p = K (ρ/ρ0 - 1)             (Islam §3.1)
//   R    = Monaghan's artificial stress of σ       (Islam eq. 16; Gray et al. 2001)
//   σ B/ρ², the particle's factor in the momentum equation (eq. 15), for the law
//   D    = 1 - intact/initial springs          (Islam §3.3; with pseudo-springs)
// the leapfrog's order for a state integrated beside it, as the SPH
// fluid's density: the rates at x(t+dt) and v(t+dt/2) give the state at
// t + dt, which the forces of the same step then use.
// Why -ρ tr(l) by default: the pair sum of eq. 14 uses raw kernel
// gradients, which see about half a support at a free surface, so the
// surface rows of a bent plate, where the bending strain is largest, would
// take about half the volumetric stress they should; with the corrected
// gradient the volumetric and deviatoric parts see the same, exact for a
// linear velocity field at every particle.
#include <plab/sph_solid/elasticity.hpp>
#include <plab/sph_solid/material.hpp>

#include <plab/pass.hpp>

#include <cstdint>

namespace {

using plab::sph::SymTensor;
using plab::sph::Tensor;
namespace solid = plab::sph_solid::solid;
namespace field = plab::sph_solid::field;

// six consecutive fields as a symmetric tensor, and back
SymTensor load_sym(double* const* f, int first, std::size_t i) {
    return {f[first][i], f[first + 1][i], f[first + 2][i], f[first + 3][i], f[first + 4][i], f[first + 5][i]};
}
void store_sym(double* const* f, int first, std::size_t i, const SymTensor& s) {
    const double v[6] = {s.xx, s.yy, s.zz, s.xy, s.yz, s.zx};
    for (int k = 0; k < 6; ++k) f[first + k][i] = v[k];
}

// the `density_rate` property's values, by index
constexpr const char* density_rate_names[] = {"velocity_gradient", "pair_sum"};
// the `kernel_correction` property's values, by index
constexpr const char* kernel_correction_names[] = {"none", "velocity_gradient", "all"};

struct SphSolidStress {
    static constexpr const char* name = "sph_solid_stress";
    static constexpr const char* doc =
        "SPH solid state update after the rates stage (Islam eqs. 14, 16-20): density, correction matrix B = A^-1, "
        "corrected velocity gradient, deviatoric stress by the Jaumann rate, p = K(rho/rho0 - 1), sigma = S - p I, "
        "Monaghan's artificial stress. Use with the sph_solid model.";
    static constexpr uint32_t phase = PLAB_PHASE_RATES_DONE;
    static constexpr uint32_t stage = 0;
    using material = plab::sph_solid::SolidMaterial;
    enum Prop : int {
        rest_density, youngs_modulus, poissons_ratio, epsilon, kernel_correction, density_rate, group, prop_count
    };
    static constexpr plab_property_desc properties[] = {
        solid::rest_density, solid::youngs_modulus, solid::poissons_ratio,
        plab::prop::number("artificial_stress", "artificial stress coefficient epsilon", "1", 0.3, 0.0, 1.0, 0,
         "epsilon of R = -epsilon sigma/rho^2 on tensile principal stresses (Monaghan 2000: 0.2-0.3); 0 off"),
        plab::prop::choice("kernel_correction", "kernel gradient correction", kernel_correction_names, 2,
         "where gradients are corrected by B = A^-1 (Chen 1999, Islam eq. 20), exact for linear fields also at free "
         "surfaces: none; velocity_gradient (l and the density rate); all (also the momentum equation, as "
         "sigma_i B_i/rho_i^2 + sigma_j B_j/rho_j^2)"),
        plab::prop::choice("density_rate", "density rate", density_rate_names, 0,
         "velocity_gradient: -rho tr(l), l the (corrected) velocity gradient (Islam eq. 12); pair_sum: "
         "sum_j m_j v_ij . grad W_ij with raw kernel gradients (Islam eq. 14)"),
        plab::prop::optional_group("group", "group of the solid's particles",
         "only these particles are updated; none: every particle"),
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");

    enum Field : int {
        density, drho_dt, pressure, deviatoric = 3, stress = 9, artificial = 15, moment = 21, correction = 27,
        gradient = 33, stress_term = 42, intact_springs = 51, initial_springs, damage, field_count
    };
#define PLAB_SIX(a) a[0], a[1], a[2], a[3], a[4], a[5]
    static constexpr plab_field_desc fields[] = {
        field::density, field::drho_dt, field::pressure,
        PLAB_SIX(field::deviatoric_stress), PLAB_SIX(field::stress), PLAB_SIX(field::artificial_stress),
        PLAB_SIX(field::moment_matrix), PLAB_SIX(field::correction),
        field::velocity_gradient[0], field::velocity_gradient[1], field::velocity_gradient[2],
        field::velocity_gradient[3], field::velocity_gradient[4], field::velocity_gradient[5],
        field::velocity_gradient[6], field::velocity_gradient[7], field::velocity_gradient[8],
        field::stress_term[0], field::stress_term[1], field::stress_term[2], field::stress_term[3], field::stress_term[4],
        field::stress_term[5], field::stress_term[6], field::stress_term[7], field::stress_term[8],
        field::intact_springs, field::initial_springs, field::damage};
#undef PLAB_SIX
    static_assert(sizeof(fields) / sizeof(fields[0]) == field_count, "one description per field");

    explicit SphSolidStress(const double* p)
        : rho0_(p[rest_density]), moduli_(plab::sph_solid::moduli(p[youngs_modulus], p[poissons_ratio], p[rest_density])),
          epsilon_(p[epsilon]), correct_(int(p[kernel_correction]) >= 1), correct_momentum_(int(p[kernel_correction]) == 2), pair_sum_(int(p[density_rate]) == 1),
          group_(int(p[group])) {}

    void run(const plab_pass_view& v) const {
        const int dim = int(v.dim);
#pragma omp parallel for schedule(static) if (v.body_count >= 4096)
        for (std::int64_t i = 0; i < std::int64_t(v.body_count); ++i)
            if (group_ < 0 || v.group[i] == group_) update(v.fields, std::size_t(i), dim, v.dt);
    }

private:
    // One particle's state from its sums (the file header's list).
    void update(double* const* f, std::size_t i, int dim, double dt) const {
        const SymTensor b = correct_ ? plab::sph::correction(load_sym(f, moment, i), dim) : SymTensor{1, 1, 1, 0, 0, 0};
        store_sym(f, correction, i, b);
        Tensor g;
        for (int a = 0; a < 3; ++a)
            for (int c = 0; c < 3; ++c) g.m[a][c] = f[gradient + 3 * a + c][i];
        const Tensor l = plab::sph::corrected(g, b);
        for (int a = 0; a < 3; ++a)
            for (int c = 0; c < 3; ++c) f[gradient + 3 * a + c][i] = l.m[a][c];  // the field now holds l
        double& rho = f[density][i];
        if (!(rho > 0)) rho = rho0_;  // before the first step: the field's default, 0
        const double rate = pair_sum_ ? f[drho_dt][i] : -rho * (l.m[0][0] + l.m[1][1] + l.m[2][2]);
        f[drho_dt][i] = rate;
        rho += dt * rate;
        SymTensor s = load_sym(f, deviatoric, i);
        s = s + dt * plab::sph_solid::jaumann_rate(s, l, moduli_.shear);
        store_sym(f, deviatoric, i, s);
        const double p = plab::sph_solid::pressure(moduli_.bulk, rho, rho0_);
        f[pressure][i] = p;
        const SymTensor sigma = plab::sph_solid::cauchy_stress(s, p);
        store_sym(f, stress, i, sigma);
        // σ B/ρ², what the law multiplies the pair's kernel gradient by (eq. 15)
        const SymTensor bm = correct_momentum_ ? b : SymTensor{1, 1, 1, 0, 0, 0};
        for (int a = 0; a < 3; ++a)
            for (int c = 0; c < 3; ++c) {
                double t = 0;
                for (int k = 0; k < 3; ++k) t += plab::sph::component(sigma, a, k) * plab::sph::component(bm, k, c);
                f[stress_term + 3 * a + c][i] = t / (rho * rho);
            }
        store_sym(f, artificial, i, plab::sph_solid::artificial_stress(sigma, rho, epsilon_));
        update_damage(f, i);
    }

    // Islam §3.3: D_i, the failed fraction of the springs the particle had.
    // Springs are only ever lost after the bond command made them, so the
    // most ever counted is the initial number, whenever the command ran.
    static void update_damage(double* const* f, std::size_t i) {
        const double intact = f[intact_springs][i];
        double& initial = f[initial_springs][i];
        if (intact > initial) initial = intact;
        f[damage][i] = initial > 0 ? 1.0 - intact / initial : 0.0;
    }

    double rho0_;
    plab::sph_solid::Moduli moduli_;
    double epsilon_;
    bool correct_, correct_momentum_, pair_sum_;
    int group_;
};

} // namespace

namespace plab::sph_solid {

// The passes of plab_sph_solid, registered by its plab_plugin_init (sph_solid.cpp).
int register_passes(const plab_registrar* r) { return plab::add_pass<SphSolidStress>(r); }

} // namespace plab::sph_solid
