// Pebble fill (issue 27): the pebbles of a clump worked out from its shape,
// so that a scene gives a mesh (or an analytic shape made into one) and a
// surface tolerance instead of a hand-written pebble list.
//
// The surface, in the body frame: in 3D closed triangles with outward
// normals (right-hand rule); in 2D the boundary as closed polygon edges, one
// per triangle (its first two vertices are the edge a -> b, the third is
// ignored, and so is z), outside boundaries counter-clockwise and holes
// clockwise (a ring's inner circle).
//
// How: candidate pebbles are the points of a regular lattice that lie inside
// (told by the side of the nearest face where it is nearest inside a face,
// else by the generalised winding number of the triangles, 2D the winding
// number of the polygon), each with its inscribed radius, the distance to
// the surface, clamped to max_radius and dropped below min_radius. The surface is
// sampled on a lattice per triangle (2D: per edge) fine enough that every
// surface point is within h = tolerance / 2 of a sample. A greedy set cover
// then adds the candidate that brings the most still-uncovered samples
// within tolerance - h of the pebbles (ties: the larger radius, then the
// earlier lattice point), until every sample is or max_count pebbles are
// placed. No randomness: equal inputs give equal pebbles, bit for bit.
//
// What is guaranteed (up to round-off):
//  - every pebble lies inside the shape (its radius is at most its centre's
//    distance to the surface), so the union never sticks out of the body;
//  - `deviation` bounds, over the whole surface and not only at the
//    samples, the distance from a surface point to the pebbles' union: the
//    largest such distance at a sample plus the samples' covering radius
//    (the distance to the union changes by at most the distance moved);
//    `reached` says that this bound is within the tolerance.
// Not guaranteed: that the tolerance can be reached (a corner needs small
// pebbles, which min_radius, the lattice spacing or max_count may forbid:
// then reached is false and deviation says what was achieved); the fewest
// pebbles (greedy cover, close to but not the optimum); a full interior
// (pebbles go where the surface needs them, so deep voids may stay: a
// clump's mass and inertia come from its true shape, not from the pebbles).
//
// Cost: each lattice point's distance is brute force over the triangles
// (pruned by bounding spheres), fine for meshes of up to a few thousand
// triangles. The lattice spacing is tolerance / 4, coarsened so that about
// 5e4 points at most fall inside (and 5e5 in the bounding box), which keeps
// a fill under a second on one core (Release) for meshes of a few hundred
// triangles; a surface that would need more than 2e5 samples at this
// tolerance is refused.
#pragma once

#include <plab_host/mass_properties.hpp>  // Pebble, Triangle
#include <plab_host/types.hpp>             // kInf

#include <cstddef>
#include <vector>

namespace plab {

struct PebbleFillOptions {
    int dim = 3;
    double tolerance = 0;                      // m: the largest distance allowed from the surface to the union
    double min_radius = 0, max_radius = kInf;  // pebble radius range, m
    std::size_t max_count = 1000;              // stop here even if the tolerance is not met
};

struct PebbleFill {
    std::vector<Pebble> pebbles;   // in the order the greedy cover placed them
    double deviation = 0;          // m: bound on the distance from any surface point to the union
    double sampled_deviation = 0;  // m: the largest distance from a surface sample (<= the true figure <= deviation)
    bool reached = false;          // deviation <= tolerance
};

// Throws std::invalid_argument for an empty surface, one enclosing no
// volume (2D: area), a non-finite vertex, tolerance <= 0, a radius range
// that is empty or negative, max_count 0, a surface too large for the
// tolerance, or a shape in which no pebble of min_radius fits (naming the
// largest radius it holds).
PebbleFill fill_with_pebbles(const std::vector<Triangle>& surface, const PebbleFillOptions& options);

} // namespace plab
