// Clumps (plab_host/clumps.hpp) in the world: the torque-free body of three
// moments through the whole cycle, no contact between pebbles of one clump,
// the energy balance of a pile of clumps, and the same bits for 1 and 2
// threads and across a restart.
#include "euler_top.hpp"
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#ifdef _OPENMP
#include <omp.h>
#endif
#include <unistd.h>

using namespace plab;

namespace {

json vec(int dim, double x, double y, double z) { return dim == 2 ? json::array({x, y}) : json::array({x, y, z}); }

// One box-shaped clump (edges 0.1, 0.2, 0.3 m: three different moments),
// no gravity, no wall: nothing but its own motion.
json spinning_box(const json& spin) {
    return {{"dimension", 3},
            {"plugins", {"linear"}},
            {"timestep", {{"fixed", 1e-3}}},
            {"bodies", {{{"type", "clump"}, {"shape", {{"type", "box"}, {"size", {0.1, 0.2, 0.3}}}}, {"density", 1000},
                         {"pebbles", {{{"position", {0, 0, 0}}, {"radius", 0.05}}, {{"position", {0, 0, 0.1}}, {"radius", 0.05}}}},
                         {"position", {0, 0, 0}}, {"orientation", {{"axis", {1, 1, 0}}, {"angle", 20}}},
                         {"angular_velocity", spin}}}},
            {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"}, {"properties", {{"kn", 1e5}}}}}}};
}

// 3-pebble clumps dropped into a box: contacts between clumps and with walls.
json clump_pile(int dim, int count) {
    const double kn = dim == 2 ? 1e6 : 1e4;  // N/m: overlaps of a few % of a radius (a 2D clump is 1 m thick)
    const json pebbles = {{{"position", vec(dim, 0, 0, 0)}, {"radius", 0.004}},
                          {{"position", vec(dim, 0.005, 0, 0)}, {"radius", 0.003}},
                          {{"position", vec(dim, 0, 0.005, 0)}, {"radius", 0.003}}};
    return {{"dimension", dim},
            {"plugins", {"linear"}},
            {"gravity", vec(dim, 0, -9.81, 0)},
            // (the energy bookkeeping of impacts converges with dt: 3-7 % off at
            // 0.8 x critical for balls and clumps alike, 1 % at 0.2)
            {"timestep", {{"safety_factor", 0.2}}},
            {"bodies", {{{"type", "clump_fill"}, {"count", count}, {"seed", 5},
                         {"box", {{"min", vec(dim, 0, 0, 0)}, {"max", vec(dim, 0.1, 0.15, 0.1)}}},
                         {"clump", {{"group", "grains"}, {"density", 2500}, {"pebbles", pebbles}}}}}},
            {"walls", {{{"type", "box"}, {"min", vec(dim, 0, 0, 0)}, {"max", vec(dim, 0.1, 0.2, 0.1)}}}},
            {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"},
                                 {"properties", {{"kn", kn}, {"ks", kn / 2}, {"fric", 0.5}, {"dp_nratio", 0.2}}}}}}};
}

std::unique_ptr<Simulation> start(const json& scene, int threads) {
#ifdef _OPENMP
    omp_set_num_threads(threads);
#endif
    (void)threads;
    auto sim = std::make_unique<Simulation>(scene);
    sim->set_quiet(true);
    sim->world().parallel_min = 0;  // thread every loop, however short
    return sim;
}

} // namespace

TEST_CASE("a torque-free clump keeps its energy and angular momentum and flips at the elliptic period", "[clump][rigid]") {
    auto sim = start(spinning_box({0.05, 1.0, 0.05}), 1);
    World& w = sim->world();
    w.prepare();
    const Clumps& C = w.clumps;
    REQUIRE(C.size() == 1);
    REQUIRE(active_contacts(w) == 0);  // its two overlapping pebbles do not touch each other
    const Vec I = C.principal_moments[0];
    const double m = 1000 * 0.1 * 0.2 * 0.3;
    CHECK(I.x() == Approx(m * (0.2 * 0.2 + 0.1 * 0.1) / 12));  // box: I = m (a² + b²)/12, ascending
    CHECK(I.z() == Approx(m * (0.2 * 0.2 + 0.3 * 0.3) / 12));
    const Vec L0 = C.angular_momentum[0];
    const double E0 = w.energies.kinetic;
    REQUIRE(E0 == Approx(C.kinetic_energy(0)));
    const double T = flip_period(I, E0, L0.squaredNorm());
    // ω along the world's axes is not body-fixed; the body-frame ω along the
    // intermediate axis (principal 2) changes sign twice per period
    auto w2 = [&] { return (C.orientation[0].conjugate() * C.angular_velocity[0]).y(); };
    std::vector<double> rises;
    double last = w2(), worst_energy = 0, worst_momentum = 0;
    for (int step = 1; step <= 100000; ++step) {
        sim->cycle(1);
        worst_energy = std::max(worst_energy, std::fabs(w.energies.kinetic / E0 - 1));
        worst_momentum = std::max(worst_momentum, (C.angular_momentum[0] - L0).norm() / L0.norm());
        const double now = w2();
        if (last < 0 && now >= 0) rises.push_back(w.time - 1e-3 + 1e-3 * last / (last - now));
        last = now;
    }
    CHECK(worst_energy < 1e-6);
    CHECK(worst_momentum < 1e-6);
    REQUIRE(rises.size() >= 3);
    CHECK((rises.back() - rises.front()) / double(rises.size() - 1) == Approx(T).epsilon(0.01));
    CHECK(C.position[0].norm() < 1e-12);  // no force: the centre stays
}

