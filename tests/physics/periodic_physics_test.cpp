// SPH and bonds across a periodic boundary (domain.periodic, issue 36): the
// host's minimum-image geometry reaches the SPH sums and the parallel bonds
// without a change to either model.
#include "simulation.hpp"

#include <plab/abi.h>
#include <plab/sph/kernels.hpp>
#include <plab_host/contacts.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace plab;

namespace {

constexpr double dp = 0.01, rho0 = 1000.0;

// A 20 x 20 lattice of fluid at rest filling a cell periodic in x and y:
// no free surface anywhere. Cubic spline, h = 1.3 dp; plain summation.
json periodic_fluid() {
    const json water = {{"groups", {"fluid"}}, {"smoothing_length", 1.3 * dp}, {"kernel", "cubic"},
                        {"rest_density", rho0}, {"speed_of_sound", 10}, {"gamma", 7}};
    return {{"dimension", 2},
            {"plugins", {"sph"}},
            // (at rest the energy turned over is zero, and round-off would read as energy from nowhere)
            {"stability", {{"enabled", false}}},
            {"domain", {{"min", {0, 0}}, {"max", {20 * dp, 20 * dp}}, {"periodic", {"x", "y"}}}},
            {"bodies", {{{"type", "lattice"}, {"group", "fluid"}, {"packing", "square"},
                         {"box", {{"min", {0, 0}}, {"max", {20 * dp, 20 * dp}}}}, {"radius", dp / 2}, {"spacing", dp},
                         {"mass", rho0 * dp * dp}, {"fix", {"rotation"}}}}},
            {"materials", {{"water", water}}},
            {"contact_models", {{{"groups", {"fluid", "fluid"}}, {"model", "sph"}, {"properties", {{"alpha", 0.1}}}}}},
            {"passes", {{{"name", "sph_density_summation"}, {"material", "water"}},
                        {{"name", "sph_eos"}, {"material", "water"}, {"properties", {{"density_band", 1.0}, {"initial_density", false}}}},
                        {{"name", "sph_xsph"}, {"material", "water"}}}}};
}

} // namespace

TEST_CASE("a periodic block of SPH fluid at rest has the interior density everywhere and stays at rest",
          "[periodic][sph]") {
    Simulation sim(periodic_fluid());
    sim.set_quiet(true);
    World& w = sim.world();
    w.prepare();
    const auto& rho = w.fields.column(w.fields.index("sph_density"));
    double lattice = 0;  // eq. 8 over an infinite square lattice: what every particle has without a free surface
    const sph::Kernel W{sph::KernelKind::cubic_spline, 2, 1.3 * dp};
    for (int i = -4; i <= 4; ++i)
        for (int j = -4; j <= 4; ++j) lattice += W.value(dp * std::sqrt(double(i * i + j * j)));
    lattice *= rho0 * dp * dp;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) REQUIRE(rho[i] == Approx(lattice).epsilon(1e-12));
    sim.cycle(100);
    double speed = 0;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        CHECK(rho[i] == Approx(lattice).epsilon(1e-9));
        speed = std::max(speed, w.bodies.velocity[i].norm());
    }
    CHECK(speed < 1e-9);  // the pressure forces cancel at every particle, edges included
}

TEST_CASE("a ring of bonded balls closed across a periodic boundary keeps its bonds and its length while it moves",
          "[periodic][bonds]") {
    constexpr double r = 0.001, L = 0.02;
    json balls = json::array();
    for (int k = 0; k < 10; ++k)  // touching, the last touching the first across x = L
        balls.push_back({{"type", "ball"}, {"group", "ring"}, {"position", {r + 2 * r * k, 0.01}},
                         {"velocity", {2.0, k == 3 ? 0.05 : 0.0}}, {"radius", r}, {"density", 2500}});
    const json scene = {{"dimension", 2},
                        {"plugins", {"linear_pbond"}},
                        {"domain", {{"min", {0, 0}}, {"max", {L, L}}, {"periodic", {"x"}}}},
                        {"bodies", balls},
                        {"contact_models", {{{"groups", {"ring", "ring"}}, {"model", "linear_pbond"},
                                             {"calibrate", {{"method", "hexagonal_2d"}, {"E", 1e9}, {"nu", 0.2},
                                                            {"sigma_ult", 1e9}, {"radius", r}, {"density", "ball"}}}}}}};
    Simulation sim(scene);
    sim.set_quiet(true);
    World& w = sim.world();
    REQUIRE(w.bond(0, 0, 1e-9 * r) == 10);  // nine along the chain and the one across the boundary
    sim.cycle(3000);
    CHECK(intact_bonds(w) == 10);
    CHECK(w.bond_breaks.empty());
    CHECK(rebuilds(w) > 2);  // the ring crossed the boundary, wrapped at rebuilds
    double length = 0;  // round the ring, each link at its minimum image
    for (int k = 0; k < 10; ++k) {
        const Vec &a = w.bodies.position[k], &b = w.bodies.position[(k + 1) % 10];
        length += (w.bodies.cell.image(a, b) - a).norm();
    }
    CHECK(length == Approx(L).epsilon(1e-3));
}

