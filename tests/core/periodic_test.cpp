// Periodic cells (domain.periodic, issue 36): a ball that leaves the cell
// comes back on the other side with its velocity; a contact across the
// boundary is the contact of the minimum images, with its history carried
// across a wrap; a periodic gas conserves momentum; the same bits on 1 and 2
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

// A periodic gas of 3D balls with seeded random velocities.
std::unique_ptr<Simulation> gas() {
    json fill = {{"type", "random_fill"}, {"group", "g"}, {"box", {{"min", {0, 0, 0}}, {"max", {0.03, 0.03, 0.03}}}},
                 {"radius", {0.0015, 0.0025}}, {"density", 2500}, {"count", 150}, {"seed", 7}};
    auto sim = std::make_unique<Simulation>(periodic_cell_scene(3, 0.03, json::array({fill})));
    sim->set_quiet(true);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (Vec& v : sim->world().bodies.velocity) v = Vec(u(rng), u(rng), u(rng));
    return sim;
}

Vec momentum(const World& w) {
    Vec p = Vec::Zero();
    for (std::size_t i = 0; i < w.bodies.size(); ++i) p += w.bodies.mass[i] * w.bodies.velocity[i];
    return p;
}

} // namespace

TEST_CASE("a ball that leaves a periodic cell comes back on the other side with its velocity", "[periodic]") {
    Simulation sim(periodic_cell_scene(2, 0.1, json::array({cell_ball(0.095, 0.05, 1.0, 0.5, 0.0), cell_ball(0.03, 0.02, 0, 0, 0)})));
    sim.set_quiet(true);
    sim.cycle(2000);  // 0.02 s: 0.02 m along x, 0.01 m along y
    const World& w = sim.world();
    const Vec x = w.bodies.position[0];
    CHECK(w.bodies.velocity[0].x() == 1.0);
    CHECK(w.bodies.velocity[0].y() == 0.5);
    CHECK(w.bodies.cell.wrap(x).x() == Approx(0.015).margin(1e-12));  // re-entered at x = 0.115 - 0.1
    CHECK(w.bodies.cell.wrap(x).y() == Approx(0.06).margin(1e-12));
    CHECK(x.x() < 0.1 + 0.002);  // wrapped at a rebuild: within a skin of the cell
    CHECK(rebuilds(w) > 1);
}

TEST_CASE("two balls touching across a periodic boundary feel the forces they feel touching in the middle of the cell",
          "[periodic]") {
    // the same pair, drifting along x at 3 m/s, sliding and spinning: one
    // straddles x = 0 and crosses it (wrapped at rebuilds), the other stays
    // in the middle of the cell; the shear force they build is history
    auto run = [](double x1) {
        const double x2 = x1 + 0.0038;  // overlap 0.2 mm
        const double wrapped = x2 >= 0.1 ? x2 - 0.1 : x2;
        auto sim = std::make_unique<Simulation>(periodic_cell_scene(
            2, 0.1, json::array({cell_ball(x1, 0.05, 3.0, 0.01, 10.0), cell_ball(wrapped, 0.05, 3.0, -0.01, -5.0)})));
        sim->set_quiet(true);
        sim->cycle(100);  // 1 ms: 3 mm along x, the overlap still closed
        return sim;
    };
    const auto across = run(0.0981), middle = run(0.0481);
    const World &a = across->world(), &m = middle->world();
    REQUIRE(active_contacts(a) == 1);
    REQUIRE(active_contacts(m) == 1);
    CHECK(rebuilds(a) > 2);  // the pair was wrapped, its history carried by the ids
    CHECK(a.bodies.position[0].x() < 0.05);  // ball 1 crossed x = L and came back at the start of the cell
    const Vec fa = a.bodies.force[0], fm = m.bodies.force[0];
    const double scale = fm.norm();
    REQUIRE(scale > 0);
    CHECK((fa - fm).norm() <= 1e-9 * scale);
    CHECK((a.bodies.force[0] + a.bodies.force[1]).norm() <= 1e-12 * scale);  // opposite forces
    CHECK(std::fabs(a.bodies.moment[0].z() - m.bodies.moment[0].z()) <= 1e-9 * std::fabs(m.bodies.moment[0].z()));
    CHECK(std::fabs(a.bodies.moment[1].z() - m.bodies.moment[1].z()) <= 1e-9 * std::fabs(m.bodies.moment[1].z()));
    // the shear force (history) is the same: the friction limit is not reached
    const ModelView va = a.model(0), vm = m.model(0);
    REQUIRE(va.balls().size() >= 1);
    const Vec ga = a.bodies.cell.image(a.bodies.position[0], a.bodies.position[1]) - a.bodies.position[0];
    const Vec gm = m.bodies.position[1] - m.bodies.position[0];
    CHECK((ga - gm).norm() <= 1e-12);  // the same branch vector
    CHECK((a.bodies.velocity[0] - m.bodies.velocity[0]).norm() <= 1e-9);
}

