// The rotation of a rigid body of any shape (issue 27): its orientation, a
// unit quaternion from the body's principal frame to the world, and its
// angular momentum in the world frame. The leapfrog kicks the angular
// momentum with the torque, L += (dt/2) M, as it kicks a ball's velocity;
// between the kicks the body turns freely, by the splitting of Dullweber,
// Leimkuhler & McLachlan (1997): exact rotations about the principal axes
// 1, 2, 3, 2, 1 over dt/2, dt/2, dt, dt/2, dt/2. Each keeps L in the world
// frame exactly and the kinetic energy to second order in dt, and together
// they integrate Euler's equations I ω̇ = M − ω × Iω (Joubert eq. 35), the
// gyroscopic term included, without ever forming it.
#pragma once

#include <plab_host/types.hpp>

#include <Eigen/Geometry>

namespace plab {

struct RigidRotation {
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // principal frame -> world
    Vec angular_momentum = Vec::Zero();                               // world frame, kg m^2/s
};

// ω = R I⁻¹ Rᵀ L in the world frame, I the principal moments (kg m^2).
Vec angular_velocity(const RigidRotation& r, const Vec& principal_moments);
// ½ L·ω.
double rotational_kinetic_energy(const RigidRotation& r, const Vec& principal_moments);
// The free rotation over dt (no torque); a zero moment leaves its axis unturned.
void rotate_freely(RigidRotation& r, const Vec& principal_moments, double dt);

} // namespace plab