TEST_CASE("a pile of clumps closes its energy balance and stays in its box", "[clump]") {
    for (int dim : {2, 3}) {
        INFO("dim " << dim);
        auto sim = start(clump_pile(dim, dim == 2 ? 60 : 120), 1);
        sim->cycle(8000);
        const World& w = sim->world();
        const Energies& e = w.energies;
        // stored (kinetic + strain) against what went in (gravity's work) and
        // what was taken out (slip, dashpots, damping); the walls do no work
        const double stored = e.kinetic + e.strain, in = e.body + e.boundary;
        const double out = e.slip + e.dashpot + e.local_damping;
        CHECK(std::fabs(stored - (in - out)) < 0.02 * in);
        CHECK(active_contacts(w) > 0);
        for (std::size_t c = 0; c < w.clumps.size(); ++c) {
            const Vec& x = w.clumps.position[c];
            CHECK((x.x() > 0 && x.x() < 0.1 && x.y() > 0 && x.y() < 0.2));
        }
    }
}

TEST_CASE("a pile of clumps gives the same bits with 1 and 2 threads and across a restart", "[clump][determinism][restart]") {
    const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                       ("plab_clumps_test_" + std::to_string(::getpid()) + ".plab");
    for (int dim : {2, 3}) {
        INFO("dim " << dim);
        const json scene = clump_pile(dim, dim == 2 ? 60 : 120);
        auto one = start(scene, 1);
        one->cycle(1500);
        auto two = start(scene, 2);
        two->cycle(1500);
        CHECK(state_hash(one->world()) == state_hash(two->world()));
        auto cut = start(scene, 2);
        cut->cycle(700);
        cut->save_checkpoint(file.string());
        cut.reset();
        auto resumed = Simulation::restart(file.string());
        resumed->set_quiet(true);
        resumed->cycle(800);
        CHECK(state_hash(resumed->world()) == state_hash(one->world()));
        CHECK(resumed->world().clumps.size() == one->world().clumps.size());
    }
    std::filesystem::remove(file);
#ifdef _OPENMP
    omp_set_num_threads(1);
#endif
}

TEST_CASE("a set command moves and fixes a clump through its pebbles' group or its id, and refuses what a clump cannot take", "[clump][scene]") {
    json scene = spinning_box({0, 0, 0});
    scene["bodies"][0].erase("orientation");  // the principal axes on the world's
    scene["commands"] = {{{"set", {{"group", "clumps"}, {"velocity", {1, 0, 0}}, {"angular_velocity", {2, 0, 0}}}}},
                         {{"cycle", 10}},
                         {{"set", {{"id", 0}, {"fix", {"x", "y", "z"}}, {"velocity", {0, -1, 0}}}}},
                         {{"cycle", 10}}};
    auto sim = start(scene, 1);
    sim->run();
    const Clumps& C = sim->world().clumps;
    // 10 free steps at 1 m/s, then 10 at the fixed (prescribed) -1 m/s in y
    CHECK(C.position[0].x() == Approx(0.01).epsilon(1e-12));
    CHECK(C.position[0].y() == Approx(-0.01).epsilon(1e-12));
    CHECK(C.velocity[0].x() == 0);
    // a spin about the largest moment's axis (x: edges 0.2, 0.3) stays; L = I ω
    CHECK(C.angular_velocity[0].x() == Approx(2).epsilon(1e-12));
    CHECK(C.angular_momentum[0].x() == Approx(2 * 1000 * 0.1 * 0.2 * 0.3 * (0.04 + 0.09) / 12).epsilon(1e-12));
    // the pebbles follow at once: the one at the centre moves with it
    const Bodies& B = sim->world().bodies;
    CHECK((B.velocity[0] - C.velocity[0]).norm() < 1e-12);
    CHECK((B.angular_velocity[0] - C.angular_velocity[0]).norm() < 1e-12);
    scene["commands"] = {{{"set", {{"group", "clumps"}, {"applied_force", {1, 0, 0}}}}}};
    auto refused = start(scene, 1);
    CHECK_THROWS_WITH(refused->run(), Catch::Matchers::Contains("scene.commands[0].set.applied_force") &&
                                          Catch::Matchers::Contains("does not apply to a clump"));
}
