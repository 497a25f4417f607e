// `plab sweep` (issue 7): runs one or more scenes (a resolution is often a
// scene of its own) over the grid of their --vary values, each point a
// separate `plab run` process (so peak memory and CPU time are the run's
// own, from wait4's rusage), and writes sweep.csv with the cost (wall and
// CPU seconds, steps, particle-steps, peak RSS, the models' stable step and
// contacts from summary.json) and the accuracy metrics the scenes declare
// (metrics.cpp), and sweep.png of one metric's error against one cost
// column with the Pareto front (sweep_plot.cpp).
#include "sweep.hpp"

#include "simulation.hpp"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace fs = std::filesystem;

namespace plab {

namespace {

struct Axis {
    std::string path;
    std::vector<std::string> values;
};

struct Point {
    std::size_t scene = 0;            // index into the scenes
    std::vector<std::string> values;  // one per axis
    std::string dir;
    int status = -1;
    double wall = 0, cpu = 0, rss_mb = 0;
    json summary;
};

Axis parse_vary(const std::string& a) {
    const auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == a.size())
        throw InputError("--vary " + a, "expected PATH=v1,v2,..., e.g. timestep.safety_factor=0.2,0.4,0.8");
    Axis axis{a.substr(0, eq), {}};
    std::stringstream ss(a.substr(eq + 1));
    for (std::string v; std::getline(ss, v, ',');)
        if (!v.empty()) axis.values.push_back(v);
    if (axis.values.empty()) throw InputError("--vary " + a, "no values");
    return axis;
}

// "a.b+c.d": one axis that sets the same value at several paths (the
// smoothing length of every rule and pass that declares it).
std::vector<std::string> coupled(const std::string& paths) {
    std::vector<std::string> out;
    std::stringstream ss(paths);
    for (std::string p; std::getline(ss, p, '+');) out.push_back(p);
    return out;
}

// Starts `plab run` for one point; returns the child's pid.
pid_t launch(const std::string& exe, const std::string& scene, const std::vector<std::string>& sets, const Point& p) {
    std::vector<std::string> argv = {exe, "run", scene, "--quiet", "--out", p.dir};
    for (const auto& s : sets) argv.insert(argv.end(), {"--set", s});
    const pid_t pid = fork();
    if (pid == 0) {
        std::vector<char*> c;
        for (auto& s : argv) c.push_back(s.data());
        c.push_back(nullptr);
        // one thread per run unless the user says otherwise: on a busy machine
        // OpenMP's barriers make a 2-thread run several times slower (types.hpp)
        if (!std::getenv("OMP_NUM_THREADS")) setenv("OMP_NUM_THREADS", "1", 1);
        const std::string log = p.dir + "/run.log";
        if (FILE* f = std::fopen(log.c_str(), "w")) {
            dup2(fileno(f), STDOUT_FILENO);
            dup2(fileno(f), STDERR_FILENO);
        }
        execv(exe.c_str(), c.data());
        _exit(127);
    }
    if (pid < 0) throw std::runtime_error("fork failed");
    return pid;
}

double number_or_nan(const json& j, const char* key) {
    return j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::nan("");
}

// Cost drivers the models report (output.cpp: cost_drivers): the smallest stable step and all contacts.
std::pair<double, double> model_drivers(const json& summary) {
    double stable = kInf, contacts = 0;
    for (const auto& m : summary.value("models", json::array())) {
        if (m.contains("stable_dt") && m["stable_dt"].is_number()) stable = std::min(stable, m["stable_dt"].get<double>());
        contacts += m.value("active_contacts", 0.0);
    }
    return {stable < kInf ? stable : std::nan(""), contacts};
}

struct Options {
    std::vector<std::string> scenes;
    std::vector<Axis> axes;
    std::vector<std::string> sets;
    int jobs = 1;
    std::string out, metric, cost = "cpu_s";
};

const std::vector<std::string> kCostColumns = {"cpu_s", "wall_s", "steps", "particle_steps", "peak_rss_mb"};

Options parse_options(const std::vector<std::string>& args) {
    Options o;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        const bool value = i + 1 < args.size();
        if (a == "--vary" && value) o.axes.push_back(parse_vary(args[++i]));
        else if (a == "--set" && value) o.sets.push_back(args[++i]);
        else if (a == "--out" && value) o.out = args[++i];
        else if (a == "--metric" && value) o.metric = args[++i];
        else if (a == "--cost" && value) o.cost = args[++i];
        else if (a == "--jobs" && value) {
            o.jobs = std::atoi(args[++i].c_str());
            if (o.jobs < 1 || o.jobs > 64) throw InputError("--jobs", "value " + args[i] + " outside [1, 64]");
        } else if (a.rfind("--", 0) == 0) throw InputError("command line", "unknown option " + a);
        else o.scenes.push_back(a);
    }
    if (o.scenes.empty() || (o.axes.empty() && o.scenes.size() < 2))
        throw InputError("command line", "usage: plab sweep SCENE.json... [--vary PATH=v1,v2]... [--set PATH=V]... "
                                         "[--jobs N] [--out DIR] [--metric NAME] [--cost COLUMN] (--vary, or two "
                                         "scenes or more)");
    if (std::find(kCostColumns.begin(), kCostColumns.end(), o.cost) == kCostColumns.end())
        throw InputError("--cost", "unknown cost column \"" + o.cost + "\"; one of cpu_s, wall_s, steps, "
                                   "particle_steps, peak_rss_mb");
    if (o.out.empty()) o.out = "plab_out/sweep_" + fs::path(o.scenes[0]).stem().string();
    return o;
}

