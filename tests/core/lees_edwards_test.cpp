// Lees–Edwards simple shear of a periodic cell (domain.shear, issue 36): a
// pair across the sheared y boundary is the pair of the minimum images,
// shifted along x by the cell's offset and moving at the image's velocity;
// a ball that crosses y comes back shifted along x, with the velocity of its
// image; the peculiar momentum is conserved; the same bits on 1 and 2
// threads and after a checkpoint–restart.
#include "simulation.hpp"
#include "../support/periodic_cell.hpp"
#include "../support/same_bits.hpp"

#include <plab_host/contacts.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace plab;
using namespace plab::testing_support;

namespace {

// The cell [0, L]^dim sheared at `rate`, the balls as given (no affine start).
json sheared_scene(int dim, double L, double rate, json balls) {
    return periodic_cell_scene(dim, L, std::move(balls), rate);
}

// A sheared periodic gas of 3D balls with seeded random velocities, no net
// momentum along y (so that the peculiar momentum is conserved).
std::unique_ptr<Simulation> sheared_gas() {
    json fill = {{"type", "random_fill"}, {"group", "g"}, {"box", {{"min", {0, 0, 0}}, {"max", {0.03, 0.03, 0.03}}}},
                 {"radius", {0.0015, 0.0025}}, {"density", 2500}, {"count", 150}, {"seed", 7}};
    auto sim = std::make_unique<Simulation>(sheared_scene(3, 0.03, 60.0, json::array({fill})));
    sim->set_quiet(true);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Bodies& b = sim->world().bodies;
    double mass = 0, py = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
        b.velocity[i] = Vec(u(rng), u(rng), u(rng));
        mass += b.mass[i];
        py += b.mass[i] * b.velocity[i].y();
    }
    for (Vec& v : b.velocity) v.y() -= py / mass;
    return sim;
}

// The momentum of the balls less that of the shear's flow at their centres.
Vec peculiar_momentum(const World& w) {
    Vec p = Vec::Zero();
    for (std::size_t i = 0; i < w.bodies.size(); ++i)
        p += w.bodies.mass[i] * (w.bodies.velocity[i] - Vec::UnitX() * w.bodies.cell.affine_velocity(w.bodies.position[i]));
    return p;
}

} // namespace

TEST_CASE("two balls touching across a sheared boundary feel the forces they feel touching in the middle of the cell",
          "[periodic][shear]") {
    // shear 20 /s in a cell 0.1 m high: the image of the cell above moves at
    // 2 m/s. Ball 2 of the pair across y = L sits at the bottom of the cell,
    // its image (x + offset, y + L) touching ball 1 at the top; its velocity
    // is its image's less 2 m/s. The pair rises at 2 m/s, so ball 1 crosses
    // y = L (wrapped at a rebuild). The pair in the middle is the same pair,
    // with ball 2 at its image's position and velocity.
    const double rate = 20, L = 0.1, lift = 2.0;
    const double dx = 0.0027, dy = 0.0027;  // overlap 0.18 mm
    auto run = [&](double y1, double image_shift) {
        const double y2 = y1 + dy - image_shift;
        const double vx2 = 1.01 - (image_shift > 0 ? rate * L : 0.0);
        auto sim = std::make_unique<Simulation>(sheared_scene(2, L, rate, json::array({cell_ball(0.05, y1, 1.0, lift, 10.0), cell_ball(0.05 + dx, y2, vx2, lift - 0.01, -5.0)})));
        sim->set_quiet(true);
        sim->cycle(100);  // 1 ms: 2 mm up, the image slid 2 mm, the overlap still closed
        return sim;
    };
    const auto across = run(0.0985, L), middle = run(0.0485, 0.0);
    const World &a = across->world(), &m = middle->world();
    REQUIRE(active_contacts(a) == 1);
    REQUIRE(active_contacts(m) == 1);
    CHECK(a.bodies.position[0].y() < 0.05);  // ball 1 crossed y = L and came back at the bottom of the cell
    CHECK(a.bodies.cell.shear_offset == Approx(rate * L * 1e-3).epsilon(1e-9));
    const Vec fa = a.bodies.force[0], fm = m.bodies.force[0];
    const double scale = fm.norm();
    REQUIRE(scale > 0);
    CHECK((fa - fm).norm() <= 1e-8 * scale);
    CHECK((a.bodies.force[0] + a.bodies.force[1]).norm() <= 1e-12 * scale);  // opposite forces
    CHECK(std::fabs(a.bodies.moment[0].z() - m.bodies.moment[0].z()) <= 1e-8 * std::fabs(m.bodies.moment[0].z()));
    CHECK(std::fabs(a.bodies.moment[1].z() - m.bodies.moment[1].z()) <= 1e-8 * std::fabs(m.bodies.moment[1].z()));
    // the same branch vector, and the same velocity of ball 2 seen from ball 1
    const Vec ga = a.bodies.cell.image(a.bodies.position[0], a.bodies.position[1]) - a.bodies.position[0];
    const Vec gm = m.bodies.position[1] - m.bodies.position[0];
    CHECK((ga - gm).norm() <= 1e-12);
    const Vec va = a.bodies.cell.image_velocity(a.bodies.position[0], a.bodies.position[1], a.bodies.velocity[1]) -
                   a.bodies.velocity[0];
    CHECK((va - (m.bodies.velocity[1] - m.bodies.velocity[0])).norm() <= 1e-9);
}

