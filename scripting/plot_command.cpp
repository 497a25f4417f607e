// `plab plot HISTORY.csv... [--label A,B] [--x COL] [--y A,B,...] [--ref
// REF.csv --ref-y COL [--ref-x COL] [--band FRACTION]] [--title TEXT]
// [--xlabel TEXT] [--ylabel TEXT] [--log x|y|xy] [--out FILE.png]`: a PNG of
// the recorded histories of one or more runs (a run per CSV, named by its
// folder or --label), optionally against reference data with an error band;
// the axes carry the units summary.json gives the columns.
#include "plot_command.hpp"

#include "plot.hpp"

#include <plab_host/errors.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

namespace plab {

using json = nlohmann::json;

namespace {

struct Table {
    std::vector<std::string> names;
    std::vector<std::vector<double>> columns;
    std::vector<double> column(const std::string& name, const std::string& file) const {
        for (std::size_t c = 0; c < names.size(); ++c)
            if (names[c] == name) return columns[c];
        std::string known;
        for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
        throw InputError("command line", "no column \"" + name + "\" in " + file + "; columns: " + known);
    }
};

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    for (std::string item; std::getline(ss, item, sep);) out.push_back(item);
    return out;
}

Table read_csv(const std::string& path) {
    std::ifstream f(path);
    if (!f) throw InputError("command line", "cannot open " + path);
    Table t;
    std::string line;
    while (std::getline(f, line) && (line.empty() || line[0] == '#')) {}
    t.names = split(line, ',');
    for (auto& n : t.names) n.erase(std::remove_if(n.begin(), n.end(), [](char c) { return c == '\r' || c == '"'; }), n.end());
    t.columns.resize(t.names.size());
    while (std::getline(f, line)) {
        if (line.empty() || line[0] == '#') continue;
        const auto cells = split(line, ',');
        for (std::size_t c = 0; c < t.names.size(); ++c)
            t.columns[c].push_back(c < cells.size() ? std::strtod(cells[c].c_str(), nullptr) : std::nan(""));
    }
    return t;
}

// The units summary.json gives the history columns of the run beside the CSV.
std::map<std::string, std::string> column_units(const std::string& csv) {
    std::map<std::string, std::string> units;
    std::ifstream f(std::filesystem::path(csv).parent_path() / "summary.json");
    if (!f) return units;
    const json s = json::parse(f, nullptr, false);
    if (s.is_discarded() || !s.contains("history_units") || !s["history_units"].is_object()) return units;
    for (const auto& [k, v] : s["history_units"].items())
        if (v.is_string()) units[k] = v.get<std::string>();
    return units;
}

std::string with_unit(const std::string& name, const std::map<std::string, std::string>& units) {
    const auto it = units.find(name);
    return it == units.end() || it->second.empty() ? name : name + " [" + it->second + "]";
}

// A run's name for the legend: its folder (plab_out/RUN/history.csv), or the file's stem.
std::string run_label(const std::string& csv) {
    const std::filesystem::path p(csv);
    const std::string folder = p.parent_path().filename().string();
    return p.filename() == "history.csv" && !folder.empty() ? folder : p.stem().string();
}

struct PlotArgs {
    std::vector<std::string> csvs, labels;
    std::string x, ys, ref, ref_x, ref_y, title, x_label, y_label, out, log;
    double band = 0;
};

const char* plot_usage =
    "usage: plab plot HISTORY.csv... [--label A,B] [--x COL] [--y A,B] [--ref REF.csv --ref-y COL [--ref-x COL] "
    "[--band FRACTION]] [--title TEXT] [--xlabel TEXT] [--ylabel TEXT] [--log x|y|xy] [--out FILE.png]";

PlotArgs parse_plot_args(const std::vector<std::string>& args) {
    PlotArgs p;
    const std::map<std::string, std::string*> options = {
        {"--x", &p.x}, {"--y", &p.ys}, {"--ref", &p.ref}, {"--ref-x", &p.ref_x}, {"--ref-y", &p.ref_y},
        {"--title", &p.title}, {"--xlabel", &p.x_label}, {"--ylabel", &p.y_label}, {"--out", &p.out}, {"--log", &p.log}};
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        const bool has_value = i + 1 < args.size();
        if (options.count(a) && has_value) *options.at(a) = args[++i];
        else if (a == "--label" && has_value) p.labels = split(args[++i], ',');
        else if (a == "--band" && has_value) {
            const std::string v = args[++i];
            char* end = nullptr;
            p.band = std::strtod(v.c_str(), &end);
            if (v.empty() || *end || !(p.band >= 0 && p.band < 1))
                throw InputError("--band", "error band '" + v + "' is not a fraction in [0, 1)");
        } else if (a.rfind("--", 0) == 0) throw InputError("command line", std::string(plot_usage));
        else p.csvs.push_back(a);
    }
    if (p.csvs.empty()) throw InputError("command line", "plab plot needs a CSV file (e.g. a run's history.csv)");
    if (!p.labels.empty() && p.labels.size() != p.csvs.size())
        throw InputError("--label", std::to_string(p.labels.size()) + " labels for " + std::to_string(p.csvs.size()) +
                                        " CSV files: give one per file, in their order");
    if (!p.log.empty() && p.log != "x" && p.log != "y" && p.log != "xy")
        throw InputError("--log", "'" + p.log + "' is not one of: x, y, xy");
    if (p.band > 0 && p.ref.empty()) throw InputError("--band", "an error band goes around reference data: give --ref");
    return p;
}

} // namespace

