// Accuracy metrics a scene declares (`metrics`), evaluated at the end of a
// run from its recorded histories and written to summary.json, so that
// `plab sweep` can set error against cost (issue 7). Two kinds:
//   analytical: a reduction of one history (final, change = final - first,
//     max, min, time_of_max, mean, time_mean, max_abs, period and frequency
//     of a vibration) times `scale`,
//     optionally over the samples whose time lies in [from, to] (a terminal
//     velocity is the mean over a plateau), against an exact value:
//     error = |value - exact| / |exact|;
//     with `against`, the exact value is another history reduced alike;
//   reference:  a history against a reference curve (a CSV beside
//     the scene or in validation/reference), both scaled to the reference's
//     variables: error = mean |sim - ref| / |ref| over the reference points
//     inside the run (and `x_max`), with the max beside it; or their RMS
//     difference (also over the curve's peak), or how far the run leads
//     ("norm"); with `reduce`, the history's peak or its time against the
//     curve's: error = |value - reference|.
#include "metrics.hpp"
#include "validation.hpp"
#include "variables.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <tuple>

namespace fs = std::filesystem;

namespace plab {

namespace {

// A vibration's period: the times the history rises through its mean, each
// interpolated between its two samples, first to last over the whole periods
// between them. Rising crossings to rising crossings: a level off the true
// centre (the mean of a part period) moves every one alike. NaN with fewer
// than two.
double period(const std::vector<double>& h, const std::vector<double>& t) {
    double mean = 0;
    for (double v : h) mean += v;
    mean /= double(h.size());
    double first = std::nan(""), last = first;
    long crossings = 0;
    for (std::size_t k = 1; k < h.size() && k < t.size(); ++k) {
        const double a = h[k - 1] - mean, b = h[k] - mean;
        if (!(a < 0 && b >= 0)) continue;
        const double at = t[k - 1] + (t[k] - t[k - 1]) * a / (a - b);
        if (crossings++ == 0) first = at;
        last = at;
    }
    return crossings >= 2 ? (last - first) / double(crossings - 1) : std::nan("");
}

double reduce(const Node& n, const std::vector<double>& h, const std::vector<double>& t, const std::string& op) {
    if (h.empty()) n.fail("the history has no samples");
    if (op == "final") return h.back();
    if (op == "change") return h.back() - h.front();  // a displacement from the first sample
    if (op == "max") return *std::max_element(h.begin(), h.end());
    if (op == "min") return *std::min_element(h.begin(), h.end());
    if (op == "time_of_max") return t[std::size_t(std::max_element(h.begin(), h.end()) - h.begin())];  // a peak's time (the first)
    if (op == "time_below_zero") {  // e.g. a surface gap: how long the first contact lasted, crossings interpolated
        const auto cross = [&](std::size_t k) { return t[k - 1] + (t[k] - t[k - 1]) * h[k - 1] / (h[k - 1] - h[k]); };
        std::size_t in = 1;
        while (in < h.size() && !(h[in] < 0)) ++in;
        std::size_t out = in + 1;
        while (out < h.size() && h[out] < 0) ++out;
        if (out >= h.size() || t.size() < h.size()) return std::nan("");  // never entered, or never left
        return cross(out) - cross(in);
    }
    // conservation of a quantity from its first sample h[0] (the reference
    // state): the secular change, mean of the last tenth of the samples after
    // it minus the first tenth; the largest excursion from it
    if (op == "drift" || op == "max_deviation") {
        const std::size_t n = h.size() - 1;
        if (n == 0) return 0.0;
        if (op == "max_deviation") {
            double m = 0;
            for (std::size_t k = 1; k <= n; ++k) m = std::max(m, std::fabs(h[k] - h[0]));
            return m;
        }
        const std::size_t window = std::max<std::size_t>(1, n / 10);
        double first = 0, last = 0;
        for (std::size_t k = 1; k <= window; ++k) first += h[k];
        for (std::size_t k = n - window + 1; k <= n; ++k) last += h[k];
        return std::fabs(last - first) / double(window);
    }
    if (op == "period" || op == "frequency") return op == "period" ? period(h, t) : 1.0 / period(h, t);
    if (op == "max_abs") {
        double m = 0;
        for (double v : h) m = std::max(m, std::fabs(v));
        return m;
    }
    double sum = 0;
    for (double v : h) sum += v;
    return sum / double(h.size());  // mean
}

} // namespace

namespace {

// Cells of one CSV line, empty ones kept ("a,b," is three cells).
std::vector<std::string> csv_cells(const std::string& line) {
    std::vector<std::string> cells(1);
    for (char c : line) {
        if (c == ',') cells.emplace_back();
        else if (c != '\r') cells.back() += c;
    }
    return cells;
}

// A number filling its cell (spaces aside), or NaN-free failure.
bool read_number(const std::string& cell, double& v) {
    const char* begin = cell.c_str();
    char* end = nullptr;
    v = std::strtod(begin, &end);
    if (end == begin) return false;
    while (*end == ' ' || *end == '\t') ++end;
    return *end == '\0';
}

// One reference file read strictly: a header line (or none, when the first
// row is numeric), then rows of as many cells as it, the x and y cells
// finite numbers; errors give the file, line and column.
struct ReferenceReader {
    std::string json_path, path;
    long xc, yc;
    std::size_t cells = 0;  // of the first row
    long line_no = 0;
    [[noreturn]] void fail(const std::string& what) const {
        throw InputError(json_path, path + ", line " + std::to_string(line_no) + ": " + what);
    }
    // false for the header line
    bool row(const std::vector<std::string>& c, double& x, double& y) {
        const bool first = cells == 0;
        if (first) cells = c.size();
        else if (c.size() != cells)
            fail(std::to_string(c.size()) + " cells where the first row has " + std::to_string(cells));
        if (long(c.size()) <= std::max(xc, yc))
            fail("no column " + std::to_string(std::max(xc, yc)) + " (the row has " + std::to_string(c.size()) + " cells)");
        const bool nx = read_number(c[std::size_t(xc)], x), ny = read_number(c[std::size_t(yc)], y);
        if (first && !(nx && ny)) return false;  // the header
        for (const auto& [ok, v, col] : {std::tuple{nx, x, xc}, std::tuple{ny, y, yc}}) {
            if (!ok) fail("column " + std::to_string(col) + " holds \"" + c[std::size_t(col)] + "\", not a number");
            if (!std::isfinite(v)) fail("column " + std::to_string(col) + " holds \"" + c[std::size_t(col)] + "\": not a finite number");
        }
        return true;
    }
};

// Within one series (rows of the same first-column label) x should run one
// way without repeats. Digitised curves break this where they are steep
// (glowinski_2001_falling_cylinder.csv line 47, 1 ms back at the impact);
// the curve metrics take the points one by one, so it is said, not refused.
void check_series_order(const ReferenceReader& r, const std::string& series, double x, std::string& last_series,
                        std::vector<double>& xs) {
    if (series != last_series) { xs.clear(); last_series = series; }
    std::string what;
    if (!xs.empty() && x == xs.back()) what = "repeats the row before (duplicate x)";
    else if (xs.size() >= 2 && (x - xs.back()) * (xs.back() - xs[xs.size() - 2]) < 0) what = "breaks the order of the rows before";
    xs.push_back(x);
    static std::set<std::string> said;  // once per file and line, however many metrics read it
    const std::string where = r.json_path + ": " + r.path + ", line " + std::to_string(r.line_no);
    if (what.empty() || !said.insert(where).second) return;
    spdlog::warn("{}: x = {} {}; the points are compared as given", where, short_number(x), what);
}

} // namespace

std::vector<std::pair<double, double>> reference_curve(const Node& ref, const std::string& scene_dir) {
    ref.allow_keys({"file", "x_column", "y_column", "x_max", "where"});
    // rows of one series: {"column": k, "equals": "P1"}, every condition met
    std::vector<std::pair<long, std::string>> where;
    if (ref.has("where")) {
        const Node wn = ref.at("where");
        wn.expect_array();
        for (std::size_t k = 0; k < wn.size(); ++k) {
            wn.at(k).allow_keys({"column", "equals"});
            where.emplace_back(wn.at(k).at("column").integer(0, 1000), wn.at(k).at("equals").string());
        }
    }
    const std::string file = ref.at("file").string();
    std::string path = file;
    if (!fs::path(file).is_absolute()) {
        path = (fs::path(scene_dir) / file).string();
        if (!fs::exists(path)) path = reference_dir() + "/" + file;
    }
    std::ifstream f(path);
    if (!f) ref.at("file").fail("cannot open \"" + file + "\" (looked beside the scene and in " + reference_dir() + ")");
    ReferenceReader reader{ref.path(), path, ref.at("x_column").integer(0, 1000), ref.at("y_column").integer(0, 1000)};
    const double x_max = ref.number_or("x_max", kInf);
    std::vector<std::pair<double, double>> points;
    std::string last_series;
    std::vector<double> series_x;
    for (std::string line; std::getline(f, line);) {
        ++reader.line_no;
        if (line.empty() || line[0] == '#' || line == "\r") continue;
        const std::vector<std::string> cells = csv_cells(line);
        double x = 0, y = 0;
        if (!reader.row(cells, x, y)) continue;
        if (std::any_of(where.begin(), where.end(), [&](const auto& c) {
                return long(cells.size()) <= c.first || cells[std::size_t(c.first)] != c.second;
            }))
            continue;
        double label_number = 0;
        check_series_order(reader, read_number(cells[0], label_number) ? "" : cells[0], x, last_series, series_x);
        if (x <= x_max) points.emplace_back(x, y);
    }
    if (points.empty()) ref.fail("no numeric points in columns " + std::to_string(reader.xc) + ", " + std::to_string(reader.yc) + " of " + path);
    return points;
}

double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
    const auto it = std::lower_bound(xs.begin(), xs.end(), x);
    if (it == xs.end() || (it == xs.begin() && *it > x)) return std::nan("");
    const std::size_t k = std::size_t(it - xs.begin());
    if (k == 0 || xs[k] == x) return ys[k];
    const double w = (x - xs[k - 1]) / (xs[k] - xs[k - 1]);
    return ys[k - 1] + w * (ys[k] - ys[k - 1]);
}

