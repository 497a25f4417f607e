#include <plab_host/mass_properties.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <utility>

namespace plab {

namespace {

// The inertia tensor I = tr(S) 1 - S from the second-moment matrix
// S = ∫ r rᵀ dV about the centroid.
Eigen::Matrix3d inertia_of(const Eigen::Matrix3d& second_moment) {
    return second_moment.trace() * Eigen::Matrix3d::Identity() - second_moment;
}

MassProperties diagonal(double volume, double ixx, double iyy, double izz) {
    MassProperties p;
    p.volume = volume;
    p.inertia.diagonal() << ixx, iyy, izz;
    return p;
}

// Volume, first and second moments about the origin, summed part by part.
struct Moments {
    double volume = 0;
    Vec first = Vec::Zero();
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    MassProperties about_centroid() const {
        MassProperties p;
        p.volume = volume;
        if (!(volume != 0)) return p;
        p.centroid = first / volume;
        p.inertia = inertia_of(second - volume * p.centroid * p.centroid.transpose());
        return p;
    }
};

} // namespace

PrincipalAxes principal_axes(const Eigen::Matrix3d& inertia) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(0.5 * (inertia + inertia.transpose()));
    Eigen::Matrix3d axes = solver.eigenvectors();
    if (axes.determinant() < 0) axes.col(2) = -axes.col(2);  // a rotation, not a reflection
    PrincipalAxes out;
    out.moments = solver.eigenvalues();
    out.orientation = Eigen::Quaterniond(axes).normalized();
    return out;
}

MassProperties sphere_properties(double r) {
    const double v = 4.0 / 3.0 * M_PI * r * r * r, i = 0.4 * v * r * r;
    return diagonal(v, i, i, i);
}

MassProperties box_properties(const Vec& a) {
    const double v = 8.0 * a.x() * a.y() * a.z();
    return diagonal(v, v * (a.y() * a.y() + a.z() * a.z()) / 3.0, v * (a.x() * a.x() + a.z() * a.z()) / 3.0,
                    v * (a.x() * a.x() + a.y() * a.y()) / 3.0);
}

MassProperties cylinder_properties(double r, double h) { return ring_properties(r, 0.0, h); }

MassProperties ring_properties(double R, double r, double h) {
    const double v = M_PI * (R * R - r * r) * h, radial = R * R + r * r;
    const double side = v * (3.0 * radial + h * h) / 12.0;
    return diagonal(v, side, side, 0.5 * v * radial);
}

// Each triangle (a, b, c) with the origin is a tetrahedron of signed volume
// a·(b×c)/6, centroid (a+b+c)/4 and second moment (V/20)(Σ vvᵀ + s sᵀ),
// s = a+b+c (the canonical tetrahedron's, mapped: Tonon 2004).
MassProperties mesh_properties(const std::vector<Triangle>& triangles) {
    Moments m;
    for (const Triangle& t : triangles) {
        const Vec &a = t[0], &b = t[1], &c = t[2];
        const double v = a.dot(b.cross(c)) / 6.0;
        const Vec s = a + b + c;
        m.volume += v;
        m.first += v * s / 4.0;
        m.second += v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
    }
    return m.about_centroid();
}

