// PNG pictures drawn with cairo: snapshots of 2D scenes (balls to scale,
// coloured by a field, with colour bar and unit, axes in metres, time stamp
// and scale bar; bonds as lines, broken ones marked; walls) and time-series plots (curves against
// reference data with an error band).
#pragma once

#include "plot.hpp"

#include <plab_host/world.hpp>

#include <cstdint>
#include <string>
#include <utility>
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
    // The colour range: [range_min, range_max] when range_min < range_max,
    // else the range of the values drawn.
    double range_min = 0, range_max = 0;
    bool axes = true;                   // x and y axes in metres around the scene
    std::vector<int> greyed_groups;     // drawn light grey, left out of the range (fixed, boundary)
    std::vector<int> hidden_groups;     // not drawn
};
// The default view: balls and finite walls, with a 3 % margin.
std::vector<double> snapshot_view(const World& w);
// Per-ball values of `field` with its unit; throws InputError("field", ...)
// naming the known fields if it is unknown.
std::vector<double> snapshot_values(const World& w, const std::string& field, std::string& unit);

// What a snapshot draws, taken from the world: a series can draw its
// frames again when the run ends, in the run's colour range.
struct SnapshotFrame {
    double time = 0;
    std::uint64_t step = 0;
    std::string field, unit;
    std::vector<std::string> group_names;
    std::vector<float> x, y, radius, value;  // the balls drawn, m and the field's unit
    std::vector<int> group;
    std::vector<float> walls, bonds, breaks;  // segments x0 y0 x1 y1, m
    std::size_t bytes() const;
};
SnapshotFrame capture_snapshot(const World& w, const SnapshotOptions& opt);
// The range of the values coloured (greyed groups are not), or NaNs for none.
std::pair<double, double> value_range(const SnapshotFrame& f, const SnapshotOptions& opt);
// Where the scene lands in the picture: px = left + (x - x0) scale,
// py = top + (y1 - y) scale.
struct SnapshotLayout {
    double left, top, scale;
    int width, height;
};
SnapshotLayout snapshot_layout(const SnapshotOptions& opt, const std::vector<double>& view);
void draw_snapshot_png(const SnapshotFrame& f, const SnapshotOptions& opt, const std::vector<double>& view,
                       double vmin, double vmax, const std::string& path);
// capture_snapshot + draw_snapshot_png, in opt's range or the frame's own.
void write_snapshot_png(const World& w, const SnapshotOptions& opt, const std::string& path);

} // namespace plab
