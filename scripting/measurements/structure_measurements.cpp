// Measurements of a structure in a flow (thesis §7.3; the elastic_gate case):
// how far one of its balls moved, and how high the water stands beside it
// (thesis Fig. 27). Where and when its first bond broke is first_break
// (coupling_measurements.cpp).
#include "measurement.hpp"

#include <algorithm>
#include <cmath>

namespace plab {

namespace {

// ball_displacement: one ball's displacement from where it started (a
// component x, y, z or magnitude, m); the ball is the group's whose centre
// lay nearest `near` at the start, the first of those equally near (within
// 1e-12 m). The gate's free end: the lowest row's ball nearest its mid-plane.
Measurement ball_displacement(const Node& with, const World& w) {
    with.allow_keys({"group", "near", "component"});
    const int group = measured_group(with, w);
    const Vec near = with.at("near").vec(w.dim);
    const std::string component = with.at("component").choice({"x", "y", "z", "magnitude"});
    std::size_t chosen = w.bodies.size();
    double best = kInf;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        if (w.bodies.group[i] != group) continue;
        const double d = (w.bodies.position[i] - near).norm();
        if (d < best - 1e-12) { best = d; chosen = i; }
    }
    if (chosen == w.bodies.size()) with.at("group").fail("the group has no balls");
    const BodyId id = w.bodies.id[chosen];
    const Vec start = w.bodies.position[chosen];
    const int c = component == "x" ? 0 : component == "y" ? 1 : component == "z" ? 2 : -1;
    return [id, start, c, hint = chosen](const World& x) {
        std::size_t i = hint;
        if (i >= x.bodies.size() || x.bodies.id[i] != id)  // the bodies were reordered: look the ball up
            for (i = 0; i < x.bodies.size() && x.bodies.id[i] != id; ++i) {}
        if (i == x.bodies.size()) return std::nan("");
        const Vec d = x.bodies.position[i] - start;
        return c < 0 ? d.norm() : d[c];
    };
}

// strip_top: the highest centre of the group's balls in the vertical strip
// x_min <= x < x_max, m; 0 while the strip holds none. Thesis Fig. 27's water
// level is this + dp/2 (the top particle's upper edge).
Measurement strip_top(const Node& with, const World& w) {
    with.allow_keys({"group", "x_min", "x_max"});
    const int group = measured_group(with, w);
    const double lo = with.at("x_min").number(), hi = with.at("x_max").number();
    if (!(hi > lo)) with.at("x_max").fail("the strip [x_min, x_max) is empty: x_max must exceed x_min = " + std::to_string(lo));
    return [group, lo, hi](const World& x) {
        double top = 0;
        for (std::size_t i = 0; i < x.bodies.size(); ++i) {
            const Vec& p = x.bodies.position[i];
            if (x.bodies.group[i] == group && p.x() >= lo && p.x() < hi) top = std::max(top, p.y());
        }
        return top;
    };
}

} // namespace

void register_structure_measurements(std::map<std::string, MeasurementInfo>& into) {
    into["ball_displacement"] = {
        "displacement (component x, y, z or magnitude) of the group's ball that started nearest the point near [m]",
        ball_displacement};
    into["strip_top"] = {"highest centre of the group's balls with x_min <= x < x_max, 0 when none [m]", strip_top};
}

} // namespace plab
