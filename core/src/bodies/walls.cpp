#include <plab_host/walls.hpp>

#include <Eigen/Geometry>
#include <algorithm>

namespace plab {

namespace {

ClosestPoint on_segment(const Vec& a, const Vec& b, const Vec& x) {
    const Vec ab = b - a;
    const double len2 = ab.squaredNorm();
    double t = len2 > 0 ? (x - a).dot(ab) / len2 : 0.0;
    const bool interior = t > 0.0 && t < 1.0;
    t = std::clamp(t, 0.0, 1.0);
    return {a + t * ab, interior};
}

// Closest point on triangle abc by Voronoi regions (Ericson, Real-Time
// Collision Detection §5.1.5), written from the published derivation.
ClosestPoint on_triangle(const Vec& a, const Vec& b, const Vec& c, const Vec& p) {
    const Vec ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return {a, false};
    const Vec bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return {b, false};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return {a + d1 / (d1 - d3) * ab, false};
    const Vec cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return {c, false};
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return {a + d2 / (d2 - d6) * ac, false};
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return {b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b), false};
    const double denom = 1.0 / (va + vb + vc);
    return {a + ab * (vb * denom) + ac * (vc * denom), true};
}

Vec rotate(const Vec& v, const Vec& omega, double dt, int dim) {
    const double angle = omega.norm() * dt;
    if (angle == 0.0) return v;
    if (dim == 2) {
        const double c = std::cos(omega.z() * dt), s = std::sin(omega.z() * dt);
        return {c * v.x() - s * v.y(), s * v.x() + c * v.y(), 0.0};
    }
    return Eigen::AngleAxisd(angle, omega.normalized()) * v;
}

} // namespace

ClosestPoint closest_point(const Facet& f, const Vec& x) {
    switch (f.kind) {
    case FacetKind::segment: return on_segment(f.a, f.b, x);
    case FacetKind::triangle: return on_triangle(f.a, f.b, f.c, x);
    case FacetKind::plane: return {x - (x - f.a).dot(f.b) * f.b, true};
    }
    return {x, true};
}

int Walls::add_wall(Wall w) {
    walls.push_back(std::move(w));
    return int(walls.size()) - 1;
}

int Walls::find(const std::string& name) const {
    for (std::size_t i = 0; i < walls.size(); ++i)
        if (walls[i].name == name) return int(i);
    return -1;
}

void Walls::add_facet(int wall, Facet f) {
    f.wall = wall;
    f.id = next_facet_id++;
    facets.push_back(f);
    walls[wall].facets.push_back(int(facets.size()) - 1);
}

double Walls::move(double dt, int dim) {
    double max_disp = 0;
    for (std::size_t w = 0; w < walls.size(); ++w) {
        Wall& wall = walls[w];
        if (wall.velocity.isZero(0) && wall.angular_velocity.isZero(0)) continue;
        const Vec shift = wall.velocity * dt;
        auto move_point = [&](Vec& p) {
            const Vec q = wall.centre + rotate(p - wall.centre, wall.angular_velocity, dt, dim) + shift;
            max_disp = std::max(max_disp, (q - p).norm());
            p = q;
        };
        for (int fi : wall.facets) {
            Facet& f = facets[fi];
            move_point(f.a);
            if (f.kind == FacetKind::plane) {
                f.b = rotate(f.b, wall.angular_velocity, dt, dim);
            } else {
                move_point(f.b);
                if (f.kind == FacetKind::triangle) move_point(f.c);
            }
        }
        wall.centre += shift;
    }
    return max_disp;
}

} // namespace plab
