// XSPH (thesis eq. 18), the sph_xsph pass and the host's drift velocity
// correction (abi.h, PLAB_PHASE_PRE_DRIFT): the correction carries no net
// momentum, the velocities (momentum) stay the leapfrog's, and the
// smoothed drift keeps a noisy fluid more ordered than the plain drift.
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace plab;

namespace {

constexpr double dp = 0.01;

// A 10 x 10 block of fluid, no walls, no gravity, on a lattice with random
// velocities of up to 0.3 m/s per component (thermal-like noise, c0 10 m/s).
json noisy_block(double epsilon) {
    const json water = {{"groups", {"fluid"}}, {"smoothing_length", 1.3 * dp}, {"kernel", "cubic"},
                        {"rest_density", 1000}, {"speed_of_sound", 10}, {"gamma", 7}};
    json passes = {{{"name", "sph_density_integration"}},
                   // a free block expands into vacuum: its density falls below rho0 by design
                   {{"name", "sph_eos"}, {"material", "water"}, {"properties", {{"density_band", 1.0}}}}};
    if (epsilon > 0)
        passes.push_back({{"name", "sph_xsph"}, {"material", "water"}, {"properties", {{"epsilon", epsilon}}}});
    return {{"dimension", 2},
            {"plugins", {"sph"}},
            {"bodies", {{{"type", "lattice"}, {"group", "fluid"}, {"packing", "square"},
                         {"box", {{"min", {0, 0}}, {"max", {10 * dp, 10 * dp}}}}, {"radius", dp / 2}, {"spacing", dp},
                         {"mass", 1000 * dp * dp}, {"fix", {"rotation"}},
                         {"jitter", {{"velocity", 0.3}, {"seed", 5}}}}}},
            {"materials", {{"water", water}}},
            {"contact_models", {{{"groups", {"fluid", "fluid"}}, {"model", "sph"}, {"properties", {{"alpha", 0.1}}}}}},
            {"passes", passes}};
}

// std/mean of each ball's distance to its nearest neighbour (0 on a lattice)
double disorder(const World& w) {
    std::vector<double> nearest;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        double best = 1e300;
        for (std::size_t j = 0; j < w.bodies.size(); ++j)
            if (j != i) best = std::min(best, (w.bodies.position[j] - w.bodies.position[i]).squaredNorm());
        nearest.push_back(std::sqrt(best));
    }
    double mean = 0, var = 0;
    for (double d : nearest) mean += d / double(nearest.size());
    for (double d : nearest) var += (d - mean) * (d - mean) / double(nearest.size());
    return std::sqrt(var) / mean;
}

Vec momentum(const World& w) {
    Vec p = Vec::Zero();
    for (std::size_t i = 0; i < w.bodies.size(); ++i) p += w.bodies.mass[i] * w.bodies.velocity[i];
    return p;
}

} // namespace

TEST_CASE("XSPH drift correction carries no net momentum and leaves the momentum to the pair forces", "[sph]") {
    Simulation sim(noisy_block(0.5));
    sim.set_quiet(true);
    World& w = sim.world();
    const int cx = w.fields.index("drift_velocity_correction_x"), cy = w.fields.index("drift_velocity_correction_y");
    REQUIRE(cx >= 0);
    REQUIRE(cy >= 0);
    double scale = 0;  // Σ m |v|: the size of the terms summed
    for (std::size_t i = 0; i < w.bodies.size(); ++i) scale += w.bodies.mass[i] * w.bodies.velocity[i].norm();
    const Vec p0 = momentum(w);
    Vec centre0 = Vec::Zero();
    double mass = 0;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) { centre0 += w.bodies.mass[i] * w.bodies.position[i]; mass += w.bodies.mass[i]; }
    double largest_correction = 0;
    for (int k = 0; k < 100; ++k) {
        w.step();
        double sx = 0, sy = 0, size = 0;
        for (std::size_t i = 0; i < w.bodies.size(); ++i) {
            const double m = w.bodies.mass[i], dx = w.fields.column(cx)[i], dy = w.fields.column(cy)[i];
            sx += m * dx;
            sy += m * dy;
            size += m * std::hypot(dx, dy);
            largest_correction = std::max(largest_correction, std::hypot(dx, dy));
        }
        CHECK(std::hypot(sx, sy) <= 1e-12 * size);  // Σ m_i δv_i = 0: each pair adds ± the same term
    }
    CHECK(largest_correction > 0.01);  // the correction is there (velocities differ by up to 0.6 m/s)
    CHECK((momentum(w) - p0).norm() <= 1e-12 * scale);
    // so the centre of mass moves with the (constant) momentum, exactly as without XSPH
    Vec centre = Vec::Zero();
    for (std::size_t i = 0; i < w.bodies.size(); ++i) centre += w.bodies.mass[i] * w.bodies.position[i];
    CHECK((centre / mass - centre0 / mass - p0 / mass * w.time).norm() <= 1e-12);
}

TEST_CASE("XSPH keeps a fluid with velocity noise more ordered than the plain drift", "[sph]") {
    double spread[2];
    for (int with : {0, 1}) {
        Simulation sim(noisy_block(with ? 0.5 : 0.0));
        sim.set_quiet(true);
        World& w = sim.world();
        while (w.time < 0.02) w.step();  // ~ 20 dp/c0: the noise has moved particles by a fraction of dp
        spread[with] = disorder(w);
    }
    INFO("nearest-neighbour spread without XSPH " << spread[0] << ", with " << spread[1]);
    CHECK(spread[0] > 0.02);             // the noise does disorder the lattice
    CHECK(spread[1] < 0.8 * spread[0]);  // XSPH moves neighbours together
}
