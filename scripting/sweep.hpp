// `plab sweep`: scenes over a grid of --set overrides, cost against accuracy.
#pragma once

#include <string>
#include <vector>

namespace plab {

// plab sweep SCENE... [--vary PATH=v1,v2]... [--set PATH=V]... [--jobs N] [--out DIR]
//            [--metric NAME] [--cost COLUMN]
int cmd_sweep(const std::vector<std::string>& args, const std::string& self_exe);

// The Pareto front: true for each point that no other point beats, i.e. no
// other point is at least as cheap and at least as accurate and strictly
// better in one of the two. A point without an error (NaN) is never on it.
std::vector<bool> pareto_front(const std::vector<double>& cost, const std::vector<double>& error);

// One run of a sweep as plotted: its overrides as a label, cost and error.
struct SweepPoint {
    std::string label;
    double cost = 0, error = 0;
};
// Error against cost (logarithmic axes where the values span more than a
// factor 20), each point labelled, the Pareto front marked and joined.
void write_sweep_png(const std::vector<SweepPoint>& points, const std::string& title, const std::string& cost_label,
                     const std::string& error_label, const std::string& path);

} // namespace plab
