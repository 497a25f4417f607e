// The kernel-gradient correction of Chen et al. (1999) (Islam eq. 20;
// Joubert et al. 2020 eq. 9): a particle's kernel gradients are mapped by
// a matrix B_i so that the SPH gradient of any linear field is exact, also
// where the support is cut (free surfaces, corners):
//   Ŵ_ij,β = B_i^βα W_ij,α,   B_i = A_i^-1,   A_i^βα = -Σ_j V_j x_ij^β W_ij,α,
// V_j = m_j/ρ_j, x_ij = x_i - x_j. With ∇_i W_ij = (dW/dr) (x_i - x_j)/r,
// A_i = -Σ_j V_j r (dW/dr) n n (n the unit vector between the pair) is
// symmetric and positive (dW/dr <= 0), and so is B_i: six numbers in 3D,
// three in 2D.
//
// The sums are accumulated pair by pair (both ends get the same term,
// moment_term()) and inverted once per particle (correction()); a gradient
// summed with the raw kernel gradients, G_ab = Σ_j V_j f_a (∇_i W_ij)_b, is
// corrected afterwards as G B (corrected()), since B enters linearly.
// Written for the SPH solid (physics/sph_solid) and meant for a
// gradient-corrected SPH fluid too. Header-only, free of host types, part
// of the SDK (<plab/sph/gradient_correction.hpp>).
#ifndef PLAB_SPH_GRADIENT_CORRECTION_HPP
#define PLAB_SPH_GRADIENT_CORRECTION_HPP

#include <plab/vec3.hpp>

#include <cmath>

namespace plab::sph {

// A symmetric 3×3 tensor by its six components (xx, yy, zz, xy, yz, zx);
// in 2D the z components of a correction are those of the identity.
struct SymTensor {
    double xx = 0, yy = 0, zz = 0, xy = 0, yz = 0, zx = 0;
};

inline SymTensor operator+(const SymTensor& a, const SymTensor& b) {
    return {a.xx + b.xx, a.yy + b.yy, a.zz + b.zz, a.xy + b.xy, a.yz + b.yz, a.zx + b.zx};
}
inline SymTensor operator*(double s, const SymTensor& a) {
    return {s * a.xx, s * a.yy, s * a.zz, s * a.xy, s * a.yz, s * a.zx};
}

// A full 3×3 tensor, row-major: m[a][b] (a velocity gradient ∂v_a/∂x_b).
struct Tensor {
    double m[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
};

inline double component(const SymTensor& s, int a, int b) {
    if (a == b) return a == 0 ? s.xx : a == 1 ? s.yy : s.zz;
    const int k = a + b;  // 1: xy, 3: yz, 2: zx
    return k == 1 ? s.xy : k == 3 ? s.yz : s.zx;
}

// The term of one pair in A_i (and, alike, in A_j): -V_other r (dW/dr) n n,
// n the unit vector between the two (its sign does not matter).
inline SymTensor moment_term(double volume_other, double r, double dW, const Vec3& n) {
    const double s = -volume_other * r * dW;
    return {s * n.x * n.x, s * n.y * n.y, s * n.z * n.z, s * n.x * n.y, s * n.y * n.z, s * n.z * n.x};
}

// B = A^-1 in 2D (the xy block; B_zz = 1) or 3D. A particle whose A is
// (nearly) singular — fewer neighbours than dimensions, all in a line —
// keeps the raw gradients: B = I. "Nearly": det A below min_det times the
// value of a full support's (1 in units of A), i.e. the neighbours span
// the plane or space too thinly to invert without amplifying noise.
inline SymTensor correction(const SymTensor& a, int dim, double min_det = 1e-3) {
    const SymTensor identity{1, 1, 1, 0, 0, 0};
    if (dim == 2) {
        const double det = a.xx * a.yy - a.xy * a.xy;
        if (!(det > min_det)) return identity;
        return {a.yy / det, a.xx / det, 1.0, -a.xy / det, 0.0, 0.0};
    }
    // cofactors of the symmetric matrix
    const double c_xx = a.yy * a.zz - a.yz * a.yz, c_yy = a.xx * a.zz - a.zx * a.zx, c_zz = a.xx * a.yy - a.xy * a.xy;
    const double c_xy = a.yz * a.zx - a.xy * a.zz, c_yz = a.xy * a.zx - a.xx * a.yz, c_zx = a.xy * a.yz - a.yy * a.zx;
    const double det = a.xx * c_xx + a.xy * c_xy + a.zx * c_zx;
    if (!(det > min_det)) return identity;
    const double inv = 1.0 / det;
    return {c_xx * inv, c_yy * inv, c_zz * inv, c_xy * inv, c_yz * inv, c_zx * inv};
}

// A gradient summed with raw kernel gradients, corrected: (G B)_ab = G_ac B_cb.
inline Tensor corrected(const Tensor& g, const SymTensor& b) {
    Tensor out;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            out.m[i][j] = g.m[i][0] * component(b, 0, j) + g.m[i][1] * component(b, 1, j) + g.m[i][2] * component(b, 2, j);
    return out;
}

// The corrected gradient of one pair, B ∇W.
inline Vec3 corrected(const SymTensor& b, const Vec3& grad) {
    return {b.xx * grad.x + b.xy * grad.y + b.zx * grad.z, b.xy * grad.x + b.yy * grad.y + b.yz * grad.z,
            b.zx * grad.x + b.yz * grad.y + b.zz * grad.z};
}

} // namespace plab::sph

#endif // PLAB_SPH_GRADIENT_CORRECTION_HPP
