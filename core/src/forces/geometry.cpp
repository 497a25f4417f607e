#include "forces/geometry.hpp"

#include "forces/row_lists.hpp"

#include <algorithm>
#include <cmath>

namespace plab {

namespace {

inline void put_row3(std::vector<double>& col, std::size_t k, const Vec& v) {
    col[3 * k] = v.x(); col[3 * k + 1] = v.y(); col[3 * k + 2] = v.z();
}

// Zeroes the outputs of row k that a model adds to (dt limit: no limit).
// Only active rows are handed to a model, so only they are zeroed: the
// outputs of an inactive row are stale and nothing reads them.
inline void clear_row_outputs(ContactSet& s, std::size_t k) {
    for (auto* v : {&s.force, &s.moment1, &s.moment2}) std::fill_n(v->data() + 3 * k, 3, 0.0);
    s.strain[k] = s.slip[k] = s.dashpot[k] = s.k_t[k] = s.k_r[k] = s.break_energy[k] = 0;
    s.dt_limit[k] = kInf;
    for (auto& a : s.acc1) a[k] = 0;
    for (auto& a : s.acc2) a[k] = 0;
}

} // namespace

// Signed: a ball behind the plane is pushed back.
double ball_plane_distance(const Facet& f, const Vec& xi, Vec& normal, std::uint8_t& interior) {
    normal = -f.b;
    interior = 1;
    return (xi - f.a).dot(f.b);
}

// A segment or triangle has two faces, and the distance to it is unsigned;
// so that a ball whose centre goes through one is not pushed out of the far
// face (its overlap would never pass the radius, and max_overlap never
// fire), the row remembers its side: when the normal of a contact inside
// the facet turns over from one step to the next (`normal` comes in as the
// last one; zero on a new row), the centre has crossed the facet, and the
// contact keeps the old normal at a negative distance, as for a plane.
double ball_facet_distance(const Facet& f, const Vec& xi, Vec& normal, std::uint8_t& interior) {
    const ClosestPoint cp = closest_point(f, xi);
    const Vec d = cp.point - xi;
    const double dist = d.norm();
    const Vec before = normal;
    const bool was_interior = interior != 0;
    normal = dist > 0 ? Vec(d / dist) : Vec::UnitX();
    interior = cp.interior;
    if (was_interior && cp.interior && before.dot(normal) < 0) {  // behind the face it came from
        normal = before;
        return -dist;
    }
    return dist;
}

// Ball–wall rows as ball_ball_geometry() does ball–ball ones: the range
// test of every row first, then the geometry of the active rows, listed
// without a branch per row (a third of a settled pile's wall candidates
// are out of range, in no pattern).
bool ball_wall_geometry(const Bodies& B, const Walls& walls, const ModelInstance& inst, ContactSet& s,
                        std::size_t begin, std::size_t end) {
    const RangeTest in_range(inst);  // (a bond holds at any gap)
    std::uint32_t rows[kContactBatch];
    bool exceeded = false;
    for (std::size_t k0 = begin; k0 < end; k0 += kContactBatch) {
        const std::size_t k1 = std::min(end, k0 + kContactBatch);
        for (std::size_t k = k0; k < k1; ++k) {
            Vec normal(&s.normal[3 * k]);  // the last step's (ball_facet_distance)
            const Facet& f = walls.facets[s.end2[k]];
            const Vec& x = B.position[s.end1[k]];
            const double dist = f.kind == FacetKind::plane ? ball_plane_distance(f, x, normal, s.interior[k])
                                                           : ball_facet_distance(f, x, normal, s.interior[k]);
            const double gap = dist - B.radius[s.end1[k]];
            put_row3(s.normal, k, normal);  // (the active rows' geometry below, and the next step's side)
            s.gap[k] = gap;
            s.distance[k] = dist;
            s.active[k] = in_range(s.history, k, dist, gap);
        }
        const std::size_t n_active = list_flagged_rows(s.active.data() + k0, k1 - k0, std::uint32_t(k0), rows);
        for (std::size_t a = 0; a < n_active; ++a) {
            const std::size_t k = rows[a];
            const std::int32_t i = s.end1[k];
            const Vec& xi = B.position[i];
            const double ri = B.radius[i], dist = s.distance[k], gap = s.gap[k];
            const Facet& f = walls.facets[s.end2[k]];
            const Vec normal(&s.normal[3 * k]);
            const Vec point = xi + normal * (ri + 0.5 * (dist - ri));
            const Vec vi = B.velocity[i] + B.angular_velocity[i].cross(point - xi);
            put_row3(s.point, k, point);
            put_row3(s.rel_velocity, k, walls.velocity_at(f.wall, point) - vi);
            put_row3(s.rel_angular_velocity, k, walls.walls[f.wall].angular_velocity - B.angular_velocity[i]);
            clear_row_outputs(s, k);  // (radii and masses: filled at rebuild, fill_pair_constants)
            exceeded |= -gap > inst.max_overlap * ri;
        }
    }
    return exceeded;
}

// Ball–ball rows in two passes: the range test over every candidate (most
// are not in contact; their gap and distance are all a model may read),
// listing the active rows without a branch per row, then the full geometry
// of the listed rows only. The in-range flags of a Verlet list follow no
// pattern, so a branch per row would be mispredicted about half the time.
namespace {
template <bool Periodic>
bool ball_ball_rows(const Bodies& B, const ModelInstance& inst, ContactSet& s, std::size_t begin, std::size_t end) {
    const RangeTest in_range(inst);
    std::uint32_t rows[kContactBatch];
    bool exceeded = false;
    for (std::size_t k0 = begin; k0 < end; k0 += kContactBatch) {
        const std::size_t k1 = std::min(end, k0 + kContactBatch);
        for (std::size_t k = k0; k < k1; ++k) {
            const std::int32_t i = s.end1[k], j = s.end2[k];
            const double dist = (seen_from<Periodic>(B, i, j) - B.position[i]).norm();
            const double gap = dist - s.radius1[k] - s.radius2[k];
            s.gap[k] = gap;
            s.distance[k] = dist;
            s.active[k] = in_range(s.history, k, dist, gap);
        }
        const std::size_t n_active = list_flagged_rows(s.active.data() + k0, k1 - k0, std::uint32_t(k0), rows);
        for (std::size_t a = 0; a < n_active; ++a) {
            const std::size_t k = rows[a];
            const double ri = s.radius1[k], rj = s.radius2[k], gap = s.gap[k];
            const std::int32_t i = s.end1[k], j = s.end2[k];
            const PairKinematics p = ball_pair_kinematics(B, i, j, seen_from<Periodic>(B, i, j), velocity_seen_from<Periodic>(B, i, j),
                                                            ri, s.distance[k], gap);
            put_row3(s.normal, k, p.normal);
            put_row3(s.point, k, p.point);
            put_row3(s.rel_velocity, k, p.rel_velocity);
            put_row3(s.rel_angular_velocity, k, p.rel_angular_velocity);
            clear_row_outputs(s, k);  // (radii and masses: filled at rebuild, fill_pair_constants)
            exceeded |= -gap > inst.max_overlap * std::min(ri, rj);
        }
    }
    return exceeded;
}
} // namespace

bool ball_ball_geometry(const Bodies& B, const ModelInstance& inst, ContactSet& s, std::size_t begin,
                        std::size_t end) {
    return B.cell.any() ? ball_ball_rows<true>(B, inst, s, begin, end) : ball_ball_rows<false>(B, inst, s, begin, end);
}

// A ball touching a wall along several facets. An edge/vertex contact is
// redundant when its surface point also lies on another facet of the same
// wall that is at least as close (ties: the lower row wins): flat
// neighbours then push once, a convex edge pushes once, and a concave corner
// (two interior contacts) pushes from both faces.
void resolve_wall_features(const Bodies& bodies, const Walls& walls, ContactSet& s) {
    const std::size_t n = s.size();
    for (std::size_t a = 0; a < n;) {
        std::size_t b = a;
        while (b < n && s.end1[b] == s.end1[a]) ++b;  // rows of one ball are adjacent (sorted by id)
        for (std::size_t k = a; b - a > 1 && k < b; ++k) {
            if (!s.active[k] || s.interior[k]) continue;
            const Facet& fk = walls.facets[s.end2[k]];
            const Vec xi = bodies.position[s.end1[k]];
            const Vec surface = xi + Vec(&s.normal[3 * k]) * s.distance[k];
            const double eps = 1e-9 * (1.0 + s.radius1[k]);
            for (std::size_t o = a; o < b; ++o) {
                if (o == k || !s.active[o] || walls.facets[s.end2[o]].wall != fk.wall) continue;
                const bool closer = s.distance[o] < s.distance[k] - eps ||
                                    (std::fabs(s.distance[o] - s.distance[k]) <= eps && (s.interior[o] || o < k));
                if (closer && (closest_point(walls.facets[s.end2[o]], surface).point - surface).norm() <= eps) {
                    s.active[k] = 0;
                    break;
                }
            }
        }
        a = b;
    }
}

} // namespace plab
