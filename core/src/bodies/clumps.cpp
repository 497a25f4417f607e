// Clumps (plab_host/clumps.hpp): making them and placing their pebbles.
#include <plab_host/clumps.hpp>

#include <plab_host/errors.hpp>

#include "integration/rigid_rotation.hpp"

#include <algorithm>
#include <cmath>

namespace plab {

double Clumps::smallest_moment(std::size_t c) const {
    double smallest = kInf;
    for (int k = 0; k < 3; ++k)
        if (principal_moments[c][k] > 0) smallest = std::min(smallest, principal_moments[c][k]);
    return smallest;
}

bool Clumps::rotation_fixed(std::size_t c) const {
    return (fixity[c] & rotation_dofs(dim)) != 0;
}

std::size_t Clumps::add(const ClumpSpec& s, Bodies& bodies) {
    if (!(s.mass > 0)) throw InputError("", "a clump needs a positive mass");
    if (s.pebbles.empty()) throw InputError("", "a clump needs at least one pebble");
    bodies.clump.resize(bodies.size(), -1);
    const std::size_t c = size();
    dim = bodies.dim;
    const Vec moments = bodies.dim == 2 ? Vec(0, 0, s.principal_moments.z()) : s.principal_moments;
    if (!(moments.maxCoeff() > 0)) throw InputError("", "a clump needs a positive moment of inertia");
    id.push_back(bodies.next_id++);
    position.push_back(s.position);
    velocity.push_back(s.velocity);
    angular_velocity.push_back(dim == 2 ? Vec(0, 0, s.angular_velocity.z()) : s.angular_velocity);
    orientation.push_back(s.orientation.normalized());
    principal_moments.push_back(moments);
    // a pebble's inertia is the clump's smallest moment: what the stable
    // step and a contact model's rolling terms see of the clump
    const double smallest = smallest_moment(c);
    mass.push_back(s.mass);
    local_damping.push_back(s.local_damping);
    fixity.push_back(s.fixity);
    group.push_back(s.group);
    if (s.surface >= std::int32_t(surfaces.size())) throw InputError("", "a clump names a surface that was never added");
    surface.push_back(s.surface);
    force.push_back(Vec::Zero());
    moment.push_back(Vec::Zero());
    angular_momentum.push_back(Vec::Zero());
    set_spin(c, angular_velocity[c]);
    update_angular_velocity(c);
    for (const PebbleSpec& p : s.pebbles) {
        BallSpec b;
        b.radius = p.radius;
        b.density = 1;  // replaced below: the pebble carries the clump's mass
        b.group = s.group;
        b.fixity = dof_all | dof_clumped;
        bodies.add(b);
        const std::size_t i = bodies.size() - 1;
        bodies.clump.resize(bodies.size(), -1);  // (empty before the world's first pebble)
        bodies.mass[i] = s.mass;
        bodies.inertia[i] = smallest;
        bodies.clump[i] = std::int32_t(c);
        pebble_body.push_back(std::int32_t(i));
        pebble_offset.push_back(p.offset);
    }
    first_pebble.push_back(pebble_body.size());
    place_pebbles(bodies, c);
    return c;
}

void Clumps::set_spin(std::size_t c, const Vec& omega) {
    const Eigen::Matrix3d R = orientation[c].toRotationMatrix();
    angular_velocity[c] = omega;
    angular_momentum[c] = R * principal_moments[c].asDiagonal() * (R.transpose() * omega);
}

void Clumps::update_angular_velocity(std::size_t c) {
    if (!rotation_fixed(c))
        angular_velocity[c] = plab::angular_velocity({orientation[c], angular_momentum[c]}, principal_moments[c]);
}

void Clumps::place_pebbles(Bodies& bodies, std::size_t c) const {
    const Eigen::Matrix3d R = orientation[c].toRotationMatrix();
    for (std::size_t p = first_pebble[c]; p < first_pebble[c + 1]; ++p) {
        const std::size_t i = std::size_t(pebble_body[p]);
        const Vec arm = R * pebble_offset[p];
        bodies.position[i] = position[c] + arm;
        bodies.velocity[i] = velocity[c] + angular_velocity[c].cross(arm);
        bodies.angular_velocity[i] = angular_velocity[c];
    }
}

void Clumps::place_pebbles(Bodies& bodies) const {
    for (std::size_t c = 0; c < size(); ++c) place_pebbles(bodies, c);
}

double Clumps::kinetic_energy(std::size_t c) const {
    return 0.5 * mass[c] * velocity[c].squaredNorm() + 0.5 * angular_momentum[c].dot(angular_velocity[c]);
}

} // namespace plab
