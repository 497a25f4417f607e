// Clumps: rigid bodies whose contact geometry is a set of spheres (discs in
// 2D), the pebbles, fixed in the body frame (PFC's clumps). A pebble is a
// ball of the world's Bodies, so every contact model works on it unchanged;
// its clump moves it. The clump has the mass, centre, orientation and
// principal moments of its true shape (the scene builder's, from
// plab_host/mass_properties.hpp), not of its pebbles. State as
// structure-of-arrays, as the balls'.
#pragma once

#include <plab_host/bodies.hpp>

#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <vector>

namespace plab {

struct PebbleSpec {
    Vec offset = Vec::Zero();  // the pebble's centre in the principal frame, from the centre of mass, m
    double radius = 0;
};

// A body's true surface in its principal frame, about the centre of mass:
// 3D, triangles with outward normals by the right-hand rule; 2D, the
// boundary's edges in z = 0 (a face's third index unused), outside
// boundaries counter-clockwise, holes clockwise. For output and the coupling
// to a resolved fluid; contacts are the pebbles'.
struct BodySurface {
    std::vector<Vec> vertices;
    std::vector<std::array<std::int32_t, 3>> faces;
    bool edges = false;  // 2D: faces are edges
};

struct ClumpSpec {
    Vec position = Vec::Zero();  // the centre of mass, m
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // principal frame -> world
    double mass = 0;                         // kg
    Vec principal_moments = Vec::Zero();     // kg m^2 (2D: only z is used)
    Vec velocity = Vec::Zero(), angular_velocity = Vec::Zero();  // world frame
    std::vector<PebbleSpec> pebbles;
    int group = 0;
    // translations fixed per component; rotation fixed whole (every rotation
    // DOF of the dimension) or not at all: a fixed DOF keeps its velocity
    std::uint8_t fixity = 0;
    double local_damping = 0;
    std::int32_t surface = -1;  // its shape's in Clumps::surfaces; -1: none
};

struct Clumps {
    int dim = 3;  // the world's (add() takes it from the bodies)
    std::vector<BodyId> id;  // from the balls' id sequence: a clump and a ball never share one
    std::vector<Vec> position, velocity, angular_velocity, angular_momentum;  // world frame
    std::vector<Eigen::Quaterniond> orientation;  // principal frame -> world
    std::vector<Vec> principal_moments;
    std::vector<double> mass, local_damping;
    std::vector<std::uint8_t> fixity;
    std::vector<int> group;
    // the sums onto the clump after the force pass: its weight, the pebbles'
    // contact forces, and their moments about the centre of mass
    std::vector<Vec> force, moment;
    // clump c's pebbles: pebble_body[first_pebble[c] .. first_pebble[c + 1])
    std::vector<std::size_t> first_pebble{0};
    std::vector<std::int32_t> pebble_body;  // the pebble's index in Bodies
    std::vector<Vec> pebble_offset;         // its centre in the principal frame, m
    // the shapes' surfaces, one per clump template (a fill shares one), and
    // each clump's (-1: none); built by the scene, not checkpointed: a
    // restart builds them again from the scene
    std::vector<BodySurface> surfaces;
    std::vector<std::int32_t> surface;

    std::size_t size() const { return id.size(); }
    std::size_t pebble_count() const { return pebble_body.size(); }
    std::size_t pebbles_of(std::size_t c) const { return first_pebble[c + 1] - first_pebble[c]; }
    bool rotation_fixed(std::size_t c) const;
    double smallest_moment(std::size_t c) const;  // the smallest positive principal moment, kg m^2

    // Adds the clump and its pebbles (balls of `bodies`, marked dof_clumped,
    // placed by the clump); returns the clump's index.
    std::size_t add(const ClumpSpec& s, Bodies& bodies);
    // Each pebble's position, velocity and spin from its clump's state.
    void place_pebbles(Bodies& bodies) const;
    void place_pebbles(Bodies& bodies, std::size_t c) const;
    // ω from L at the current orientation (after L or the orientation changed).
    void update_angular_velocity(std::size_t c);
    // ω of clump c set, and the angular momentum L = R I Rᵀ ω it stands for.
    void set_spin(std::size_t c, const Vec& omega);
    // kinetic energy of clump c, translation and rotation (½ M v² + ½ L·ω)
    double kinetic_energy(std::size_t c) const;
};

} // namespace plab
