// The hypoelastic solid of the SPH solid package (Islam 2023 §3.1), per
// particle, as functions of values:
//   σ = S - p I,  p = K (ρ/ρ0 - 1)                     (Islam §3.1, the linear EOS)
//   Ṡ = 2G (ε̇ - ⅓ tr(ε̇) I) + S ωᵀ + ω S             (Islam eq. 17, the Jaumann rate)
//   ε̇ = ½ (l + lᵀ),  ω = ½ (l - lᵀ)                   (Islam eq. 18)
// and Monaghan's artificial stress (Monaghan 2000; Gray, Monaghan & Swegle
// 2001), the tensor form of the term Islam writes as eq. 16: in the
// principal frame of σ_i, R_i^aa = -ε σ_i^aa/ρ_i² where σ_i^aa > 0 (zero
// where compressive), turned back into the x, y, z frame.
// 2D is plane strain: ε̇_zz = 0, the trace and S_zz are those of 3D (the
// plate and beam references, Gray et al. 2001, are plane-strain too).
// Header-only, free of host types, part of the SDK (<plab/sph_solid/elasticity.hpp>).
#ifndef PLAB_SPH_SOLID_ELASTICITY_HPP
#define PLAB_SPH_SOLID_ELASTICITY_HPP

#include <plab/sph/gradient_correction.hpp>

#include <algorithm>
#include <cmath>

namespace plab::sph_solid {

using plab::sph::SymTensor;
using plab::sph::Tensor;

// Elastic constants from E and ν: bulk modulus K, shear modulus G, and the
// speed of a longitudinal wave c = sqrt((K + 4G/3)/ρ0), the fastest signal
// the CFL limit and the artificial viscosity see.
struct Moduli {
    double bulk, shear, wave_speed;
};
inline Moduli moduli(double youngs_modulus, double poissons_ratio, double rest_density) {
    const double k = youngs_modulus / (3 * (1 - 2 * poissons_ratio));
    const double g = youngs_modulus / (2 * (1 + poissons_ratio));
    return {k, g, std::sqrt((k + 4 * g / 3) / rest_density)};
}

// p = K (ρ/ρ0 - 1) (Islam §3.1)
inline double pressure(double bulk, double rho, double rho0) { return bulk * (rho / rho0 - 1); }

// σ = S - p I
inline SymTensor cauchy_stress(const SymTensor& s, double p) { return {s.xx - p, s.yy - p, s.zz - p, s.xy, s.yz, s.zx}; }

// Islam eqs. 17–18: the deviatoric stress rate from the velocity gradient
// l_ab = ∂v_a/∂x_b. (S ωᵀ + ω S)_ab = S_ac ω_bc + ω_ac S_cb; it is
// symmetric because S is, and it rotates S with the material without
// creating or destroying stress (objectivity: a rigid spin gives ε̇ = 0
// and changes S by a rotation only).
inline SymTensor jaumann_rate(const SymTensor& s, const Tensor& l, double shear) {
    double e[3][3], w[3][3];
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
            e[a][b] = 0.5 * (l.m[a][b] + l.m[b][a]);
            w[a][b] = 0.5 * (l.m[a][b] - l.m[b][a]);
        }
    const double trace = e[0][0] + e[1][1] + e[2][2];
    double rate[3][3];
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
            double spin = 0;
            for (int c = 0; c < 3; ++c)
                spin += sph::component(s, a, c) * w[b][c] + w[a][c] * sph::component(s, c, b);
            rate[a][b] = 2 * shear * (e[a][b] - (a == b ? trace / 3 : 0.0)) + spin;
        }
    return {rate[0][0], rate[1][1], rate[2][2], rate[0][1], rate[1][2], rate[2][0]};
}

// The eigenvalues λ_k and unit eigenvectors (columns of q) of a symmetric
// tensor, by cyclic Jacobi rotations (a few sweeps to round-off for 3×3).
struct Principal {
    double value[3];
    double q[3][3];  // q[a][k]: component a of eigenvector k
};
inline Principal principal(const SymTensor& s) {
    double a[3][3] = {{s.xx, s.xy, s.zx}, {s.xy, s.yy, s.yz}, {s.zx, s.yz, s.zz}};
    Principal p{{0, 0, 0}, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    for (int sweep = 0; sweep < 10; ++sweep) {
        const double off = a[0][1] * a[0][1] + a[1][2] * a[1][2] + a[2][0] * a[2][0];
        const double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
        if (!(off > 1e-32 * diag)) break;  // (also an all-zero tensor)
        for (int i = 0; i < 2; ++i)
            for (int j = i + 1; j < 3; ++j) {
                if (a[i][j] == 0) continue;
                // the rotation that zeroes a[i][j] (Golub & Van Loan, symmetric Schur)
                const double theta = (a[j][j] - a[i][i]) / (2 * a[i][j]);
                const double t = (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1));
                const double c = 1 / std::sqrt(t * t + 1), sn = t * c;
                for (int k = 0; k < 3; ++k) {  // a = Jᵀ a J
                    const double aki = a[k][i], akj = a[k][j];
                    a[k][i] = c * aki - sn * akj;
                    a[k][j] = sn * aki + c * akj;
                }
                for (int k = 0; k < 3; ++k) {
                    const double aik = a[i][k], ajk = a[j][k];
                    a[i][k] = c * aik - sn * ajk;
                    a[j][k] = sn * aik + c * ajk;
                }
                for (int k = 0; k < 3; ++k) {
                    const double qki = p.q[k][i], qkj = p.q[k][j];
                    p.q[k][i] = c * qki - sn * qkj;
                    p.q[k][j] = sn * qki + c * qkj;
                }
            }
    }
    for (int k = 0; k < 3; ++k) p.value[k] = a[k][k];
    return p;
}

// Monaghan's artificial stress of one particle: R = Q diag(r_k) Qᵀ with
// r_k = -ε λ_k/ρ² for a tensile principal stress λ_k > 0, else 0 (Gray et
// al. 2001 eq. 3.5). The pair term is (R_i + R_j) f_ij^n (the law).
inline SymTensor artificial_stress(const SymTensor& sigma, double rho, double epsilon) {
    if (epsilon <= 0) return {};
    const Principal p = principal(sigma);
    double r[3];
    for (int k = 0; k < 3; ++k) r[k] = p.value[k] > 0 ? -epsilon * p.value[k] / (rho * rho) : 0.0;
    const auto at = [&](int a, int b) {
        return p.q[a][0] * r[0] * p.q[b][0] + p.q[a][1] * r[1] * p.q[b][1] + p.q[a][2] * r[2] * p.q[b][2];
    };
    return {at(0, 0), at(1, 1), at(2, 2), at(0, 1), at(1, 2), at(2, 0)};
}

} // namespace plab::sph_solid

#endif // PLAB_SPH_SOLID_ELASTICITY_HPP
