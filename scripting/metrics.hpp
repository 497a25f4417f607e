// Accuracy metrics a scene declares under "metrics" (docs/speed-accuracy.md).
#pragma once

#include "simulation.hpp"

namespace plab {

// One entry per metric: name, value/reference or points, error (relative).
// Errors in the block name their JSON path.
json evaluate_metrics(const json& metrics, const Simulation& sim, const std::string& scene_dir);

// The (x, y) points of a reference CSV: {"file" (beside scene_dir, else in
// validation/reference), "x_column", "y_column", "x_max", "where": [{"column",
// "equals"}]}. Errors name the path.
std::vector<std::pair<double, double>> reference_curve(const Node& ref, const std::string& scene_dir);

// Linear interpolation of the samples (xs ascending, ys) at x; NaN outside them.
double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x);

} // namespace plab