TEST_CASE("a ball that crosses a sheared boundary comes back shifted by the offset, with its image's velocity",
          "[periodic][shear]") {
    // shear 10 /s in a cell 0.1 m high: the cell above moves at +1 m/s.
    // Ball 1 rises through y = L, ball 2 sinks through y = 0, both from rest
    // along x: each comes back at the other side with v_x -1 and +1 m/s, and
    // its image across the boundary it crossed is where it would be without
    // shear (x 0.05 and 0.03): the offset since the crossing is the slide of
    // the image.
    const double rate = 10, L = 0.1;
    Simulation sim(sheared_scene(2, L, rate, json::array({cell_ball(0.05, 0.095, 0.0, 1.0, 0.0), cell_ball(0.03, 0.005, 0.0, -1.0, 0.0)})));
    sim.set_quiet(true);
    sim.cycle(2000);  // 0.02 s: 20 mm along y, the offset 20 mm
    const World& w = sim.world();
    const PeriodicCell& cell = w.bodies.cell;
    REQUIRE(rebuilds(w) > 1);
    CHECK(cell.shear_offset == Approx(rate * L * 0.02).epsilon(1e-9));
    CHECK(w.bodies.velocity[0].x() == -rate * L);
    CHECK(w.bodies.velocity[1].x() == rate * L);
    CHECK(w.bodies.velocity[0].y() == 1.0);
    const Vec x1 = cell.wrap(w.bodies.position[0]), x2 = cell.wrap(w.bodies.position[1]);
    CHECK(x1.y() == Approx(0.015).margin(1e-12));
    CHECK(x2.y() == Approx(0.085).margin(1e-12));
    // the image above ball 1 (below ball 2) is at the unsheared place
    const double up = std::fmod(x1.x() + cell.shear_offset + L, L), down = std::fmod(x2.x() - cell.shear_offset + 2 * L, L);
    CHECK(up == Approx(0.05).margin(1e-12));
    CHECK(down == Approx(0.03).margin(1e-12));
}

TEST_CASE("a sheared granular gas conserves its peculiar momentum to round-off, with contacts across the boundary",
          "[periodic][shear]") {
    auto sim = sheared_gas();
    const World& w = sim->world();
    const Vec p0 = peculiar_momentum(w);
    const double scale = momentum_scale(w);
    const std::size_t across = cycle_counting_across(
        *sim, 20, 50, [](const Vec& x1, const Vec& x2) { return std::fabs(x2.y() - x1.y()) > 0.015; });
    CHECK(across > 0);
    CHECK(w.bodies.cell.shear_offset > 0);
    CHECK((peculiar_momentum(w) - p0).norm() <= 1e-12 * scale);
}

TEST_CASE("a sheared gas gives bit-identical states with 1 and 2 threads", "[periodic][shear][determinism]") {
    const auto hash = hashes_on_1_and_2_threads(sheared_gas, 600);
    CHECK(hash[0] == hash[1]);
}

TEST_CASE("a sheared gas restarted from a checkpoint reaches the state of the uninterrupted run", "[periodic][shear][restart]") {
    auto whole = sheared_gas();
    whole->cycle(600);
    auto resumed = restarted_after(sheared_gas, 301, "plab_sheared");
    CHECK(resumed->world().bodies.cell.sheared);
    CHECK(resumed->world().bodies.cell.shear_rate == 60.0);
    resumed->cycle(299);
    CHECK(state_hash(resumed->world()) == state_hash(whole->world()));
}

TEST_CASE("a sheared cell starts the balls on the shear's flow unless told otherwise", "[periodic][shear]") {
    json scene = sheared_scene(2, 0.1, 10.0, json::array({cell_ball(0.05, 0.075, 0.0, 0.0, 0.0), cell_ball(0.02, 0.025, 0.0, 0.0, 0.0)}));
    scene["domain"]["shear"].erase("initial_velocity");
    Simulation sim(scene);
    CHECK(sim.world().bodies.velocity[0].x() == Approx(0.25).epsilon(1e-12));  // rate (y - L/2)
    CHECK(sim.world().bodies.velocity[1].x() == Approx(-0.25).epsilon(1e-12));
}
