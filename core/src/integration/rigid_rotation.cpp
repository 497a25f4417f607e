#include "integration/rigid_rotation.hpp"

#include <cmath>

namespace plab {

Vec angular_velocity(const RigidRotation& r, const Vec& principal_moments) {
    const Eigen::Matrix3d R = r.orientation.toRotationMatrix();  // (one matrix for both turns)
    const Vec body = R.transpose() * r.angular_momentum;
    Vec w = Vec::Zero();
    for (int k = 0; k < 3; ++k)
        if (principal_moments[k] > 0) w[k] = body[k] / principal_moments[k];
    return R * w;
}

double rotational_kinetic_energy(const RigidRotation& r, const Vec& principal_moments) {
    return 0.5 * r.angular_momentum.dot(angular_velocity(r, principal_moments));
}

namespace {

// The exact free rotation about principal axis k for time h: the body turns
// by θ = h π_k / I_k about its own axis k (π = Rᵀ L, the body-frame angular
// momentum, whose k-th component the turn keeps): q ← q (cos θ/2, sin θ/2 e_k),
// and π, seen from the turned body, turns by −θ about e_k. One sincos per turn.
void turn_about_axis(Eigen::Quaterniond& q, Vec& pi, const Vec& moments, int k, double h) {
    if (!(moments[k] > 0)) return;
    const double half = 0.5 * h * pi[k] / moments[k];
    const double s = std::sin(half), c = std::cos(half);
    const double w = q.w(), x = q.x(), y = q.y(), z = q.z();
    const int i = (k + 1) % 3, j = (k + 2) % 3;  // the plane the turn moves
    // q (c, s e_k), written out: the vector part's components k, i, j
    Eigen::Vector3d v(x, y, z), out;
    out[k] = c * v[k] + s * w;
    out[i] = c * v[i] + s * v[j];
    out[j] = c * v[j] - s * v[i];
    q = Eigen::Quaterniond(c * w - s * v[k], out.x(), out.y(), out.z());
    const double cos_t = c * c - s * s, sin_t = 2 * s * c;  // θ from θ/2
    const double pi_i = pi[i], pi_j = pi[j];
    pi[i] = cos_t * pi_i + sin_t * pi_j;
    pi[j] = -sin_t * pi_i + cos_t * pi_j;
}

} // namespace

void rotate_freely(RigidRotation& r, const Vec& moments, double dt) {
    Eigen::Quaterniond q = r.orientation;
    Vec pi = q.conjugate() * r.angular_momentum;
    turn_about_axis(q, pi, moments, 0, 0.5 * dt);
    turn_about_axis(q, pi, moments, 1, 0.5 * dt);
    turn_about_axis(q, pi, moments, 2, dt);
    turn_about_axis(q, pi, moments, 1, 0.5 * dt);
    turn_about_axis(q, pi, moments, 0, 0.5 * dt);
    r.orientation = q.normalized();
}

} // namespace plab