// Every point of the grid, for every scene; every override must apply to
// its scene before anything runs.
std::vector<Point> make_points(const Options& o) {
    std::vector<Point> points;
    for (std::size_t sc = 0; sc < o.scenes.size(); ++sc) {
        std::vector<Point> grid(1);
        grid[0].scene = sc;
        for (const Axis& a : o.axes) {
            std::vector<Point> grown;
            for (const Point& p : grid)
                for (const auto& v : a.values) {
                    Point q = p;
                    q.values.push_back(v);
                    grown.push_back(q);
                }
            grid = grown;
        }
        const json base = read_scene_file(o.scenes[sc]);
        for (Point& p : grid) {
            json probe = base;
            for (const auto& s : o.sets) apply_override(probe, s);
            for (std::size_t a = 0; a < o.axes.size(); ++a)
                for (const auto& path : coupled(o.axes[a].path)) apply_override(probe, path + "=" + p.values[a]);
            p.dir = (fs::path(o.out) / ("run_" + std::to_string(points.size()))).string();
            fs::create_directories(p.dir);
            points.push_back(p);
        }
    }
    return points;
}

// Runs the points, `jobs` at a time; fills in status, cost and summary.
void run_points(std::vector<Point>& points, const Options& o, const std::string& self_exe) {
    std::map<pid_t, std::pair<std::size_t, std::chrono::steady_clock::time_point>> running;
    std::size_t next = 0;
    while (next < points.size() || !running.empty()) {
        while (next < points.size() && int(running.size()) < o.jobs) {
            std::vector<std::string> s = o.sets;
            for (std::size_t a = 0; a < o.axes.size(); ++a)
                for (const auto& path : coupled(o.axes[a].path)) s.push_back(path + "=" + points[next].values[a]);
            running[launch(self_exe, o.scenes[points[next].scene], s, points[next])] = {next, std::chrono::steady_clock::now()};
            std::fprintf(stderr, "sweep: run %zu of %zu started\n", next + 1, points.size());
            ++next;
        }
        int status = 0;
        rusage ru{};
        const pid_t pid = wait4(-1, &status, 0, &ru);
        if (pid < 0) break;
        const auto it = running.find(pid);
        if (it == running.end()) continue;
        Point& p = points[it->second.first];
        p.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - it->second.second).count();
        p.cpu = double(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) + 1e-6 * double(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
        p.rss_mb = double(ru.ru_maxrss) / 1024.0;  // kB on Linux
        p.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        std::ifstream f(fs::path(p.dir) / "summary.json");
        if (f) p.summary = json::parse(f, nullptr, false);
        if (p.summary.is_discarded()) p.summary = json::object();
        running.erase(it);
    }
}

double metric_error(const Point& p, const std::string& name) {
    for (const auto& m : p.summary.value("metrics", json::array()))
        if (m.value("name", "") == name) return number_or_nan(m, "error");
    return std::nan("");
}

double cost_of(const Point& p, const std::string& column) {
    const double bodies = number_or_nan(p.summary, "bodies"), steps = number_or_nan(p.summary, "steps");
    if (column == "wall_s") return p.wall;
    if (column == "steps") return steps;
    if (column == "particle_steps") return bodies * steps;
    if (column == "peak_rss_mb") return p.rss_mb;
    return p.cpu;
}

// The metric the front and the picture use: --metric (with or without the
// "_error" of its column), else the first one a run reports.
std::string chosen_metric(const std::vector<std::string>& names, const std::string& wanted) {
    if (wanted.empty()) return names.empty() ? "" : names[0];
    for (const auto& n : names)
        if (n == wanted || n + "_error" == wanted) return n;
    std::string known;
    for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
    throw InputError("--metric", "no metric \"" + wanted + "\" in the runs' summaries; metrics: " +
                                     (known.empty() ? "none (the scene declares no \"metrics\")" : known));
}

