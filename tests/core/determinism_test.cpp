// The reduction is deterministic: the same scene gives bit-identical states
// whatever the thread count (issue: kernel, plug-in host).
#include "simulation.hpp"
#include "settling_scene.hpp"

#include <catch2/catch.hpp>

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace plab;

namespace {

json pile(int dim) { return settling_scene(dim, dim == 2 ? 150 : 600); }

std::uint64_t run_with_threads(int dim, int threads, long steps) {
#ifdef _OPENMP
    omp_set_num_threads(threads);
    REQUIRE(omp_get_max_threads() == threads);  // (the suite runs with OMP_NUM_THREADS=1)
#endif
    Simulation sim(pile(dim));
    sim.set_quiet(true);
    sim.world().parallel_min = 0;  // thread every loop, however short
    sim.cycle(steps);
    return state_hash(sim.world());
}

} // namespace

TEST_CASE("a settling pile gives bit-identical states with 1 and 2 threads", "[determinism]") {
    for (int dim : {2, 3}) {
        INFO("dim " << dim);
        const std::uint64_t one = run_with_threads(dim, 1, 1500);
        const std::uint64_t two = run_with_threads(dim, 2, 1500);
        CHECK(one == two);
    }
#ifdef _OPENMP
    omp_set_num_threads(omp_get_num_procs());
#endif
}

// A big world's rebuild frees its columns and scratch (World::lean_rebuild_rows);
// a small one keeps them. Memory management only: the same bits, bonds and
// rebuilds included (the settling pile rebuilds many times in 1500 steps).
TEST_CASE("a lean rebuild gives the same state as one that keeps its buffers", "[determinism][detection]") {
    auto run = [](std::size_t lean_rows) {
        Simulation sim(pile(3));
        sim.set_quiet(true);
        sim.world().lean_rebuild_rows = lean_rows;
        sim.cycle(1500);
        REQUIRE(rebuilds(sim.world()) > 10);
        return state_hash(sim.world());
    };
    CHECK(run(0) == run(std::size_t(1) << 30));
}

TEST_CASE("a scene run twice gives the same state hash", "[determinism]") {
    CHECK(run_with_threads(2, 2, 500) == run_with_threads(2, 2, 500));
}

TEST_CASE("a brittle plate breaking under impact gives bit-identical states and break logs with 1 and 2 threads",
          "[determinism][bonds]") {
    auto run = [](int threads) {
#ifdef _OPENMP
        omp_set_num_threads(threads);
        REQUIRE(omp_get_max_threads() == threads);
#endif
        json scene = breaking_plate_scene();
        Simulation sim(scene);
        sim.set_quiet(true);
        World& w = sim.world();
        w.parallel_min = 0;
        w.bond(w.find_group("plate"), w.find_group("plate"), 1e-9);
        sim.cycle(3000);
        std::vector<std::uint64_t> log;
        for (const BondBreak& b : w.bond_breaks) log.insert(log.end(), {b.step, b.id1, b.id2, std::uint64_t(b.mode)});
        return std::make_pair(state_hash(w), log);
    };
    const auto one = run(1), two = run(2);
    CHECK(!one.second.empty());  // bonds did break
    CHECK(one.first == two.first);
    CHECK(one.second == two.second);
#ifdef _OPENMP
    omp_set_num_threads(omp_get_num_procs());
#endif
}

namespace {

// More bodies than one block of the per-body loops (World::kBodyBlock), with
// local damping on half of them and a fixed DOF on one, so every energy sum
// is taken over several blocks and both kick paths run.
Energies energies_with_threads(int threads) {
#ifdef _OPENMP
    omp_set_num_threads(threads);
#endif
    json scene = settling_scene(2, 2500);
    scene["walls"][0]["max"] = {0.3, 0.4};
    scene["bodies"][0]["box"]["max"] = {0.3, 0.3};
    scene["bodies"][0]["radius"] = {0.001, 0.002};
    Simulation sim(scene);
    sim.set_quiet(true);
    World& w = sim.world();
    w.parallel_min = 0;
    for (std::size_t i = 0; i < w.bodies.size(); i += 2) w.bodies.local_damping[i] = 0.3;
    w.bodies.fixity[1700] |= dof_x;
    w.mark_dirty();
    sim.cycle(400);
    return w.energies;
}

} // namespace

TEST_CASE("energy sums over many blocks of bodies are bit-identical with 1 and 2 threads", "[determinism]") {
    const Energies one = energies_with_threads(1), two = energies_with_threads(2);
    CHECK(one.kinetic > 0);
    CHECK(one.local_damping > 0);  // the damped half dissipates
    CHECK(one.kinetic == two.kinetic);
    CHECK(one.body == two.body);
    CHECK(one.boundary == two.boundary);
    CHECK(one.local_damping == two.local_damping);
    CHECK(one.dashpot == two.dashpot);
#ifdef _OPENMP
    omp_set_num_threads(omp_get_num_procs());
#endif
}
