// The picture of a sweep (issue 7): each run's error against its cost, the
// Pareto front (the runs no other run beats in both) marked and joined, so
// a user sees which setting buys accuracy and which only costs time. Drawn
// with the plot code of `plab plot` and the validation reports (pictures.cpp).
#include "sweep.hpp"

#include "plot.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace plab {

std::vector<bool> pareto_front(const std::vector<double>& cost, const std::vector<double>& error) {
    std::vector<bool> front(cost.size(), false);
    auto valid = [&](std::size_t i) { return std::isfinite(cost[i]) && std::isfinite(error[i]); };
    for (std::size_t i = 0; i < cost.size(); ++i) {
        if (!valid(i)) continue;
        bool dominated = false;
        for (std::size_t j = 0; j < cost.size() && !dominated; ++j)
            dominated = j != i && valid(j) && cost[j] <= cost[i] && error[j] <= error[i] &&
                        (cost[j] < cost[i] || error[j] < error[i]);
        front[i] = !dominated;
    }
    return front;
}

namespace {

// A wide positive range reads better on a log axis: sweeps halve a length
// or a step, so costs and errors change by factors.
bool wide(const std::vector<double>& v) {
    double lo = INFINITY, hi = 0;
    for (double x : v) {
        if (!std::isfinite(x)) continue;
        if (x <= 0) return false;
        lo = std::min(lo, x);
        hi = std::max(hi, x);
    }
    return hi > 20 * lo;
}

} // namespace

void write_sweep_png(const std::vector<SweepPoint>& points, const std::string& title, const std::string& cost_label,
                     const std::string& error_label, const std::string& path) {
    std::vector<double> cost, error;
    for (const SweepPoint& p : points) { cost.push_back(p.cost); error.push_back(p.error); }
    const std::vector<bool> front = pareto_front(cost, error);
    Curve runs{"runs (labelled with their overrides)", {}, {}, true, 0};
    Curve best{"Pareto front: no run is both cheaper and more accurate", {}, {}, true, 0};
    best.joined = true;
    best.marker_radius = 5.5;
    std::vector<std::size_t> order(points.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return cost[a] < cost[b]; });
    for (std::size_t i : order) {
        if (!std::isfinite(cost[i]) || !std::isfinite(error[i])) continue;
        runs.x.push_back(cost[i]);
        runs.y.push_back(error[i]);
        runs.point_labels.push_back(points[i].label);
        if (front[i]) { best.x.push_back(cost[i]); best.y.push_back(error[i]); }
    }
    Plot plot;
    plot.title = title;
    plot.x_label = cost_label;
    plot.y_label = error_label;
    plot.log_x = wide(runs.x);
    plot.log_y = wide(runs.y);
    plot.legend_above = true;  // any corner of the axes may hold a run
    plot.curves = {best, runs};  // the runs' markers and labels over the front's
    write_plot_png(plot, path, 1000, 620);
}

} // namespace plab
