// The free rotation of a rigid body (integration/rigid_rotation.hpp)
// against Euler's equations: angular momentum and energy kept, the flip of
// an asymmetric body spun near its intermediate axis at the period of the
// elliptic-function solution (Landau & Lifshitz, Mechanics §37), a spin
// about the major axis stable, and a torque's kick.
#include "integration/rigid_rotation.hpp"

#include "euler_top.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

using namespace plab;


TEST_CASE("free rotation keeps angular momentum and energy, and flips at the elliptic period", "[rigid][rotation]") {
    const Vec I(1.0, 2.0, 3.0);
    RigidRotation r;
    r.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vec(1, 1, 0).normalized()));
    const Vec w_body(0.05, 1.0, 0.05);  // near the intermediate axis
    r.angular_momentum = r.orientation * I.cwiseProduct(w_body);
    const Vec L0 = r.angular_momentum;
    const double E0 = rotational_kinetic_energy(r, I);
    const double T = flip_period(I, E0, L0.squaredNorm());
    const double dt = T / 5000;
    std::vector<double> up;  // times ω2 (body) rises through zero
    double last = w_body.y(), worst_energy = 0;
    for (int step = 1; step <= 100000; ++step) {
        rotate_freely(r, I, dt);
        worst_energy = std::max(worst_energy, std::fabs(rotational_kinetic_energy(r, I) / E0 - 1));
        const double w2 = (r.orientation.conjugate() * angular_velocity(r, I)).y();
        if (last < 0 && w2 >= 0) up.push_back(dt * (step - 1 + last / (last - w2)));
        last = w2;
    }
    CHECK((r.angular_momentum - L0).norm() < 1e-12 * L0.norm());  // exactly, as each turn keeps it
    CHECK(worst_energy < 1e-6);
    REQUIRE(up.size() >= 3);
    const double measured = (up.back() - up.front()) / double(up.size() - 1);
    CHECK(measured == Approx(T).epsilon(0.01));
}

TEST_CASE("a spin about the major axis stays about it, and a torque kick adds M dt to the angular momentum", "[rigid][rotation]") {
    const Vec I(1.0, 2.0, 3.0);
    RigidRotation r;
    r.angular_momentum = r.orientation * I.cwiseProduct(Vec(0.01, 0.01, 1.0));
    double widest = 0;
    for (int step = 0; step < 20000; ++step) {
        rotate_freely(r, I, 1e-3);
        widest = std::max(widest, std::acos(std::min(1.0, (r.orientation * Vec::UnitZ()).dot(r.angular_momentum.normalized()))));
    }
    CHECK(widest < 0.05);  // the major axis wobbles about L by about its initial 1 % tilt, no more
    RigidRotation still;
    const Vec torque(0, 0, 0.5);
    still.angular_momentum += 0.5 * 0.2 * torque;  // the two half kicks of one step of 0.2 s
    rotate_freely(still, I, 0.2);
    still.angular_momentum += 0.5 * 0.2 * torque;
    CHECK(angular_velocity(still, I).z() == Approx(0.5 * 0.2 / 3.0));
    CHECK(still.orientation.angularDistance(Eigen::Quaterniond(Eigen::AngleAxisd(0.5 * 0.2 * 0.2 / 3.0 / 2, Vec::UnitZ()))) < 1e-12);
}
