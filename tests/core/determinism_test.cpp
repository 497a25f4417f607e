// The reduction is deterministic: the same scene gives bit-identical states
// whatever the thread count (issue: kernel, plug-in host).
#include "simulation.hpp"

#include <catch2/catch.hpp>

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace plab;

namespace {

json settling_scene(int dim) {
    auto v = [dim](double x, double y, double z) { return dim == 2 ? json::array({x, y}) : json::array({x, y, z}); };
    return {{"dimension", dim},
            {"plugins", {"linear"}},
            {"gravity", v(0, -9.81, 0)},
            {"bodies", {{{"type", "random_fill"}, {"group", "grains"}, {"box", {{"min", v(0, 0, 0)}, {"max", v(0.1, 0.1, 0.1)}}},
                         {"radius", {0.002, 0.004}}, {"density", 2500}, {"count", dim == 2 ? 150 : 600}, {"seed", 3}}}},
            {"walls", {{{"type", "box"}, {"min", v(0, 0, 0)}, {"max", v(0.1, 0.2, 0.1)}}}},
            {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"},
                                 {"properties", {{"kn", 1e4}, {"ks", 5e3}, {"fric", 0.5}, {"dp_nratio", 0.2}}}}}}};
}

std::uint64_t run_with_threads(int dim, int threads, long steps) {
#ifdef _OPENMP
    omp_set_num_threads(threads);
#endif
    Simulation sim(settling_scene(dim));
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
