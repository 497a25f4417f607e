// Weakly compressible SPH (issue: sph): kernels and their normalisation
// (thesis eqs. 11-12, quintic spline), the pair force's exact momentum
// conservation, the `mass` key of the scene generators, and the quick
// static tank (thesis 5.1) within its stated tolerance.
#include "simulation.hpp"

#include <plab/sph/kernels.hpp>
#include "../support/static_tank.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace plab;
using sph::Kernel;
using sph::KernelKind;

namespace {

constexpr KernelKind all_kernels[] = {KernelKind::wendland_c2, KernelKind::cubic_spline, KernelKind::quintic_spline};

// Σ W(|x_i|) a^dim over a square / cubic lattice of pitch a centred on the
// origin: the midpoint rule for the integral of W, exact to O((a/h)^2).
double lattice_sum(const Kernel& W, double a) {
    const int n = int(std::ceil(W.support() / a)) + 1;
    double sum = 0;
    for (int i = -n; i <= n; ++i)
        for (int j = -n; j <= n; ++j)
            for (int k = (W.dim == 3 ? -n : 0); k <= (W.dim == 3 ? n : 0); ++k)
                sum += W.value(a * std::sqrt(double(i * i + j * j + k * k)));
    return sum * std::pow(a, W.dim);
}

} // namespace

TEST_CASE("SPH kernels integrate to one in 2D and 3D", "[sph]") {
    for (KernelKind kind : all_kernels)
        for (int dim : {2, 3}) {
            const Kernel W{kind, dim, 0.013};  // any h: the constants carry 1/h^dim
            INFO("kernel " << int(kind) << " dim " << dim);
            // lattice pitch h/20 (2D), h/10 (3D): the rule's error is well below 1e-3
            CHECK(lattice_sum(W, W.h / (dim == 2 ? 20.0 : 10.0)) == Approx(1.0).margin(1e-3));
            CHECK(W.value(W.support()) == 0.0);
            CHECK(W.value(1.01 * W.support()) == 0.0);
        }
}

TEST_CASE("SPH kernel derivative matches finite differences and is antisymmetric in the pair", "[sph]") {
    for (KernelKind kind : all_kernels)
        for (int dim : {2, 3}) {
            const Kernel W{kind, dim, 0.01};
            INFO("kernel " << int(kind) << " dim " << dim);
            for (double q = 0.05; q < sph::support_factor(kind); q += 0.0731) {
                const double r = q * W.h, e = 1e-6 * W.h;
                const double fd = (W.value(r + e) - W.value(r - e)) / (2 * e);
                CHECK(W.derivative(r) == Approx(fd).epsilon(1e-6).margin(1e-9 * std::fabs(W.value(0)) / W.h));
                CHECK(W.derivative(r) <= 0.0);  // monotone: the pair gradient points from j to i
            }
            // ∇_i W_ij = dW/dr (x_i - x_j)/r = -∇_j W_ji: the same scalar, opposite unit vectors
            CHECK(W.derivative(0.0) == Approx(0.0).margin(1e-12 * W.value(0) / W.h));
        }
}

namespace {

// A free 2D blob of SPH fluid (no walls, no gravity) with random velocities.
json free_blob(int dim) {
    const double dp = 0.01, h = 1.2 * dp;
    const json box = dim == 2 ? json{{"min", {0, 0}}, {"max", {0.08, 0.08}}}
                              : json{{"min", {0, 0, 0}}, {"max", {0.05, 0.05, 0.05}}};
    const double mass = dim == 2 ? 1000 * dp * dp : 1000 * dp * dp * dp;
    return {{"dimension", dim},
            {"plugins", {"sph"}},
            {"bodies", {{{"type", "lattice"}, {"group", "fluid"}, {"packing", dim == 2 ? "square" : "cubic"},
                         {"box", box}, {"radius", dp / 2}, {"spacing", dp}, {"mass", mass}, {"fix", {"rotation"}},
                         {"jitter", {{"position", 0.1 * dp}, {"velocity", 0.3}, {"seed", 3}}}}}},
            {"contact_models", {{{"groups", {"fluid", "fluid"}}, {"model", "sph"},
                                 {"properties", {{"smoothing_length", h}, {"kernel", "wendland_c2"}, {"viscosity", "laminar"}, {"speed_of_sound", 10}, {"mu", 1e-3}}}}}},
            {"passes", {{{"name", "sph_density_integration"}},
                        // a free blob expands into vacuum: its density falls far below rho0 by design
                        {{"name", "sph_eos"}, {"properties", {{"speed_of_sound", 10}, {"density_band", 1.0}}}}}}};
}

} // namespace

