// Mass properties of a rigid body's shape, per unit density: its volume (a
// 2D body's area times the 1 m thickness of a 2D world), centroid and
// inertia tensor about the centroid; and the principal frame of that
// tensor. For the scene builder, which gives a rigid body its mass and
// inertia from its shape (issue 27): exact for the analytic shapes and for
// closed triangle meshes (the divergence theorem), converged by quadrature
// for a union of overlapping spheres or discs (a pebble clump).
#pragma once

#include <plab_host/types.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <vector>

namespace plab {

struct MassProperties {
    double volume = 0;                                // m^3 (2D: area x 1 m)
    Vec centroid = Vec::Zero();                       // m
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // about the centroid, per unit density, m^5
    // Scaled by a density: the mass and the inertia tensor in kg, kg m^2.
    double mass(double density) const { return density * volume; }
};

// The principal moments (ascending) and the rotation from the principal
// frame to the frame the tensor was given in (columns: the principal axes,
// a right-handed frame).
struct PrincipalAxes {
    Vec moments = Vec::Zero();
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};
PrincipalAxes principal_axes(const Eigen::Matrix3d& inertia);

// Analytic shapes, centred at the origin; cylinders and rings along z.
MassProperties sphere_properties(double radius);
MassProperties box_properties(const Vec& half_extents);
MassProperties cylinder_properties(double radius, double height);
MassProperties ring_properties(double outer_radius, double inner_radius, double height);  // a hollow cylinder

// A closed, consistently oriented triangle mesh (outward normals by the
// right-hand rule), convex or not: exact by the divergence theorem, as a sum
// of the signed tetrahedra each triangle makes with the origin. A volume
// that comes out negative means inward normals; the caller decides.
using Triangle = std::array<Vec, 3>;
MassProperties mesh_properties(const std::vector<Triangle>& triangles);

// The union of overlapping spheres (dim 3) or discs (dim 2, z ignored):
// each column of a square grid integrated exactly along its length through
// the union of the chords it cuts, the grid halved until the volume and the
// trace of the inertia change by less than `tolerance` (relative) between
// two grids. `converged` reports whether they did within the finest grid
// allowed (about 4e6 columns).
struct Pebble {
    Vec centre;
    double radius;
};
struct UnionProperties {
    MassProperties properties;
    double change = 0;  // the relative change at the last halving
    bool converged = false;
};
UnionProperties pebble_union_properties(const std::vector<Pebble>& pebbles, int dim, double tolerance = 1e-4);

} // namespace plab
