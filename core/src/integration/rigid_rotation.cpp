#include "integration/rigid_rotation.hpp"

namespace plab {

Vec angular_velocity(const RigidRotation& r, const Vec& principal_moments) {
    const Vec body = r.orientation.conjugate() * r.angular_momentum;
    Vec w = Vec::Zero();
    for (int k = 0; k < 3; ++k)
        if (principal_moments[k] > 0) w[k] = body[k] / principal_moments[k];
    return r.orientation * w;
}

double rotational_kinetic_energy(const RigidRotation& r, const Vec& principal_moments) {
    return 0.5 * r.angular_momentum.dot(angular_velocity(r, principal_moments));
}

namespace {

// The exact free rotation about principal axis k for time h: the body turns
// by θ = h π_k / I_k about its own axis k (π = Rᵀ L, the body-frame angular
// momentum, whose k-th component that turn keeps).
void turn_about_axis(RigidRotation& r, const Vec& moments, int k, double h) {
    if (!(moments[k] > 0)) return;
    const double pi_k = (r.orientation.conjugate() * r.angular_momentum)[k];
    const double theta = h * pi_k / moments[k];
    r.orientation = (r.orientation * Eigen::Quaterniond(Eigen::AngleAxisd(theta, Vec::Unit(k)))).normalized();
}

} // namespace

void rotate_freely(RigidRotation& r, const Vec& moments, double dt) {
    turn_about_axis(r, moments, 0, 0.5 * dt);
    turn_about_axis(r, moments, 1, 0.5 * dt);
    turn_about_axis(r, moments, 2, dt);
    turn_about_axis(r, moments, 1, 0.5 * dt);
    turn_about_axis(r, moments, 0, 0.5 * dt);
}

} // namespace plab
