// The scene of a validation case, for the tests that assert the physics the
// case measures on a smaller or varied set-up: validation/<case>/<file> with
// --set overrides (e.g. {"variables.dp", 0.01}).
#pragma once

#include "simulation.hpp"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace plab::testing_support {

inline std::string case_dir(const std::string& name) { return std::string(PLAB_SOURCE_DIR) + "/validation/" + name; }

inline json case_scene(const std::string& name, const std::vector<std::pair<std::string, json>>& sets = {},
                       const std::string& file = "scene.json") {
    json scene = read_scene_file(case_dir(name) + "/" + file);
    for (const auto& [path, value] : sets) apply_override(scene, path + "=" + value.dump());
    scene.erase("output");
    return scene;
}

// The scene run to its end (its commands), quiet.
inline std::unique_ptr<Simulation> run_scene(const json& scene) {
    auto sim = std::make_unique<Simulation>(scene);
    sim->set_quiet(true);
    sim->run();
    return sim;
}

// The value (or error) of one of the scene's metrics after sim.run().
inline double metric(const Simulation& sim, const std::string& name, const char* field = "value") {
    const json summary = sim.summary();  // (a range over summary()["metrics"] would outlive the temporary)
    for (const json& m : summary["metrics"])
        if (m["name"] == name) return m[field].is_number() ? m[field].get<double>() : std::nan("");
    throw std::runtime_error("no metric " + name);
}

} // namespace plab::testing_support