TEST_CASE("a periodic granular gas conserves momentum to round-off, with contacts across the boundary",
          "[periodic]") {
    auto sim = gas();
    const World& w = sim->world();
    const Vec p0 = momentum(w);
    const double scale = momentum_scale(w);
    const std::size_t across =
        cycle_counting_across(*sim, 20, 50, [](const Vec& x1, const Vec& x2) { return (x2 - x1).norm() > 0.015; });
    CHECK(across > 0);
    CHECK((momentum(w) - p0).norm() <= 1e-13 * scale);
}

TEST_CASE("a periodic gas gives bit-identical states with 1 and 2 threads", "[periodic][determinism]") {
    const auto hash = hashes_on_1_and_2_threads(gas, 600);
    CHECK(hash[0] == hash[1]);
}

TEST_CASE("a periodic gas restarted from a checkpoint reaches the state of the uninterrupted run", "[periodic][restart]") {
    auto whole = gas();
    whole->cycle(600);
    auto resumed = restarted_after(gas, 300, "plab_periodic");
    CHECK(resumed->world().bodies.cell.any());
    resumed->cycle(300);
    CHECK(state_hash(resumed->world()) == state_hash(whole->world()));
}

TEST_CASE("the contact stress of a compressed periodic lattice, over the cell, is -kn d / s with every contact once",
          "[periodic][measurements]") {
    // a square lattice of fixed balls (radius R, spacing s < 2R) filling a
    // cell periodic in x and y: one x and one y contact per ball, a fifth of
    // them across the boundary, each pushing kn d with branch s (the minimum
    // image's): sigma_xx = sigma_yy = -kn d / s over the cell, xy zero
    const double R = 0.001, s = 0.0019, L = 10 * s, d = 2 * R - s, expected = -1e5 * d / s;
    json bodies = json::array();
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j)
            bodies.push_back({{"type", "ball"}, {"group", "grid"}, {"position", {(i + 0.5) * s, (j + 0.5) * s}},
                              {"radius", R}, {"density", 2500}, {"fix", {"all"}}});
    for (const char* component : {"xx", "yy", "xy"}) {
        INFO(component);
        json scene = periodic_cell_scene(2, L, bodies);
        scene["contact_models"][0]["properties"] = {{"kn", 1e5}};
        scene["histories"] = {{"every", 1}, {"record", {{{"name", "s"}, {"quantity", "measure.contact_stress"},
                                                         {"with", {{"min", {0, 0}}, {"max", {L, L}}, {"component", component}}}}}}};
        Simulation sim(scene);
        sim.set_quiet(true);
        sim.cycle(1);
        REQUIRE(active_contacts(sim.world()) == 200);
        const double got = sim.history("s").back();
        if (std::string(component) == "xy") CHECK(std::fabs(got) <= 1e-9 * std::fabs(expected));
        else CHECK(got == Approx(expected).epsilon(1e-12));
    }
}
