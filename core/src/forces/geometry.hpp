// The contact geometry the host computes once per candidate row (Yade's
// Ig2), by the kind of pair: ball–ball, ball–facet (a segment or a triangle
// of a wall) and ball–plane. Each kernel takes rows [begin, end) of a
// contact table: the range test of every row (gap, centre distance, the
// active flag), then the normal, contact point and relative velocities of
// the active rows, whose outputs it zeroes for the model. It returns true
// when an active contact overlaps beyond its model's max_overlap (the
// instability detector's check, done here while the gap is at hand).
#pragma once

#include <plab_host/bodies.hpp>
#include <plab_host/walls.hpp>

#include "contacts/model_instance.hpp"

#include <cstdint>
#include <vector>

namespace plab {

// Whether a candidate (ball–ball or ball–wall) is in its model's range:
// bonded rows always are; otherwise the gap or the centre distance, as the
// model declares.
struct RangeTest {
    bool by_distance;
    int persist;  // history slot that marks a bond, or -1
    double range;
    std::size_t stride;
    explicit RangeTest(const ModelInstance& inst)
        : by_distance(inst.desc->range_kind == PLAB_RANGE_DISTANCE), persist(inst.desc->persist_slot),
          range(inst.range), stride(std::size_t(inst.stride)) {}
    // The rule with the range kind and whether bonds count fixed at compile
    // time (range_test_rows()'s candidate loop tests neither per row).
    template <bool ByDistance, bool Bonds>
    bool in(const double* history, std::size_t k, double dist, double gap) const {
        const bool near = ByDistance ? dist <= range : gap <= range;
        return Bonds ? near | (history[k * stride + std::size_t(persist)] > 0) : near;
    }
    bool operator()(const double* history, std::size_t k, double dist, double gap) const {
        if (by_distance) return persist >= 0 ? in<true, true>(history, k, dist, gap) : in<true, false>(history, k, dist, gap);
        return persist >= 0 ? in<false, true>(history, k, dist, gap) : in<false, false>(history, k, dist, gap);
    }
    bool operator()(const std::vector<double>& history, std::size_t k, double dist, double gap) const {
        return (*this)(history.data(), k, dist, gap);
    }
};

// The surface gap of two balls at centre distance dist: every ball–ball
// path (the range test, both packers, row_gap) takes it from
// here, so a gap recomputed for a reader has the range test's bits.
inline double surface_gap(double dist, double ri, double rj) { return dist - ri - rj; }

// The contact geometry of balls i and j at centre distance `dist`, gap `gap`:
// normal from i to j, contact point in the middle of the overlap, and the
// velocities of j relative to i at that point.
struct PairKinematics {
    Vec normal, point, rel_velocity, rel_angular_velocity;
    Vec arm1, arm2;  // point - x_i and point - x_j: the lever arms of r x F
};
// The unit vector from xi to xj at centre distance dist: one division, not
// three (every ball–ball path takes it from here, so all give the same bits).
inline Vec centre_normal(const Vec& xi, const Vec& xj, double dist) {
    return dist > 0 ? Vec((xj - xi) * (1.0 / dist)) : Vec::UnitX();
}
// centre_normal() in the plane (a 2D world: z = 0), the same arithmetic on
// x and y; its z is zero.
struct PlaneNormal { double x, y; };
inline PlaneNormal centre_normal_2d(const Vec& xi, const Vec& xj, double dist) {
    const double inv = 1.0 / dist;
    const bool apart = dist > 0;  // (else the normal is x)
    return {apart ? (xj.x() - xi.x()) * inv : 1.0, apart ? (xj.y() - xi.y()) * inv : 0.0};
}
// The contact point of two balls: on the normal from ball i's centre xi,
// its radius ri plus half the gap further (the middle of the overlap).
inline Vec ball_contact_point(const Vec& xi, const Vec& normal, double ri, double gap) {
    return xi + normal * (ri + 0.5 * gap);
}
// Ball j's centre as ball i sees it: its minimum image in a periodic cell
// (Periodic, chosen once per batch: no test per row without one).
template <bool Periodic>
inline Vec seen_from(const Bodies& B, std::int32_t i, std::int32_t j) {
    if constexpr (Periodic) return B.cell.image(B.position[i], B.position[j]);
    else return B.position[j];
}
// Ball j's velocity as ball i sees it: its image's across a sheared
// boundary (Lees–Edwards: -/+ shear_rate L_y along x), its own otherwise.
template <bool Periodic>
inline Vec velocity_seen_from(const Bodies& B, std::int32_t i, std::int32_t j) {
    if constexpr (Periodic) return B.cell.image_velocity(B.position[i], B.position[j], B.velocity[j]);
    else return B.velocity[j];
}
// (xj, vj: ball j's centre and velocity, or its minimum image's in a periodic cell)
inline PairKinematics ball_pair_kinematics(const Bodies& B, std::int32_t i, std::int32_t j, const Vec& xj, const Vec& vj_,
                                           double ri, double dist, double gap) {
    const Vec& xi = B.position[i];
    PairKinematics p;
    p.normal = centre_normal(xi, xj, dist);
    p.point = ball_contact_point(xi, p.normal, ri, gap);
    p.arm1 = p.point - xi;
    p.arm2 = p.point - xj;
    const Vec vj = vj_ + B.angular_velocity[j].cross(p.arm2);
    const Vec vi = B.velocity[i] + B.angular_velocity[i].cross(p.arm1);
    p.rel_velocity = vj - vi;
    p.rel_angular_velocity = B.angular_velocity[j] - B.angular_velocity[i];
    return p;
}
inline PairKinematics ball_pair_kinematics(const Bodies& B, std::int32_t i, std::int32_t j, double ri, double dist,
                                           double gap) {
    return ball_pair_kinematics(B, i, j, B.position[j], B.velocity[j], ri, dist, gap);
}
// End 2's centre of ball–ball row k as end 1 sees it (the minimum image in
// a periodic cell): for the readers, where a test per row costs nothing.
inline Vec row_end2_centre(const Bodies& B, const ContactSet& s, std::size_t k) {
    const Vec& xj = B.position[s.end2[k]];
    return B.cell.any() ? B.cell.image(B.position[s.end1[k]], xj) : xj;
}

// A row's gap, normal and contact point at the last force pass, for the
// readers of the tables (outputs, stress, stiffness sums): a packed table's
// are recomputed from the positions with the force pass's arithmetic (the
// same bits, as long as no ball moved since), any other table's are read
// from its columns.
inline double row_gap(const Bodies& B, const ContactSet& s, std::size_t k) {
    if (!s.packed) return s.gap[k];
    const double dist = (row_end2_centre(B, s, k) - B.position[s.end1[k]]).norm();
    return surface_gap(dist, B.radius[s.end1[k]], B.radius[s.end2[k]]);
}
inline Vec row_normal(const Bodies& B, const ContactSet& s, std::size_t k) {
    if (!s.packed) return Vec(&s.normal[3 * k]);
    const Vec &xi = B.position[s.end1[k]], xj = row_end2_centre(B, s, k);
    return centre_normal(xi, xj, (xj - xi).norm());
}
inline Vec row_point(const Bodies& B, const ContactSet& s, std::size_t k) {
    if (!s.packed) return Vec(&s.point[3 * k]);
    return ball_contact_point(B.position[s.end1[k]], row_normal(B, s, k), B.radius[s.end1[k]], row_gap(B, s, k));
}
// The radius of row k's end 1 or end 2 (a wall's: 0), from the bodies: a
// packed table keeps no radius columns, and a ball's radius changes only
// with the scene, which rebuilds the lists.
inline double row_end_radius(const Bodies& B, const ContactSet& s, std::size_t k, bool end2) {
    return end2 ? (s.with_wall ? 0.0 : B.radius[s.end2[k]]) : B.radius[s.end1[k]];
}

bool ball_ball_geometry(const Bodies& bodies, const ModelInstance& inst, ContactSet& s, std::size_t begin,
                        std::size_t end);
// Rows of a table whose end 2 is a wall facet: ball–plane or ball–facet by
// the facet's kind.
bool ball_wall_geometry(const Bodies& bodies, const Walls& walls, const ModelInstance& inst, ContactSet& s,
                        std::size_t begin, std::size_t end);
// The distance of a ball's centre x from a plane, and the normal into it.
double ball_plane_distance(const Facet& plane, const Vec& x, Vec& normal, std::uint8_t& interior);
// The same for a segment or a triangle (see geometry.cpp: the side kept).
double ball_facet_distance(const Facet& facet, const Vec& x, Vec& normal, std::uint8_t& interior);
inline bool contact_geometry(const Bodies& bodies, const Walls& walls, const ModelInstance& inst, ContactSet& s,
                             std::size_t begin, std::size_t end) {
    return s.with_wall ? ball_wall_geometry(bodies, walls, inst, s, begin, end)
                       : ball_ball_geometry(bodies, inst, s, begin, end);
}
// A ball touching one wall along several facets pushed once per face.
void resolve_wall_features(const Bodies& bodies, const Walls& walls, ContactSet& s);

} // namespace plab
