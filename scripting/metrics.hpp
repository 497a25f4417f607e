// Accuracy metrics a scene declares under "metrics" (docs/speed-accuracy.md).
#pragma once

#include "simulation.hpp"

namespace plab {

// One entry per metric: name, value/reference or points, error (relative).
// Errors in the block name their JSON path.
json evaluate_metrics(const json& metrics, const Simulation& sim, const std::string& scene_dir);

} // namespace plab
