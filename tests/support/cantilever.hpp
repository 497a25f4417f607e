// The tip-loaded cantilever of validation/cantilever (thesis 6.2), solved
// with overrides and read back through the case's own histories; and the
// runs of validation/cantilever_failure by their labels, so a test solves
// exactly what the case does (its strength rule among the overrides).
#pragma once

#include "case_scene.hpp"

#include <memory>

namespace plab::testing_support {

// The --set overrides of one run of a case (its case.json "runs"), as
// case_scene() takes them.
inline std::vector<std::pair<std::string, json>> case_run_sets(const std::string& name, const std::string& label) {
    const json spec = read_scene_file(case_dir(name) + "/case.json");
    for (const json& run : spec["runs"])
        if (run["label"] == label) {
            std::vector<std::pair<std::string, json>> sets;
            if (run.contains("set"))
                for (const auto& [path, value] : run["set"].items()) sets.emplace_back(path, value);
            return sets;
        }
    throw std::runtime_error("validation/" + name + "/case.json has no run labelled \"" + label + "\"");
}

// The cantilever's scene with `sets`, solved to its ratio.
inline std::unique_ptr<Simulation> solved_cantilever(const std::vector<std::pair<std::string, json>>& sets) {
    auto sim = std::make_unique<Simulation>(case_scene("cantilever", sets));
    sim->set_quiet(true);
    sim->run();
    return sim;
}

// A history column's value in the state the run ended in (histories.at_end).
inline double at_end(const Simulation& sim, const std::string& column) { return sim.history(column).back(); }

} // namespace plab::testing_support
