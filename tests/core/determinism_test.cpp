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
    return sim.world().state_hash();
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
        return std::make_pair(w.state_hash(), log);
    };
    const auto one = run(1), two = run(2);
    CHECK(!one.second.empty());  // bonds did break
    CHECK(one.first == two.first);
    CHECK(one.second == two.second);
#ifdef _OPENMP
    omp_set_num_threads(omp_get_num_procs());
#endif
}
