// Validation cases as data (docs/validation.md): validation/<case>/case.json
// names the case's scene(s), its runs (a label and --set overrides, in the
// quick and/or the full version), the checks that judge them (the first that
// applies is the headline figure; every one must pass) and the plots.
// This one runner serves every such case: it runs each scene as `plab run`
// does, takes the figures from the scene's own `metrics`, and judges them.
#include "metrics.hpp"
#include "validation.hpp"
#include "variables.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>

namespace fs = std::filesystem;

namespace plab {

namespace {

// What one run of a case leaves for its checks, details and plots.
struct RunRecord {
    std::string label;
    json metrics = json::array();
    std::vector<std::string> columns;
    std::vector<std::vector<double>> rows;
    std::size_t bodies = 0;
    std::uint64_t steps = 0;
    double cpu = 0;
    std::string stopped;  // why the run stopped early, if it did
    std::vector<std::pair<std::string, double>> variables;  // its scene's, resolved

    std::vector<double> column(const Node& where, const std::string& name) const {
        const auto it = std::find(columns.begin(), columns.end(), name);
        if (it == columns.end()) where.fail("run \"" + label + "\" records no history \"" + name + "\"");
        std::vector<double> out;
        for (const auto& r : rows) out.push_back(r[std::size_t(it - columns.begin())]);
        return out;
    }
    const json* metric(const std::string& name) const {
        for (const json& m : metrics)
            if (m.value("name", "") == name) return &m;
        return nullptr;
    }
};

bool in_mode(const Node& n, bool quick) {
    if (!n.has("in")) return true;
    const Node in = n.at("in");
    in.expect_array();
    for (std::size_t k = 0; k < in.size(); ++k)
        if (in.at(k).choice({"quick", "full"}) == (quick ? "quick" : "full")) return true;
    return false;
}

RunRecord run_one(const fs::path& dir, const Node& run) {
    run.allow_keys({"label", "scene", "set", "in"});
    RunRecord rec;
    rec.label = run.at("label").string();
    const fs::path scene_path = dir / run.string_or("scene", "scene.json");
    json scene = read_scene_file(scene_path.string());
    if (run.has("set")) {
        run.at("set").expect_object();
        for (const auto& [path, value] : run.at("set").value().items())
            apply_override(scene, path + "=" + (value.is_string() ? value.get<std::string>() : value.dump()));
    }
    scene.erase("output");  // a case writes no files of its own; the report has its plots
    const std::clock_t c0 = std::clock();
    Simulation sim(scene, dir.string());
    sim.set_quiet(true);
    try {
        sim.run();
    } catch (const std::exception& e) {
        rec.stopped = e.what();
    }
    rec.cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    rec.bodies = sim.world().bodies.size();
    rec.steps = sim.world().step_count;
    for (const auto& c : sim.history_columns()) rec.columns.push_back(c.name);
    rec.rows = sim.history_rows();
    rec.variables = scene_variables(sim.scene());
    const json summary = sim.summary();
    if (summary.contains("metrics")) rec.metrics = summary["metrics"];
    return rec;
}

const RunRecord& find_run(const Node& where, const std::vector<RunRecord>& runs, const std::string& label) {
    for (const RunRecord& r : runs)
        if (r.label == label) return r;
    where.fail("no run labelled \"" + label + "\" in this version of the case");
}

// Two runs' histories against each other: |y_a - y_b| / |y_b| at run b's
// samples (or at the x of the reference curve \"at\") inside [from, to];
// "norm" mean (default) or max.
double compare_runs(const Node& c, const std::vector<RunRecord>& runs, const fs::path& dir) {
    const Node pair = c.at("compare");
    pair.expect_array();
    if (pair.size() != 2) pair.fail("compare names two runs: [\"run a\", \"run b\"] (b is the reference)");
    const RunRecord &a = find_run(pair.at(0), runs, pair.at(0).string()), &b = find_run(pair.at(1), runs, pair.at(1).string());
    const std::string y = c.at("history").string(), x = c.string_or("x", "time");
    const std::vector<double> xa = a.column(c, x), ya = a.column(c, y), xb = b.column(c, x), yb = b.column(c, y);
    const double from = c.number_or("from", -kInf), to = c.number_or("to", kInf);
    const bool max = c.has("norm") && c.at("norm").choice({"mean", "max"}) == "max";
    // where to compare: b's samples, or the x of a reference curve ("at")
    std::vector<double> xs = xb;
    if (c.has("at")) {
        xs.clear();
        for (const auto& point : reference_curve(c.at("at"), dir.string())) xs.push_back(point.first);
    }
    double sum = 0, worst = 0;
    std::size_t n = 0;
    for (const double x : xs) {
        const double va = interpolate(xa, ya, x), vb = interpolate(xb, yb, x);
        if (x < from || x > to || std::isnan(va) || std::isnan(vb) || vb == 0) continue;
        const double e = std::fabs(va - vb) / std::fabs(vb);
        sum += e;
        worst = std::max(worst, e);
        ++n;
    }
    if (n == 0) return std::nan("");
    return max ? worst : sum / double(n);
}

double metric_of(const Node& c, const RunRecord& r) {
    const std::string name = c.at("metric").string();
    const json* m = r.metric(name);
    if (!m) c.at("metric").fail("run \"" + r.label + "\" has no metric \"" + name + "\" (its scene's \"metrics\")");
    const std::string field = c.string_or("field", "error");
    return m->contains(field) && (*m)[field].is_number() ? (*m)[field].get<double>() : std::nan("");
}

// Run a's metric minus run b's ("difference": ["case II", "case I"]: the
// weaker plate breaks into more pieces).
double metric_difference(const Node& c, const std::vector<RunRecord>& runs) {
    const Node pair = c.at("difference");
    pair.expect_array();
    if (pair.size() != 2) pair.fail("difference names two runs: [\"run a\", \"run b\"] (the figure is a's minus b's)");
    return metric_of(c, find_run(pair.at(0), runs, pair.at(0).string())) -
           metric_of(c, find_run(pair.at(1), runs, pair.at(1).string()));
}

// A run's metric, or the worst over a list of runs ("run": ["2D", "3D"]);
// or two runs compared.
double check_error(const Node& c, const std::vector<RunRecord>& runs, const fs::path& dir) {
    if (c.has("compare")) return compare_runs(c, runs, dir);
    if (c.has("difference")) return metric_difference(c, runs);
    const Node rn = c.at("run");
    if (!rn.value().is_array()) return metric_of(c, find_run(rn, runs, rn.string()));
    // the worst of the runs: the largest for a tolerance, the smallest for a bound from below
    const bool lower = c.has("at_least");
    double worst = lower ? kInf : -kInf;
    for (std::size_t k = 0; k < rn.size(); ++k) {
        const double e = metric_of(c, find_run(rn.at(k), runs, rn.at(k).string()));
        if (std::isnan(e)) return e;  // a run without the figure fails the check
        worst = lower ? std::min(worst, e) : std::max(worst, e);
    }
    return worst;
}

std::string run_line(const RunRecord& r) {
    char buf[512];
    std::snprintf(buf, sizeof buf, "    %s: %zu bodies, %llu steps, cpu %.1f s", r.label.c_str(), r.bodies,
                  static_cast<unsigned long long>(r.steps), r.cpu);
    std::string s = buf;
    const auto number = [](const json& m, const char* key) {
        return m.contains(key) && m[key].is_number() ? m[key].get<double>() : std::nan("");
    };
    for (const json& m : r.metrics) {
        const std::string name = m.value("name", "?");
        if (m.contains("error")) {  // a figure against a reference
            std::snprintf(buf, sizeof buf, "; %s error %.4g", name.c_str(), number(m, "error"));
            s += buf;
            if (m.contains("value"))
                std::snprintf(buf, sizeof buf, " (%.6g against %.6g)", number(m, "value"), number(m, "reference")), s += buf;
        } else {
            std::snprintf(buf, sizeof buf, "; %s %.6g", name.c_str(), number(m, "value"));
            s += buf;
        }
    }
    if (!r.stopped.empty()) s += "; stopped: " + r.stopped;
    return s + "\n";
}

// Every k-th row, so that a plot holds about 400 points of a run.
std::vector<std::size_t> plotted_rows(std::size_t n) {
    std::vector<std::size_t> rows;
    for (std::size_t k = 0; k < n; k += std::max<std::size_t>(1, n / 400)) rows.push_back(k);
    return rows;
}

// The analytical solution of a run as a curve: "expression" of the run's
// history columns and its scene's variables, at the run's samples.
Curve analytical_curve(const Node& a, const RunRecord& r, const std::string& x, bool several) {
    a.allow_keys({"expression", "label"});
    const Expression f(a.at("expression").string(), r.columns, r.variables, a.at("expression").path());
    const std::vector<double> xs = r.column(a, x);
    const std::string label = a.string_or("label", "analytical");
    Curve c{several ? r.label + ": " + label : label, {}, {}};
    for (std::size_t k : plotted_rows(r.rows.size())) {
        c.x.push_back(xs[k]);
        c.y.push_back(f(r.rows[k]));
    }
    return c;
}

// A metric of each run against a variable of its scene ("x"), with the
// metric's own reference (its analytical value) as a line.
Plot metric_plot(const Node& p, const std::vector<const RunRecord*>& runs) {
    const std::string x = p.at("x").string(), name = p.at("metric").string();
    Plot plot{p.at("title").string(), p.string_or("x_label", x), p.string_or("y_label", name), {}};
    std::vector<std::pair<double, std::pair<double, double>>> points;  // x, (value, reference)
    for (const RunRecord* r : runs) {
        const auto var = std::find_if(r->variables.begin(), r->variables.end(), [&](const auto& v) { return v.first == x; });
        if (var == r->variables.end()) p.at("x").fail("run \"" + r->label + "\" has no variable \"" + x + "\"");
        const json* m = r->metric(name);
        if (!m) p.at("metric").fail("run \"" + r->label + "\" has no metric \"" + name + "\"");
        const auto number = [&](const char* key) { return m->contains(key) && (*m)[key].is_number() ? (*m)[key].get<double>() : std::nan(""); };
        points.push_back({var->second, {number("value"), number("reference")}});
    }
    std::sort(points.begin(), points.end());
    Curve simulated{"plab", {}, {}, true}, reference{"analytical", {}, {}};
    for (const auto& [vx, vr] : points) {
        simulated.x.push_back(vx);
        simulated.y.push_back(vr.first);
        if (std::isfinite(vr.second)) {
            reference.x.push_back(vx);
            reference.y.push_back(vr.second);
        }
    }
    if (!reference.x.empty()) plot.curves.push_back(std::move(reference));
    plot.curves.push_back(std::move(simulated));
    return plot;
}

// A case's plot: "y" (a column, or several) of its runs (all, or "runs"),
// against a reference curve and/or each run's "analytical" solution.
Plot make_plot(const Node& p, const std::vector<RunRecord>& runs, const fs::path& dir) {
    p.allow_keys({"title", "x", "y", "metric", "x_label", "y_label", "runs", "reference", "analytical", "log"});
    std::vector<const RunRecord*> chosen;
    for (const RunRecord& r : runs) {
        if (p.has("runs")) {
            const auto& names = p.at("runs").value();
            if (std::find(names.begin(), names.end(), json(r.label)) == names.end()) continue;
        }
        chosen.push_back(&r);
    }
    if (p.has("metric")) {
        if (p.has("y") || p.has("reference") || p.has("analytical"))
            p.at("metric").fail("a metric plot draws the metric and its own reference: no y, reference or analytical");
        return metric_plot(p, chosen);
    }
    const std::string x = p.at("x").string();
    std::vector<std::string> ys;
    if (p.at("y").value().is_array())
        for (std::size_t k = 0; k < p.at("y").size(); ++k) ys.push_back(p.at("y").at(k).string());
    else ys.push_back(p.at("y").string());
    Plot plot{p.at("title").string(), p.string_or("x_label", x), p.string_or("y_label", ys[0]), {}};
    if (p.has("log")) {
        const std::string log = p.at("log").choice({"x", "y", "xy"});
        plot.log_x = log != "y";
        plot.log_y = log != "x";
    }
    for (const RunRecord* r : chosen) {
        const std::vector<double> xv = r->column(p, x);
        for (const std::string& y : ys) {
            const std::vector<double> yv = r->column(p, y);
            Curve c{ys.size() > 1 ? r->label + ": " + y : r->label, {}, {}};
            for (std::size_t k : plotted_rows(xv.size())) {
                c.x.push_back(xv[k]);
                c.y.push_back(yv[k]);
            }
            plot.curves.push_back(std::move(c));
        }
        if (p.has("analytical")) plot.curves.push_back(analytical_curve(p.at("analytical"), *r, x, chosen.size() > 1));
    }
    if (p.has("reference")) {
        const Node ref = p.at("reference");
        json curve = ref.value();
        const std::string label = ref.string_or("label", ref.at("file").string());
        curve.erase("label");
        Curve c{label, {}, {}, true};
        for (const auto& [rx, ry] : reference_curve(Node(curve, ref.path()), dir.string())) {
            c.x.push_back(rx);
            c.y.push_back(ry);
        }
        plot.curves.push_back(std::move(c));
    }
    return plot;
}

CaseResult run_case(const fs::path& dir, const json& spec, bool quick) {
    const Node root(spec, (dir / "case.json").string());
    std::vector<RunRecord> runs;
    const Node rn = root.at("runs");
    rn.expect_array();
    for (std::size_t k = 0; k < rn.size(); ++k)
        if (in_mode(rn.at(k), quick)) runs.push_back(run_one(dir, rn.at(k)));
    CaseResult result;
    for (const RunRecord& r : runs) result.details += run_line(r);
    const Node cn = root.at("checks");
    cn.expect_array();
    bool headline = false;
    for (std::size_t k = 0; k < cn.size(); ++k) {
        const Node c = cn.at(k);
        c.allow_keys({"name", "run", "metric", "field", "compare", "difference", "history", "x", "at", "from", "to", "norm",
                      "tolerance", "at_least", "in"});
        if (!in_mode(c, quick)) continue;
        const double e = check_error(c, runs, dir);
        // "tolerance": the figure at most this; "at_least": a bound from below (e.g. a clearance, m)
        const bool lower = c.has("at_least");
        const double bound = lower ? c.at("at_least").number() : c.at("tolerance").number(0, kInf);
        const bool pass = lower ? e >= bound : e <= bound;  // NaN fails
        if (!headline) { result.error = e; result.tolerance = bound; result.metric = c.at("name").string(); headline = true; }
        result.failed_checks += !pass;
        char buf[512];
        std::snprintf(buf, sizeof buf, "    check %s: %.4g (%s %.4g) %s\n", c.at("name").string().c_str(), e,
                      lower ? "at least" : "tolerance", bound, pass ? "PASS" : "FAIL");
        result.details += buf;
    }
    if (!headline) root.at("checks").fail("no check applies to the " + std::string(quick ? "quick" : "full") + " version");
    // A run that stopped early (unstable, out of cycles) fails its case even
    // when its checks read a figure from before the stop (issue 37).
    for (const RunRecord& r : runs)
        if (!r.stopped.empty()) {
            ++result.failed_checks;
            result.details += "    check run \"" + r.label + "\" reached its end: FAIL (" + r.stopped + ")\n";
        }
    if (root.has("plots"))
        for (std::size_t k = 0; k < root.at("plots").size(); ++k) result.plots.push_back(make_plot(root.at("plots").at(k), runs, dir));
    if (root.has("note")) result.details += "    " + root.at("note").string() + "\n";
    return result;
}

} // namespace

std::vector<ValidationCase> data_cases(const std::string& folder) {
    std::error_code ec;
    std::vector<fs::path> dirs;
    for (const auto& e : fs::directory_iterator(folder, ec))
        if (fs::exists(e.path() / "case.json")) dirs.push_back(e.path());
    std::sort(dirs.begin(), dirs.end());
    std::vector<ValidationCase> cases;
    for (const fs::path& dir : dirs) {
        const json spec = read_scene_file((dir / "case.json").string());
        const Node root(spec, (dir / "case.json").string());
        root.allow_keys({"description", "runs", "checks", "plots", "note"});
        cases.push_back({dir.filename().string(), root.at("description").string(),
                         [dir, spec](bool quick) { return run_case(dir, spec, quick); }});
    }
    return cases;
}

} // namespace plab