TEST_CASE("SPH pair forces conserve linear momentum to round-off in a free blob", "[sph]") {
    for (int dim : {2, 3}) {
        INFO("dim " << dim);
        Simulation sim(free_blob(dim));
        sim.set_quiet(true);
        World& w = sim.world();
        auto momentum = [&]() {
            Vec p = Vec::Zero();
            for (std::size_t i = 0; i < w.bodies.size(); ++i) p += w.bodies.mass[i] * w.bodies.velocity[i];
            return p;
        };
        double scale = 0;  // Σ m|v|: the size of the terms summed
        for (std::size_t i = 0; i < w.bodies.size(); ++i) scale += w.bodies.mass[i] * w.bodies.velocity[i].norm();
        const Vec p0 = momentum();
        double largest_force = 0;
        for (int k = 0; k < 300; ++k) {
            w.step();
            for (std::size_t i = 0; i < w.bodies.size(); ++i) largest_force = std::max(largest_force, w.bodies.force[i].norm());
        }
        CHECK(largest_force > 0);  // the fluid does push
        CHECK((momentum() - p0).norm() <= 1e-12 * scale);
        // pressures developed: the density changed through the continuity equation
        const auto& rho = w.fields.column(w.fields.index("sph_density"));
        double spread = 0;
        for (double r : rho) spread = std::max(spread, std::fabs(r - 1000));
        CHECK(spread > 0.1);
    }
}

TEST_CASE("the `mass` key sets each ball's mass, inertia from that mass", "[sph][scene]") {
    const double r = 0.0025, m = 1000 * 0.005 * 0.005;  // an SPH particle: rho0 dp^2, dp = 2r
    json scene = {{"dimension", 2},
                  {"bodies", {{{"type", "ball"}, {"position", {0, 0}}, {"radius", r}, {"mass", m}},
                              {{"type", "lattice"}, {"box", {{"min", {1, 0}}, {"max", {1.02, 0.02}}}}, {"radius", r},
                               {"mass", m}, {"packing", "square"}}}}};
    Simulation sim(scene);
    const World& w = sim.world();
    REQUIRE(w.bodies.size() == 1 + 16);
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        CHECK(w.bodies.mass[i] == Approx(m).epsilon(1e-14));
        CHECK(w.bodies.inertia[i] == Approx(0.5 * m * r * r).epsilon(1e-14));
    }
    scene["bodies"][0]["density"] = 1000;
    CHECK_THROWS_WITH(Simulation(scene), Catch::Matchers::Contains("either \"density\" or \"mass\""));
}

TEST_CASE("quick static tank keeps the hydrostatic pressure and its particles in place", "[sph]") {
    using namespace testing_support;  // the quick variant of `plab validate static_tank --quick`
    const TankFigures t = run_tank(quick_tank_scene());
    const double dp = 0.01;
    CHECK(t.fluid == 225);
    CHECK(t.pressure_l2 <= 0.04);            // time-averaged pressure vs rho0 g (H - y)
    CHECK(t.max_displacement <= 0.5 * dp);   // the column stays put
    CHECK(t.min_clearance > 0.25 * dp);      // no particle reaches, let alone crosses, a wall
}