namespace {

using Interval = std::pair<double, double>;

// The union of intervals, merged in place; returns their count.
std::size_t merge(std::vector<Interval>& iv) {
    std::sort(iv.begin(), iv.end());
    std::size_t n = 0;
    for (const Interval& x : iv) {
        if (n > 0 && x.first <= iv[n - 1].second) iv[n - 1].second = std::max(iv[n - 1].second, x.second);
        else iv[n++] = x;
    }
    return n;
}

// One column at (u, w) of cross-section `area` along the axis `along`
// (3D: z; 2D: y), through the chords of the pebbles it cuts: exact along
// the column, midpoint across it (with the column's own ∫u² = area h²/12).
void add_column(const std::vector<Pebble>& pebbles, int along, double u, double w, double area, double h,
                std::vector<Interval>& iv, Moments& m) {
    iv.clear();
    constexpr int iu = 0, iw = 1;  // the column's coordinates: x, y (2D: x only)
    for (const Pebble& p : pebbles) {
        const double du = u - p.centre[iu], dw = along == 2 ? w - p.centre[iw] : 0.0;
        const double half2 = p.radius * p.radius - du * du - dw * dw;
        if (half2 > 0) iv.emplace_back(p.centre[along] - std::sqrt(half2), p.centre[along] + std::sqrt(half2));
    }
    const std::size_t n = merge(iv);
    for (std::size_t k = 0; k < n; ++k) {
        const double z0 = iv[k].first, z1 = iv[k].second;
        const double len = z1 - z0, mom1 = 0.5 * (z1 * z1 - z0 * z0), mom2 = (z1 * z1 * z1 - z0 * z0 * z0) / 3.0;
        Vec at = Vec::Zero();
        at[iu] = u;
        if (along == 2) at[iw] = w;
        const double v = area * len;
        m.volume += v;
        m.first += v * at;
        m.first[along] += area * mom1;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                if (i == along && j == along) m.second(i, j) += area * mom2;
                else if (i == along || j == along) m.second(i, j) += area * mom1 * at[i == along ? j : i];
                else m.second(i, j) += v * at[i] * at[j];
            }
        m.second(iu, iu) += v * h * h / 12.0;
        if (along == 2) m.second(iw, iw) += v * h * h / 12.0;
    }
}

// The union on a grid of spacing h over the pebbles' bounding box.
MassProperties union_on_grid(const std::vector<Pebble>& pebbles, int dim, double h, const Vec& lo, const Vec& hi) {
    Moments m;
    std::vector<Interval> iv;
    const int along = dim == 2 ? 1 : 2;
    const long nu = long(std::ceil((hi.x() - lo.x()) / h)), nw = dim == 2 ? 1 : long(std::ceil((hi.y() - lo.y()) / h));
    const double area = dim == 2 ? h : h * h;  // 2D: the column's width x the 1 m thickness
    for (long a = 0; a < nu; ++a)
        for (long b = 0; b < nw; ++b)
            add_column(pebbles, along, lo.x() + (a + 0.5) * h, lo.y() + (b + 0.5) * h, area, h, iv, m);
    if (dim == 2) m.second(2, 2) += m.volume / 12.0;  // the 1 m slab's own ∫z² (z in [-0.5, 0.5])
    return m.about_centroid();
}

} // namespace

UnionProperties pebble_union_properties(const std::vector<Pebble>& pebbles, int dim, double tolerance) {
    UnionProperties out;
    if (pebbles.empty()) return out;
    Vec lo = Vec::Constant(kInf), hi = Vec::Constant(-kInf);
    double smallest = kInf;
    for (const Pebble& p : pebbles) {
        lo = lo.cwiseMin(p.centre - Vec::Constant(p.radius));
        hi = hi.cwiseMax(p.centre + Vec::Constant(p.radius));
        smallest = std::min(smallest, p.radius);
    }
    constexpr double kMaxColumns = 4e6;
    double h = smallest / 2;
    MassProperties last = union_on_grid(pebbles, dim, h, lo, hi);
    for (;;) {
        h /= 2;
        const double columns = dim == 2 ? (hi.x() - lo.x()) / h : (hi.x() - lo.x()) * (hi.y() - lo.y()) / (h * h);
        if (columns > kMaxColumns) break;
        const MassProperties next = union_on_grid(pebbles, dim, h, lo, hi);
        out.change = std::max(std::fabs(next.volume - last.volume) / next.volume,
                              std::fabs(next.inertia.trace() - last.inertia.trace()) / next.inertia.trace());
        last = next;
        if (out.change < tolerance) {
            out.converged = true;
            break;
        }
    }
    out.properties = last;
    return out;
}

} // namespace plab