namespace {

// The samples (time, value) whose time (the `time_history`) lies in [from, to]
// and whose value is a number.
struct Samples {
    std::vector<double> t, h;
    std::vector<double> x;  // the column "x" at the same samples, when the metric names one (reduce slope)
    double t_before = std::nan("");  // time of the last sample before the window (NaN: none)
};
Samples in_window(const Node& m, const std::vector<double>& t, const std::vector<double>& h, const std::vector<double>* x = nullptr) {
    const double from = m.number_or("from", -kInf), to = m.number_or("to", kInf);
    if (!(to > from)) m.at("to").fail("the window [from, to] = [" + std::to_string(from) + ", " + std::to_string(to) +
                                      "] is empty; \"to\" must exceed \"from\"");
    Samples out;
    for (std::size_t k = 0; k < h.size() && k < t.size(); ++k) {  // a NaN sample has no value (a probe with nothing in reach)
        if (t[k] >= from && t[k] <= to && !std::isnan(h[k]) && (!x || (k < x->size() && !std::isnan((*x)[k])))) {
            out.t.push_back(t[k]);
            out.h.push_back(h[k]);
            if (x) out.x.push_back((*x)[k]);
        }
        if (t[k] < from) out.t_before = t[k];
    }
    return out;  // empty when a run stopped before the window: no error figure, not a scene error
}

json relative_to(json out, double value, double exact) {
    out["value"] = value;
    out["reference"] = exact;
    out["error"] = exact != 0 ? std::fabs(value - exact) / std::fabs(exact) : std::fabs(value);
    return out;
}

// The mean over time, each sample standing for the interval since the one
// before it (that before the window included): the integral of the history
// over the window's time over that time, as a terminal velocity is averaged
// over a plateau whatever the steps (NaN for a window of no length).
double time_mean(const Samples& s) {
    double sum = 0, span = 0, before = s.t_before;
    for (std::size_t k = 0; k < s.h.size(); ++k) {
        const double dt = std::isnan(before) ? 0.0 : s.t[k] - before;
        sum += s.h[k] * dt;
        span += dt;
        before = s.t[k];
    }
    return span > 0 ? sum / span : std::nan("");
}

// The recorded column `name`; an error at `where` when there is none.
std::vector<double> named_history(const Node& where, const std::string& name, const Simulation& sim) {
    try {
        return sim.history(name);
    } catch (const InputError&) {
        where.fail("no history named \"" + name + "\" in scene.histories.record");
    }
}

// The least-squares slope of y against x (NaN for fewer than two distinct x):
// a rate of one measured quantity against another, e.g. the volumetric
// against the axial strain of a sheared sample (its dilatancy).
double slope(const std::vector<double>& x, const std::vector<double>& y) {
    const double n = double(x.size());
    double mx = 0, my = 0;
    for (std::size_t k = 0; k < x.size(); ++k) { mx += x[k] / n; my += y[k] / n; }
    double sxy = 0, sxx = 0;
    for (std::size_t k = 0; k < x.size(); ++k) {
        sxy += (x[k] - mx) * (y[k] - my);
        sxx += (x[k] - mx) * (x[k] - mx);
    }
    return sxx > 0 ? sxy / sxx : std::nan("");
}

// The history reduced to one number ("reduce", default final) times
// "scale", over |the first sample of the history "relative_to"| if given
// (e.g. an energy drift over the initial kinetic energy).
double reduced(const Node& m, const Samples& s, const Simulation& sim) {
    const std::string op = m.has("reduce") ? m.at("reduce").choice({"final", "change", "max", "min", "time_of_max", "mean",
                                                                    "time_mean", "max_abs", "time_below_zero", "drift",
                                                                    "max_deviation", "period", "frequency", "slope"})
                                           : "final";
    const double raw = op == "time_mean" ? time_mean(s) : op == "slope" ? slope(s.x.empty() ? s.t : s.x, s.h) : reduce(m, s.h, s.t, op);
    double value = raw * m.number_or("scale", 1.0);
    if (m.has("relative_to")) {
        const std::vector<double> base = named_history(m.at("relative_to"), m.at("relative_to").string(), sim);
        value /= std::fabs(base.empty() ? std::nan("") : base.front());
    }
    return value;
}

// Every sample against an exact solution written in the time `t` (and the
// scene's variables): the largest relative error ("norm": "max", default)
// or the mean ("mean").
json exact_metric(const Node& m, const Samples& s, const Simulation& sim, json out) {
    const Expression exact(m.at("exact").string(), {"t"}, scene_variables(sim.scene()), m.at("exact").path());
    const bool mean = m.has("norm") && m.at("norm").choice({"max", "mean"}) == "mean";
    double worst = 0, sum = 0;
    for (std::size_t k = 0; k < s.h.size(); ++k) {
        const double e = exact({s.t[k]});
        const double err = e != 0 ? std::fabs(s.h[k] - e) / std::fabs(e) : std::fabs(s.h[k]);
        worst = std::max(worst, err);
        sum += err;
    }
    out["points"] = s.h.size();
    out["error"] = mean ? sum / double(s.h.size()) : worst;
    out["max_error"] = worst;
    return out;
}

// The first time (x_scale × time_history) at which y_scale × the history
// reaches `first_above`: the run's against the reference curve's; the error
// is the absolute difference, in the reference's x units.
json event_metric(const Node& m, const Samples& s, const std::string& scene_dir, json out) {
    const Node ev = m.at("event");
    ev.allow_keys({"first_above"});
    const double level = ev.at("first_above").number();
    const double xs = m.number_or("x_scale", 1.0), ys = m.number_or("y_scale", 1.0);
    double run = std::nan(""), ref = std::nan("");
    for (std::size_t k = 0; k < s.h.size() && std::isnan(run); ++k)
        if (s.h[k] * ys >= level) run = s.t[k] * xs;
    for (const auto& [rx, ry] : reference_curve(m.at("reference"), scene_dir))
        if (ry >= level) { ref = rx; break; }
    if (std::isnan(ref)) m.at("reference").fail("the reference never reaches " + std::to_string(level));
    out["value"] = run;
    out["reference"] = ref;
    out["error"] = std::fabs(run - ref);  // NaN when the run never reaches the level
    return out;
}

// The history against a reference curve at the reference points inside the
// run. "norm": mean (default) of |sim - ref| / |ref|, with the max beside
// it; "rms", the root mean square of sim - ref in the reference's units (a
// curve through zero, e.g. a velocity from rest); "rms_over_peak", that over
// the curve's largest |y| (also past the run's end); "lead", the largest
// (sim - ref) / |ref|, 0 when the run never leads (a front bounded from
// above by a faster one).
json curve_metric(const Node& m, const Samples& s, const std::string& scene_dir, json out) {
    const double xs = m.number_or("x_scale", 1.0), ys = m.number_or("y_scale", 1.0);
    const std::string norm = m.has("norm") ? m.at("norm").choice({"mean", "rms", "rms_over_peak", "lead"}) : "mean";
    std::vector<double> x(s.t.size()), y(s.h.size());
    for (std::size_t k = 0; k < s.t.size(); ++k) x[k] = s.t[k] * xs;
    for (std::size_t k = 0; k < s.h.size(); ++k) y[k] = s.h[k] * ys;
    double sum = 0, worst = 0, lead = 0, squares = 0, peak = 0;
    std::size_t n = 0, inside = 0;
    for (const auto& [rx, ry] : reference_curve(m.at("reference"), scene_dir)) {
        peak = std::max(peak, std::fabs(ry));
        const double sim_y = interpolate(x, y, rx);
        if (std::isnan(sim_y)) continue;
        squares += (sim_y - ry) * (sim_y - ry);
        ++inside;
        if (ry == 0) continue;
        const double e = std::fabs(sim_y - ry) / std::fabs(ry);
        sum += e;
        worst = std::max(worst, e);
        lead = std::max(lead, (sim_y - ry) / std::fabs(ry));
        ++n;
    }
    const bool rms = norm == "rms" || norm == "rms_over_peak";
    const std::size_t points = rms ? inside : n;
    out["points"] = points;
    out["error"] = points == 0        ? std::nan("")
                   : rms            ? std::sqrt(squares / double(points)) / (norm == "rms" ? 1.0 : peak)
                   : norm == "lead" ? lead
                                    : sum / double(points);
    out["max_error"] = worst;
    return out;
}

// The history's peak or its time ("reduce": max, min, time_of_max) against
// the same of the whole reference curve: error = |value - reference| in the
// reference's units (a peak displacement, or when it came).
json reduced_against_reference(const Node& m, const Samples& s, const std::string& scene_dir, json out) {
    const std::string op = m.at("reduce").choice({"max", "min", "time_of_max"});
    const double xs = m.number_or("x_scale", 1.0), ys = m.number_or("y_scale", 1.0);
    std::vector<double> x, y, rx, ry;
    for (std::size_t k = 0; k < s.h.size(); ++k) {
        x.push_back(s.t[k] * xs);
        y.push_back(s.h[k] * ys);
    }
    for (const auto& [px, py] : reference_curve(m.at("reference"), scene_dir)) {
        rx.push_back(px);
        ry.push_back(py);
    }
    const double value = reduce(m, y, x, op), reference = reduce(m.at("reference"), ry, rx, op);
    out["value"] = value;
    out["reference"] = reference;
    out["error"] = std::fabs(value - reference);
    return out;
}

json one_metric(const Node& m, const Simulation& sim, const std::string& scene_dir) {
    m.allow_keys({"name", "history", "reduce", "scale", "relative_to", "analytical", "against", "exact", "norm", "event", "from", "to",
                  "time_history", "x_scale", "y_scale", "reference", "x"});
    json out = {{"name", m.at("name").string()}};
    const std::vector<double> h = named_history(m.at("history"), m.at("history").string(), sim);
    const std::vector<double> t = named_history(m, m.string_or("time_history", "time"), sim);
    if (m.has("x") && !(m.has("reduce") && m.at("reduce").string() == "slope"))
        m.at("x").fail("\"x\" goes with \"reduce\": \"slope\" (the slope of the history against x)");
    const std::vector<double> x = m.has("x") ? named_history(m.at("x"), m.at("x").string(), sim) : std::vector<double>{};
    const Samples s = in_window(m, t, h, m.has("x") ? &x : nullptr);
    if (s.h.empty()) {
        out["error"] = std::nan("");
        out["note"] = "no sample inside [from, to]: the run ended before the window";
        return out;
    }
    if (m.has("analytical")) return relative_to(std::move(out), reduced(m, s, sim), m.at("analytical").number());
    if (m.has("against")) {  // a solution that depends on the run (e.g. on a measured length): another column, reduced alike
        const Samples r = in_window(m, t, named_history(m.at("against"), m.at("against").string(), sim), m.has("x") ? &x : nullptr);
        return relative_to(std::move(out), reduced(m, s, sim), reduced(m, r, sim));
    }
    if (m.has("exact")) return exact_metric(m, s, sim, std::move(out));
    if (!m.has("reference")) {  // a figure without a reference: its value only (a check may bound it)
        out["value"] = reduced(m, s, sim);
        return out;
    }
    if (m.has("event")) return event_metric(m, s, scene_dir, std::move(out));
    if (m.has("reduce")) return reduced_against_reference(m, s, scene_dir, std::move(out));
    return curve_metric(m, s, scene_dir, std::move(out));
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
