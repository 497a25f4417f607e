// A rigid body's true shape in a scene (`bodies[i].shape`): its mass
// properties (plab_host/mass_properties.hpp), its surface (for output, the
// pebble fill and the resolved fluid coupling) and an inside test, all in
// the body frame. Shapes: sphere, box, cylinder, ring, a closed mesh, and a
// union of analytic parts (Joubert et al. 2020's cross of five cuboids).
#pragma once

#include "json_reader.hpp"

#include <plab_host/clumps.hpp>
#include <plab_host/mass_properties.hpp>

#include <functional>
#include <string>

namespace plab {

struct BodyShape {
    MassProperties properties;  // per unit density
    BodySurface surface;
    std::function<bool(const Vec&)> inside;  // strictly inside; null for a mesh
};

// The shape of `s` (a 2D world's shapes are 1 m thick); a mesh's relative
// file is found in `scene_dir`.
BodyShape read_shape(const Node& s, int dim, const std::string& scene_dir);

// The rotation of a body frame: 2D, an angle in degrees about z; 3D,
// {"axis": [x, y, z], "angle": degrees} or a unit quaternion [w, x, y, z].
Eigen::Quaterniond read_orientation(const Node& n, int dim);

// The surface of a union of spheres (discs), each drawn whole: the look of a
// clump given by its pebbles alone.
BodySurface pebbles_surface(const std::vector<Pebble>& pebbles, int dim);

// The surface's faces as triangles (3D) or as edges a -> b in a triangle's
// first two corners (2D), for the mass-property and fill routines.
std::vector<Triangle> surface_triangles(const BodySurface& s);

} // namespace plab
