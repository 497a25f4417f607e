// Accuracy metrics a scene declares (`metrics`), evaluated at the end of a
// run from its recorded histories and written to summary.json, so that
// `plab sweep` can set error against cost (issue 7). Two kinds:
//   analytical: a reduction of one history (final, change = final - first,
//     max, min, mean, max_abs) times `scale`, optionally over the samples
//     whose time lies in [from, to] (a terminal velocity is the mean over a
//     plateau), against an exact value: error = |value - exact| / |exact|;
//   reference:  a history against a reference curve (a CSV in
//     shared/reference or beside the scene), both scaled to the reference's
//     variables: error = mean |sim - ref| / |ref| over the reference points
//     inside the run (and `x_max`), with the max beside it.
#include "metrics.hpp"
#include "validation.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace plab {

namespace {

double reduce(const Node& n, const std::vector<double>& h, const std::string& op) {
    if (h.empty()) n.fail("the history has no samples");
    if (op == "final") return h.back();
    if (op == "change") return h.back() - h.front();  // a displacement from the first sample
    if (op == "max") return *std::max_element(h.begin(), h.end());
    if (op == "min") return *std::min_element(h.begin(), h.end());
    if (op == "max_abs") {
        double m = 0;
        for (double v : h) m = std::max(m, std::fabs(v));
        return m;
    }
    double sum = 0;
    for (double v : h) sum += v;
    return sum / double(h.size());  // mean
}

std::vector<std::pair<double, double>> read_curve(const Node& ref, const std::string& scene_dir) {
    ref.allow_keys({"file", "x_column", "y_column", "x_max"});
    const std::string file = ref.at("file").string();
    std::string path = file;
    if (!fs::path(file).is_absolute()) {
        path = (fs::path(scene_dir) / file).string();
        if (!fs::exists(path)) path = reference_dir() + "/" + file;
    }
    std::ifstream f(path);
    if (!f) ref.at("file").fail("cannot open \"" + file + "\" (looked beside the scene and in " + reference_dir() + ")");
    const long xc = ref.at("x_column").integer(0, 1000), yc = ref.at("y_column").integer(0, 1000);
    const double x_max = ref.number_or("x_max", kInf);
    std::vector<std::pair<double, double>> points;
    std::string line;
    while (std::getline(f, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> cells;
        std::stringstream ss(line);
        for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
        if (long(cells.size()) <= std::max(xc, yc)) continue;
        char *ex = nullptr, *ey = nullptr;
        const double x = std::strtod(cells[xc].c_str(), &ex), y = std::strtod(cells[yc].c_str(), &ey);
        if (ex == cells[xc].c_str() || ey == cells[yc].c_str()) continue;  // a header or text cell
        if (x <= x_max) points.emplace_back(x, y);
    }
    if (points.empty()) ref.fail("no numeric points in columns " + std::to_string(xc) + ", " + std::to_string(yc) + " of " + path);
    return points;
}

// Linear interpolation of (xs, ys) at x; NaN outside the sampled range.
double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
    const auto it = std::lower_bound(xs.begin(), xs.end(), x);
    if (it == xs.end() || (it == xs.begin() && *it > x)) return std::nan("");
    const std::size_t k = std::size_t(it - xs.begin());
    if (k == 0 || xs[k] == x) return ys[k];
    const double w = (x - xs[k - 1]) / (xs[k] - xs[k - 1]);
    return ys[k - 1] + w * (ys[k] - ys[k - 1]);
}

// The samples of h whose time (the `time_history`) lies in [from, to], s.
std::vector<double> in_window(const Node& m, const Simulation& sim, const std::vector<double>& h) {
    const auto t = sim.history(m.string_or("time_history", "time"));
    const double from = m.number_or("from", -kInf), to = m.number_or("to", kInf);
    if (!(to > from)) m.at("to").fail("the window [from, to] = [" + std::to_string(from) + ", " + std::to_string(to) +
                                      "] s is empty; \"to\" must exceed \"from\"");
    std::vector<double> out;
    for (std::size_t k = 0; k < h.size() && k < t.size(); ++k)
        if (t[k] >= from && t[k] <= to) out.push_back(h[k]);
    return out;  // empty when a run stopped before the window: no error figure, not a scene error
}

json one_metric(const Node& m, const Simulation& sim, const std::string& scene_dir) {
    m.allow_keys({"name", "history", "reduce", "scale", "analytical", "from", "to", "time_history", "x_scale", "y_scale",
                  "reference"});
    const std::string name = m.at("name").string();
    const Node hn = m.at("history");
    std::vector<double> h;
    try {
        h = sim.history(hn.string());
    } catch (const InputError&) {
        hn.fail("no history named \"" + hn.string() + "\" in scene.histories.record");
    }
    json out = {{"name", name}};
    if (m.has("analytical")) {
        const std::string op =
            m.has("reduce") ? m.at("reduce").choice({"final", "change", "max", "min", "mean", "max_abs"}) : "final";
        if (m.has("from") || m.has("to")) h = in_window(m, sim, h);
        if (h.empty()) {
            out["error"] = std::nan("");
            out["note"] = "no sample inside [from, to]: the run ended before the window";
            return out;
        }
        const double value = reduce(m, h, op) * m.number_or("scale", 1.0);
        const double exact = m.at("analytical").number();
        out["value"] = value;
        out["reference"] = exact;
        out["error"] = exact != 0 ? std::fabs(value - exact) / std::fabs(exact) : std::fabs(value);
        return out;
    }
    if (!m.has("reference")) m.fail("a metric needs \"analytical\" (a value) or \"reference\" (a curve)");
    const auto t = sim.history(m.string_or("time_history", "time"));
    const double xs = m.number_or("x_scale", 1.0), ys = m.number_or("y_scale", 1.0);
    std::vector<double> x(t.size()), y(h.size());
    for (std::size_t k = 0; k < t.size(); ++k) x[k] = t[k] * xs;
    for (std::size_t k = 0; k < h.size(); ++k) y[k] = h[k] * ys;
    double sum = 0, worst = 0;
    std::size_t n = 0;
    for (const auto& [rx, ry] : read_curve(m.at("reference"), scene_dir)) {
        const double sim_y = interpolate(x, y, rx);
        if (std::isnan(sim_y) || ry == 0) continue;
        const double e = std::fabs(sim_y - ry) / std::fabs(ry);
        sum += e;
        worst = std::max(worst, e);
        ++n;
    }
    out["points"] = n;
    out["error"] = n ? sum / double(n) : std::nan("");
    out["max_error"] = worst;
    return out;
}

} // namespace

json evaluate_metrics(const json& metrics, const Simulation& sim, const std::string& scene_dir) {
    const Node n(metrics, "scene.metrics");
    n.expect_array();
    json out = json::array();
    for (std::size_t i = 0; i < n.size(); ++i) out.push_back(one_metric(n.at(i), sim, scene_dir));
    return out;
}

} // namespace plab