int cmd_plot(const std::vector<std::string>& args) {
    const PlotArgs p = parse_plot_args(args);
    Plot plot;
    plot.log_x = p.log.find('x') != std::string::npos;
    plot.log_y = p.log.find('y') != std::string::npos;
    std::vector<std::string> y_names;
    std::string x = p.x;
    std::map<std::string, std::string> units;
    for (std::size_t k = 0; k < p.csvs.size(); ++k) {
        const std::string& csv = p.csvs[k];
        const Table t = read_csv(csv);
        if (t.names.empty()) throw InputError("command line", csv + " has no header line");
        if (x.empty()) x = t.names[0];
        if (k == 0) {
            y_names = p.ys.empty() ? std::vector<std::string>{} : split(p.ys, ',');
            if (y_names.empty())
                for (const auto& n : t.names)
                    if (n != x) y_names.push_back(n);
            units = column_units(csv);
        }
        const std::string run = p.labels.empty() ? run_label(csv) : p.labels[k];
        const std::vector<double> xv = t.column(x, csv);
        for (const auto& name : y_names)
            plot.curves.push_back({p.csvs.size() > 1 ? run + ": " + name : name, xv, t.column(name, csv), false, 0});
    }
    if (!p.ref.empty()) {
        const Table r = read_csv(p.ref);
        if (p.ref_y.empty()) throw InputError("--ref", "name the reference column with --ref-y");
        const std::string rx = p.ref_x.empty() ? r.names[0] : p.ref_x;
        plot.curves.push_back({std::filesystem::path(p.ref).stem().string() + ": " + p.ref_y, r.column(rx, p.ref),
                               r.column(p.ref_y, p.ref), true, p.band});
    }
    plot.x_label = p.x_label.empty() ? with_unit(x, units) : p.x_label;
    plot.y_label = !p.y_label.empty() ? p.y_label : y_names.size() == 1 ? with_unit(y_names[0], units) : "";
    if (plot.y_label.empty() && !y_names.empty()) {  // one unit for all the curves: say it
        std::string unit = units.count(y_names[0]) ? units[y_names[0]] : "";
        for (const auto& n : y_names) unit = units.count(n) && units[n] == unit ? unit : "";
        if (!unit.empty()) plot.y_label = "[" + unit + "]";
    }
    if (!p.title.empty()) plot.title = p.title;
    else {
        std::string runs;
        for (std::size_t k = 0; k < p.csvs.size(); ++k)
            runs += (k ? ", " : "") + (p.labels.empty() ? run_label(p.csvs[k]) : p.labels[k]);
        plot.title = runs;
    }
    std::string out = p.out;
    if (out.empty())
        out = (std::filesystem::path(p.csvs[0]).parent_path() / (std::filesystem::path(p.csvs[0]).stem().string() + ".png")).string();
    write_plot_png(plot, out);
    std::cout << "wrote " << out << "\n";
    return 0;
}

} // namespace plab
