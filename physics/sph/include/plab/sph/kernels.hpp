// SPH smoothing kernels W(r, h) and their radial derivatives dW/dr, in 2D and
// 3D, each normalised so that the integral of W over its support is one:
//   Wendland C2   (thesis eq. 12; Islam eq. 5): C (2-q)^4 (1+2q),        q <= 2
//   cubic spline  (thesis eq. 11):               C [(2-q)^3 - 4(1-q)^3], q <= 1
//                                                C (2-q)^3,              1 < q <= 2
//   quintic spline (Morris 1997):                C [(3-q)^5 - 6(2-q)^5 + 15(1-q)^5], q <= 3
// with q = r/h. Normalisation constants C (2D, 3D):
//   Wendland 7/(64 pi h^2), 21/(256 pi h^3);
//   cubic    5/(14 pi h^2), 1/(4 pi h^3)  -- the thesis prints 15/(14 pi h^2)
//            for eq. 11, three times too large (tests/physics/sph_test.cpp
//            integrates W over a lattice and finds 1 with 5/14);
//   quintic  7/(478 pi h^2), 1/(120 pi h^3).
// Header-only and free of host types, part of the SDK (<plab/sph/kernels.hpp>):
// the sph model and passes, the coupling plug-ins, the tests and out-of-tree
// plug-ins share it.
#ifndef PLAB_SPH_KERNELS_HPP
#define PLAB_SPH_KERNELS_HPP

#include <cmath>

namespace plab::sph {

enum class KernelKind : int { wendland_c2 = 0, cubic_spline = 1, quintic_spline = 2 };
// the names scenes give the kernels, in KernelKind's order (a choice property)
inline constexpr const char* kernel_names[] = {"wendland_c2", "cubic", "quintic"};

// Support radius in units of h: 2 for Wendland C2 and the cubic spline, 3 for the quintic.
inline double support_factor(KernelKind k) { return k == KernelKind::quintic_spline ? 3.0 : 2.0; }

inline double normalisation(KernelKind k, int dim, double h) {
    const double hd = dim == 2 ? h * h : h * h * h;
    switch (k) {
    case KernelKind::wendland_c2: return (dim == 2 ? 7.0 / 64.0 : 21.0 / 256.0) / (M_PI * hd);
    case KernelKind::cubic_spline: return (dim == 2 ? 5.0 / 14.0 : 0.25) / (M_PI * hd);
    case KernelKind::quintic_spline: return (dim == 2 ? 7.0 / 478.0 : 1.0 / 120.0) / (M_PI * hd);
    }
    return 0;
}

namespace detail {
inline double pos(double x) { return x > 0 ? x : 0.0; }
inline double p3(double x) { return x * x * x; }
inline double p4(double x) { return x * x * x * x; }
inline double p5(double x) { return x * x * x * x * x; }

// shape f(q) and its derivative df/dq, without the constant C
inline double shape(KernelKind k, double q) {
    switch (k) {
    case KernelKind::wendland_c2: return q < 2 ? p4(2 - q) * (1 + 2 * q) : 0.0;
    case KernelKind::cubic_spline: return p3(pos(2 - q)) - 4 * p3(pos(1 - q));
    case KernelKind::quintic_spline: return p5(pos(3 - q)) - 6 * p5(pos(2 - q)) + 15 * p5(pos(1 - q));
    }
    return 0;
}
inline double shape_derivative(KernelKind k, double q) {
    switch (k) {
    case KernelKind::wendland_c2: return q < 2 ? -10 * q * p3(2 - q) : 0.0;  // d/dq[(2-q)^4(1+2q)]
    case KernelKind::cubic_spline: {
        const double a = pos(2 - q), b = pos(1 - q);
        return -3 * a * a + 12 * b * b;
    }
    case KernelKind::quintic_spline:
        return -5 * p4(pos(3 - q)) + 30 * p4(pos(2 - q)) - 75 * p4(pos(1 - q));
    }
    return 0;
}
} // namespace detail

// A kernel bound to a smoothing length and a dimension.
struct Kernel {
    KernelKind kind = KernelKind::wendland_c2;
    int dim = 2;
    double h = 1;

    double support() const { return support_factor(kind) * h; }
    double value(double r) const { return normalisation(kind, dim, h) * detail::shape(kind, r / h); }
    // dW/dr (<= 0): the gradient with respect to x_i is dW/dr (x_i - x_j)/r
    double derivative(double r) const {
        return normalisation(kind, dim, h) / h * detail::shape_derivative(kind, r / h);
    }
};

} // namespace plab::sph

#endif // PLAB_SPH_KERNELS_HPP