TEST_CASE("XSPH smooths a shear wave across a periodic boundary as it does inside the cell", "[periodic][sph]") {
    // v_x = U sin(2 pi y / L): the row at y and the row at y + L/2 move
    // opposite ways, and so must their XSPH corrections, the rows that
    // touch y = 0 (whose neighbours lie across the boundary) included
    Simulation sim(periodic_fluid());
    sim.set_quiet(true);
    World& w = sim.world();
    const double L = 20 * dp, U = 0.01;
    for (std::size_t i = 0; i < w.bodies.size(); ++i)
        w.bodies.velocity[i] = Vec(U * std::sin(2 * M_PI * w.bodies.position[i].y() / L), 0, 0);
    sim.cycle(1);
    const auto& dvx = w.fields.column(w.fields.index(PLAB_DRIFT_CORRECTION_X));
    double row[20][20] = {};  // [row][column]
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        const Vec x = w.bodies.cell.wrap(w.bodies.position[i]);
        row[long(x.y() / dp) % 20][long(x.x() / dp) % 20] = dvx[i];
    }
    double largest = 0;
    for (int r = 0; r < 20; ++r)
        for (int c = 0; c < 20; ++c) largest = std::max(largest, std::fabs(row[r][c]));
    REQUIRE(largest > 0);
    for (int r : {0, 1, 2, 17, 18, 19})  // within the kernel's support of y = 0
        for (int c = 0; c < 20; ++c) CHECK(std::fabs(row[r][c] + row[(r + 10) % 20][c]) <= 1e-9 * largest);
}

namespace {

// A solid disc moving through a periodic block of SPH fluid at rest (the
// unresolved coupling, coupling_fluid_particle), at (x, 0.0093).
json disc_in_periodic_fluid(double x) {
    const double h = 1.5 * dp;
    const json sph = {{"smoothing_length", h}, {"kernel", "wendland_c2"}, {"rest_density", rho0}, {"speed_of_sound", 5.0},
                      {"viscosity", "laminar"}, {"mu", 0.01}};
    const json kernel = {{"smoothing_length", h}, {"kernel", "wendland_c2"}};
    json drag = kernel;
    drag.update({{"fluid_group", "fluid"}, {"solid_group", "solid"}, {"rest_density", rho0}, {"mu", 0.01}});
    return {{"dimension", 2},
            {"plugins", {"sph", "coupling_fluid_particle"}},
            {"domain", {{"min", {0, 0}}, {"max", {20 * dp, 20 * dp}}, {"periodic", {"x", "y"}}}},
            {"bodies", {{{"type", "lattice"}, {"group", "fluid"}, {"packing", "square"},
                         {"box", {{"min", {0, 0}}, {"max", {20 * dp, 20 * dp}}}}, {"radius", dp / 2}, {"spacing", dp},
                         {"mass", rho0 * dp * dp}, {"fix", {"rotation"}}},
                        {{"type", "ball"}, {"group", "solid"}, {"position", {x, 0.0093}}, {"radius", 0.4 * dp},
                         {"density", 2500}, {"velocity", {0.3, -0.1}}}}},
            {"contact_models", {{{"groups", {"fluid", "fluid"}}, {"model", "sph"}, {"properties", sph}},
                                {{"groups", {"fluid", "solid"}}, {"model", "fluid_particle"}, {"properties", kernel}}}},
            {"passes", {{{"name", "sph_density_integration"}},
                        {{"name", "sph_eos"}, {"properties", {{"rest_density", rho0}, {"speed_of_sound", 5.0}}}},
                        {{"name", "fluid_particle_drag"}, {"properties", drag}}}}};
}

} // namespace

TEST_CASE("the fluid-particle coupling sees the fluid across a periodic boundary as the fluid beside it",
          "[periodic][coupling]") {
    // The lattice is the same seen from x and from x + 10 dp: a disc on the
    // boundary (its kernel support across it) and one in the middle feel
    // the same fluid, voidage and drag.
    struct Seen { double force_x, force_y, solid_fraction_sum; };
    auto seen = [](double x) {
        Simulation sim(disc_in_periodic_fluid(x));
        sim.set_quiet(true);
        World& w = sim.world();
        w.step();
        const std::size_t disc = w.bodies.size() - 1;
        const auto& voidage = w.fields.column(w.fields.index("voidage"));
        double sum = 0;
        for (std::size_t i = 0; i < disc; ++i) sum += 1 - voidage[i];
        return Seen{w.fields.column(w.fields.index("fp_force_x"))[disc],
                    w.fields.column(w.fields.index("fp_force_y"))[disc], sum};
    };
    const Seen edge = seen(0.2 * dp), middle = seen(10.2 * dp);
    REQUIRE(middle.solid_fraction_sum > 0);
    REQUIRE(std::abs(middle.force_x) > 0);
    CHECK(edge.solid_fraction_sum == Approx(middle.solid_fraction_sum).epsilon(1e-9));
    CHECK(edge.force_x == Approx(middle.force_x).epsilon(1e-9));
    CHECK(edge.force_y == Approx(middle.force_y).epsilon(1e-9));
}
