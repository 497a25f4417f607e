// `plab sweep` (issue 7): runs a scene over the grid of its --vary values,
// each point a separate `plab run` process (so peak memory and CPU time are
// the run's own, from wait4's rusage), and writes sweep.csv with the cost
// (wall and CPU seconds, steps, particle-steps, peak RSS, the models' stable
// step and contacts from summary.json) and the accuracy metrics the scene
// declares (metrics.cpp). A text table marks the Pareto front of the first
// metric's error against CPU time. No PNG: that needs the cairo output of
// branch `sdk` (docs/speed-accuracy.md).
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

// Points no other point beats in both CPU time and error.
std::vector<bool> pareto(const std::vector<double>& cost, const std::vector<double>& error) {
    std::vector<bool> front(cost.size(), false);
    for (std::size_t i = 0; i < cost.size(); ++i) {
        if (std::isnan(error[i])) continue;
        bool dominated = false;
        for (std::size_t j = 0; j < cost.size() && !dominated; ++j)
            dominated = j != i && !std::isnan(error[j]) && cost[j] <= cost[i] && error[j] <= error[i] &&
                        (cost[j] < cost[i] || error[j] < error[i]);
        front[i] = !dominated;
    }
    return front;
}

void write_table(const std::vector<Axis>& axes, std::vector<Point>& points, const std::string& out_dir) {
    std::vector<std::string> metric_names;
    for (const auto& p : points)
        for (const auto& m : p.summary.value("metrics", json::array()))
            if (std::find(metric_names.begin(), metric_names.end(), m["name"].get<std::string>()) == metric_names.end())
                metric_names.push_back(m["name"]);
    std::vector<double> cost, first_error;
    for (const auto& p : points) {
        cost.push_back(p.cpu);
        double e = std::nan("");
        for (const auto& m : p.summary.value("metrics", json::array()))
            if (!metric_names.empty() && m["name"] == metric_names[0]) e = number_or_nan(m, "error");
        first_error.push_back(e);
    }
    const std::vector<bool> front = pareto(cost, first_error);
    std::ostringstream csv, txt;
    csv.precision(6);
    for (const auto& a : axes) csv << a.path << ',';
    csv << "status,stopped_on,bodies,steps,particle_steps,wall_s,cpu_s,peak_rss_mb,stable_dt_s,contacts";
    for (const auto& m : metric_names) csv << ',' << m << "_error";
    csv << ",pareto\n";
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Point& p = points[i];
        const json& s = p.summary;
        const double bodies = number_or_nan(s, "bodies"), steps = number_or_nan(s, "steps");
        const auto [stable, contacts] = model_drivers(s);
        for (const auto& v : p.values) csv << v << ',';
        const std::string stopped = s.contains("stopped") ? s["stopped"]["quantity"].get<std::string>() : "";
        csv << (p.status == 0 ? "ok" : p.status == 3 ? "unstable" : "error") << ',' << stopped << ',' << bodies << ','
            << steps << ',' << bodies * steps << ',' << p.wall << ',' << p.cpu << ',' << p.rss_mb << ',' << stable << ','
            << contacts;
        for (const auto& name : metric_names) {
            double e = std::nan("");
            for (const auto& m : s.value("metrics", json::array()))
                if (m["name"] == name) e = number_or_nan(m, "error");
            csv << ',' << e;
        }
        csv << ',' << (front[i] ? "yes" : "no") << "\n";
    }
    std::ofstream(fs::path(out_dir) / "sweep.csv") << csv.str();
    // the same as an aligned text table on stdout
    std::vector<std::vector<std::string>> rows;
    std::string line;
    std::stringstream in(csv.str());
    while (std::getline(in, line)) {
        std::vector<std::string> cells;
        std::stringstream ls(line);
        for (std::string c; std::getline(ls, c, ',');) cells.push_back(c);
        rows.push_back(cells);
    }
    std::vector<std::size_t> width(rows[0].size(), 0);
    for (const auto& r : rows)
        for (std::size_t c = 0; c < r.size() && c < width.size(); ++c) width[c] = std::max(width[c], r[c].size());
    for (const auto& r : rows) {
        for (std::size_t c = 0; c < r.size() && c < width.size(); ++c)
            std::printf("%-*s%s", int(width[c]), r[c].c_str(), c + 1 < r.size() ? "  " : "\n");
    }
    std::printf("\n%zu runs; CSV in %s/sweep.csv; pareto = no other run is both cheaper (CPU s) and more accurate "
                "(first metric)\n", points.size(), out_dir.c_str());
}

} // namespace

int cmd_sweep(const std::vector<std::string>& args, const std::string& self_exe) {
    std::string scene, out;
    std::vector<Axis> axes;
    std::vector<std::string> sets;
    int jobs = 1;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--vary" && i + 1 < args.size()) axes.push_back(parse_vary(args[++i]));
        else if (a == "--set" && i + 1 < args.size()) sets.push_back(args[++i]);
        else if (a == "--out" && i + 1 < args.size()) out = args[++i];
        else if (a == "--jobs" && i + 1 < args.size()) {
            jobs = std::atoi(args[++i].c_str());
            if (jobs < 1 || jobs > 64) throw InputError("--jobs", "value " + args[i] + " outside [1, 64]");
        } else if (a.rfind("--", 0) == 0) throw InputError("command line", "unknown option " + a);
        else if (scene.empty()) scene = a;
        else throw InputError("command line", "more than one scene given");
    }
    if (scene.empty() || axes.empty())
        throw InputError("command line", "usage: plab sweep SCENE.json --vary PATH=v1,v2 [--vary ...] [--set PATH=V]... "
                                         "[--jobs N] [--out DIR]");
    // every override must apply to the scene before anything runs
    const json base = read_scene_file(scene);
    if (out.empty()) out = "plab_out/sweep_" + fs::path(scene).stem().string();
    std::vector<Point> points(1);
    for (const Axis& a : axes) {
        std::vector<Point> grown;
        for (const Point& p : points)
            for (const auto& v : a.values) {
                Point q = p;
                q.values.push_back(v);
                grown.push_back(q);
            }
        points = grown;
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
        json probe = base;
        for (const auto& s : sets) apply_override(probe, s);
        for (std::size_t a = 0; a < axes.size(); ++a)
            for (const auto& path : coupled(axes[a].path)) apply_override(probe, path + "=" + points[i].values[a]);
        points[i].dir = (fs::path(out) / ("run_" + std::to_string(i))).string();
        fs::create_directories(points[i].dir);
    }
    std::map<pid_t, std::pair<std::size_t, std::chrono::steady_clock::time_point>> running;
    std::size_t next = 0;
    while (next < points.size() || !running.empty()) {
        while (next < points.size() && int(running.size()) < jobs) {
            std::vector<std::string> s = sets;
            for (std::size_t a = 0; a < axes.size(); ++a)
                for (const auto& path : coupled(axes[a].path)) s.push_back(path + "=" + points[next].values[a]);
            running[launch(self_exe, scene, s, points[next])] = {next, std::chrono::steady_clock::now()};
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
    write_table(axes, points, out);
    return 0;
}

} // namespace plab