// The text of a point in the table and the picture: the scene (when there
// are several) and each override as LAST_KEY=value.
std::string label(const Options& o, const Point& p) {
    std::string text = o.scenes.size() > 1 ? fs::path(o.scenes[p.scene]).stem().string() : "";
    for (std::size_t a = 0; a < o.axes.size(); ++a) {
        const std::string path = coupled(o.axes[a].path)[0];
        const auto dot = path.rfind('.');
        text += (text.empty() ? "" : " ") + (dot == std::string::npos ? path : path.substr(dot + 1)) + "=" + p.values[a];
    }
    return text;
}

// The CSV as an aligned text table on stdout.
void print_table(const std::string& csv) {
    std::vector<std::vector<std::string>> rows;
    std::stringstream in(csv);
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> cells;
        std::stringstream ls(line);
        for (std::string c; std::getline(ls, c, ',');) cells.push_back(c);
        rows.push_back(cells);
    }
    std::vector<std::size_t> width(rows[0].size(), 0);
    for (const auto& r : rows)
        for (std::size_t c = 0; c < r.size() && c < width.size(); ++c) width[c] = std::max(width[c], r[c].size());
    for (const auto& r : rows)
        for (std::size_t c = 0; c < r.size() && c < width.size(); ++c)
            std::printf("%-*s%s", int(width[c]), r[c].c_str(), c + 1 < r.size() ? "  " : "\n");
}

void write_results(const Options& o, const std::vector<Point>& points) {
    std::vector<std::string> metric_names;
    for (const auto& p : points)
        for (const auto& m : p.summary.value("metrics", json::array()))
            if (std::find(metric_names.begin(), metric_names.end(), m["name"].get<std::string>()) == metric_names.end())
                metric_names.push_back(m["name"]);
    const std::string metric = chosen_metric(metric_names, o.metric);
    std::vector<double> cost, error;
    std::vector<SweepPoint> plotted;
    for (const auto& p : points) {
        cost.push_back(cost_of(p, o.cost));
        // a run the detector stopped (or that failed) has no trustworthy error
        error.push_back(p.status == 0 ? metric_error(p, metric) : std::nan(""));
        plotted.push_back({label(o, p), cost.back(), error.back()});
    }
    const std::vector<bool> front = pareto_front(cost, error);
    std::ostringstream csv;
    csv.precision(6);
    if (o.scenes.size() > 1) csv << "scene,";
    for (const auto& a : o.axes) csv << a.path << ',';
    csv << "status,stopped_on,bodies,steps,particle_steps,wall_s,cpu_s,peak_rss_mb,stable_dt_s,contacts";
    for (const auto& m : metric_names) csv << ',' << m << "_error";
    csv << ",pareto\n";
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Point& p = points[i];
        const json& s = p.summary;
        const auto [stable, contacts] = model_drivers(s);
        if (o.scenes.size() > 1) csv << fs::path(o.scenes[p.scene]).stem().string() << ',';
        for (const auto& v : p.values) csv << v << ',';
        const std::string stopped = s.contains("stopped") ? s["stopped"]["quantity"].get<std::string>() : "";
        // plab run exits 3 when the detector stops it, 128 + the signal when it is stopped (SIGTERM)
        const char* status = p.status == 0 ? "ok" : p.status == 3 ? "unstable" : p.status > 128 ? "interrupted" : "error";
        csv << status << ',' << stopped << ','
            << number_or_nan(s, "bodies") << ',' << cost_of(p, "steps") << ',' << cost_of(p, "particle_steps") << ','
            << p.wall << ',' << p.cpu << ',' << p.rss_mb << ',' << stable << ',' << contacts;
        for (const auto& name : metric_names) csv << ',' << metric_error(p, name);
        csv << ',' << (front[i] ? "yes" : "no") << "\n";
    }
    std::ofstream(fs::path(o.out) / "sweep.csv") << csv.str();
    print_table(csv.str());
    std::printf("\n%zu runs; CSV in %s/sweep.csv; pareto = no other run is both cheaper (%s) and more accurate (%s)\n",
                points.size(), o.out.c_str(), o.cost.c_str(), metric.empty() ? "no metric" : metric.c_str());
    if (metric.empty()) return;
    const std::string png = (fs::path(o.out) / "sweep.png").string();
    const std::string scene = o.scenes.size() > 1 ? "" : " " + fs::path(o.scenes[0]).stem().string();
    write_sweep_png(plotted, "plab sweep" + scene + ": " + metric + " error against " + o.cost, o.cost,
                    metric + " relative error", png);
    std::printf("picture of error against cost in %s\n", png.c_str());
}

} // namespace

int cmd_sweep(const std::vector<std::string>& args, const std::string& self_exe) {
    const Options o = parse_options(args);
    std::vector<Point> points = make_points(o);
    run_points(points, o, self_exe);
    write_results(o, points);
    return 0;
}

} // namespace plab
