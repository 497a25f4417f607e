// The torque-free rigid body of three different principal moments (Landau &
// Lifshitz, Mechanics §37), for the rotation tests.
#pragma once

#include <plab_host/types.hpp>

#include <cmath>
#include <utility>

// The period of ω for I1 < I2 < I3: T = 4 K(k) / p, with the roles of axes 1
// and 3 exchanged when L^2 < 2 E I2.
inline double flip_period(plab::Vec I, double energy, double l2) {
    if (l2 < 2 * energy * I.y()) std::swap(I.x(), I.z());
    const double p = std::sqrt((I.z() - I.y()) * (l2 - 2 * energy * I.x()) / (I.x() * I.y() * I.z()));
    const double k2 = (I.y() - I.x()) * (2 * energy * I.z() - l2) / ((I.z() - I.y()) * (l2 - 2 * energy * I.x()));
    return 4 * std::comp_ellint_1(std::sqrt(k2)) / p;
}
