// The hidden study tests' run of a case's scene (docs/coupling.md): to its
// end or to the stop of an unstable run, whose metrics are still evaluated,
// so a study prints how far it got and what it measured.
#pragma once

#include "case_scene.hpp"

#include <string>

namespace plab::testing_support {

// "" when the run finished, else "; stopped: <why>".
inline std::string run_study(Simulation& sim) {
    sim.set_quiet(true);
    try {
        sim.run();
    } catch (const std::exception& e) {
        return std::string("; stopped: ") + e.what();
    }
    return "";
}

inline int group_count(const Simulation& sim, const std::string& group) {
    const World& w = sim.world();
    const int g = w.find_group(group);
    int n = 0;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) n += w.bodies.group[i] == g;
    return n;
}

} // namespace plab::testing_support
