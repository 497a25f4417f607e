// Measurements of a granular deposit: the slope of a heap's flank, its
// angle of repose (the angle_of_repose case).
#include "measurement.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace plab {

namespace {

// The least-squares slope dy/dx of points (x, y); NaN for fewer than three.
double fitted_slope(const std::vector<double>& x, const std::vector<double>& y) {
    const std::size_t n = x.size();
    if (n < 3) return std::nan("");
    double mx = 0, my = 0;
    for (std::size_t k = 0; k < n; ++k) { mx += x[k]; my += y[k]; }
    mx /= double(n);
    my /= double(n);
    double sxy = 0, sxx = 0;
    for (std::size_t k = 0; k < n; ++k) {
        sxy += (x[k] - mx) * (y[k] - my);
        sxx += (x[k] - mx) * (x[k] - mx);
    }
    return sxy / sxx;
}

// heap_angle: the angle of a heap's flank to the horizontal, degrees: the
// surface (each vertical strip's highest ball top, centre + radius) in
// strips of `strip_width` from x_min to x_max, fitted by a straight line. In
// 3D the highest ball of a strip over all z: the profile through a conical
// heap's apex. Only balls with centres between `y_min` and `y_max` (both
// optional) are the heap's, not grains still in a hopper above it or fallen
// past its base; with `y_min` (the base's level) a strip without a ball
// reads y_min, the bare base. NaN while fewer than three strips have a
// surface.
Measurement heap_angle(const Node& with, const World& w) {
    with.allow_keys({"group", "x_min", "x_max", "strip_width", "y_min", "y_max"});
    const int group = measured_group(with, w);
    const double lo = with.at("x_min").number(), hi = with.at("x_max").number();
    if (!(hi > lo)) with.at("x_max").fail("the flank [x_min, x_max] is empty: x_max must exceed x_min = " + std::to_string(lo));
    const double width = with.at("strip_width").number();
    if (!(width > 0) || !(width <= (hi - lo) / 3))
        with.at("strip_width").fail("strip width " + std::to_string(width) + " m is outside (0, (x_max - x_min) / 3]: "
                                    "a line is fitted to three strips or more");
    const double y_min = with.has("y_min") ? with.at("y_min").number() : -kInf;
    const double y_max = with.has("y_max") ? with.at("y_max").number() : kInf;
    if (!(y_max > y_min)) with.at("y_max").fail("y_max must exceed y_min = " + std::to_string(y_min));
    const std::size_t strips = std::size_t((hi - lo) / width);
    return [group, lo, width, strips, y_min, y_max](const World& x) {
        std::vector<double> top(strips, y_min);
        for (std::size_t i = 0; i < x.bodies.size(); ++i) {
            const double y = x.bodies.position[i].y();
            if (x.bodies.group[i] != group || y < y_min || y > y_max) continue;
            const double s = (x.bodies.position[i].x() - lo) / width;
            if (!(s >= 0) || s >= double(strips)) continue;
            double& t = top[std::size_t(s)];
            t = std::max(t, y + x.bodies.radius[i]);
        }
        std::vector<double> xs, ys;
        for (std::size_t s = 0; s < strips; ++s)
            if (top[s] > -kInf) { xs.push_back(lo + (double(s) + 0.5) * width); ys.push_back(top[s]); }  // (none empty with y_min)
        return std::atan(std::fabs(fitted_slope(xs, ys))) * 180.0 / M_PI;
    };
}

} // namespace

void register_granular_measurements(std::map<std::string, MeasurementInfo>& into) {
    into["heap_angle"] = {"angle of a heap's flank to the horizontal: a line fitted to the highest ball top of each strip of "
                          "strip_width from x_min to x_max, of the balls with y_min <= y <= y_max (optional; an empty strip reads y_min) [degrees]",
                          heap_angle};
}

} // namespace plab
