// Walls: 2D line segments (polylines), 3D triangles (rectangles are two
// triangles) and infinite planes (lines in 2D). A wall is a set of facets
// moving rigidly with a prescribed velocity and angular velocity about a
// point, so a gate can be lifted or a piston pushed.
#pragma once

#include <plab_host/types.hpp>

#include <string>
#include <vector>

namespace plab {

enum class FacetKind { segment, triangle, plane };

struct Facet {
    FacetKind kind = FacetKind::segment;
    int wall = 0;       // owning wall index
    BodyId id = 0;      // stable id (contact key)
    Vec a = Vec::Zero(), b = Vec::Zero(), c = Vec::Zero();  // vertices; plane: a = point, b = unit normal
};

// Closest point of a facet to a point, and whether it lies on the facet's
// interior (false: on an edge or vertex; such contacts defer to interior ones).
struct ClosestPoint {
    Vec point;
    bool interior;
};
ClosestPoint closest_point(const Facet& f, const Vec& x);

struct Wall {
    std::string name;
    int group = 0;
    Vec velocity = Vec::Zero();
    Vec angular_velocity = Vec::Zero();
    Vec centre = Vec::Zero();       // centre of rotation, moves with the wall
    Vec force = Vec::Zero();        // force the balls exert on the wall, N
    Vec moment = Vec::Zero();       // about `centre`, N m
    std::vector<int> facets;
};

struct Walls {
    std::vector<Wall> walls;
    std::vector<Facet> facets;
    BodyId next_facet_id = 0;

    int add_wall(Wall w);
    int find(const std::string& name) const;  // wall index, -1 when unknown
    void add_facet(int wall, Facet f);
    // Rigid motion over dt; returns the largest vertex displacement.
    double move(double dt, int dim);
    // Velocity of wall w's material point at x.
    Vec velocity_at(int wall, const Vec& x) const {
        const Wall& w = walls[wall];
        return w.velocity + w.angular_velocity.cross(x - w.centre);
    }
};

} // namespace plab
