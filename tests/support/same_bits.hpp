// The two ways a run must give the same bits: on 1 and 2 OpenMP threads,
// and restarted from a checkpoint. `make` returns a fresh
// std::unique_ptr<Simulation> of the scene under test.
#pragma once

#include "simulation.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <unistd.h>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace plab::testing_support {

// The state hashes after `steps` on 1 and 2 threads (every loop parallel:
// parallel_min 0); the thread count is 1 again afterwards.
template <class Make> std::array<std::uint64_t, 2> hashes_on_1_and_2_threads(Make make, int steps) {
    std::array<std::uint64_t, 2> hash{};
    for (int threads : {1, 2}) {
#ifdef _OPENMP
        omp_set_num_threads(threads);
#endif
        auto sim = make();
        sim->world().parallel_min = 0;
        sim->cycle(steps);
        hash[threads - 1] = state_hash(sim->world());
    }
#ifdef _OPENMP
    omp_set_num_threads(1);
#endif
    return hash;
}

// A run of `make()` checkpointed after `steps` and restarted from that file
// (removed again), quiet, ready to go on.
template <class Make> std::unique_ptr<Simulation> restarted_after(Make make, int steps, const std::string& name) {
    namespace fs = std::filesystem;
    const fs::path file = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()) + ".plab");
    {
        auto first = make();
        first->cycle(steps);
        first->save_checkpoint(file.string());
    }
    auto resumed = Simulation::restart(file.string());
    resumed->set_quiet(true);
    fs::remove(file);
    return resumed;
}

} // namespace plab::testing_support
