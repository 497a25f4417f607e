// PNG pictures drawn with cairo: snapshots of 2D scenes (balls to scale,
// coloured by a field, with colour bar, time stamp and scale bar; bonds as
// lines, broken ones marked; walls) and time-series plots (curves against
// reference data with an error band).
#pragma once

#include "plot.hpp"

#include <plab_core/world.hpp>

#include <string>
#include <vector>

namespace plab {

// ---- snapshots ----

// Fields a snapshot can colour balls by (besides any plug-in field by name,
// e.g. sph_pressure): see snapshot_field_names().
std::vector<std::string> snapshot_field_names(const World& w);
struct SnapshotOptions {
    std::string field = "velocity";  // one of snapshot_field_names()
    int width = 1000;                // px; the height follows the scene's aspect
    bool bonds = true;               // draw intact bonds (grey) and broken ones (red)
    // The region drawn, m (x0, y0, x1, y1); empty: the balls and walls now.
    // A frame series keeps one view so the frames line up as an animation.
    std::vector<double> view;
};
// The default view: balls and finite walls, with a 3 % margin.
std::vector<double> snapshot_view(const World& w);
// Per-ball values of `field` with its unit; throws InputError("field", ...)
// naming the known fields if it is unknown.
std::vector<double> snapshot_values(const World& w, const std::string& field, std::string& unit);
void write_snapshot_png(const World& w, const SnapshotOptions& opt, const std::string& path);

} // namespace plab
