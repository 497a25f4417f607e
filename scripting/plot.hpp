// Plots as PNG (cairo): time series against reference data with an error
// band, and scatter plots (cost against error, `plab sweep`) with labelled
// points on linear or logarithmic axes. Kept free of the kernel so validation cases can hand back
// their series (CaseResult::plots) without more includes.
#pragma once

#include <string>
#include <vector>

namespace plab {

struct Curve {
    std::string label;
    std::vector<double> x, y;
    bool markers = false;     // drawn as markers (data points), else as a line
    double band = 0;          // > 0: y (1 +- band), the tolerance around a reference (a shaded band
                              // along a line, an error bar on each marker)
    bool joined = false;      // markers joined by a line in the given order (a Pareto front)
    double marker_radius = 3.5;               // px
    std::vector<std::string> point_labels;    // empty, or one text per point, drawn beside its marker
};
struct Plot {
    std::string title, x_label, y_label;
    std::vector<Curve> curves;
    bool log_x = false, log_y = false;  // logarithmic axes: points with a value <= 0 there are not drawn
    bool legend_above = false;          // legend between the title and the axes (else inside, upper left)
};
void write_plot_png(const Plot& plot, const std::string& path, int width = 900, int height = 560);

} // namespace plab
