// Time-series plots as PNG (cairo): curves against reference data with an
// error band. Kept free of the kernel so validation cases can hand back
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
};
struct Plot {
    std::string title, x_label, y_label;
    std::vector<Curve> curves;
};
void write_plot_png(const Plot& plot, const std::string& path, int width = 900, int height = 560);

} // namespace plab
