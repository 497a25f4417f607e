// `plab plot HISTORY.csv [--x COL] [--y A,B,...] [--ref REF.csv --ref-y COL
// [--ref-x COL] [--band FRACTION]] [--title TEXT] [--out FILE.png]`: a PNG of
// recorded histories, optionally against reference data with an error band.
#include "plot_command.hpp"

#include "plot.hpp"

#include <plab_core/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace plab {

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

} // namespace

int cmd_plot(const std::vector<std::string>& args) {
    std::string csv, x, ys, ref, ref_x, ref_y, title, out;
    double band = 0;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        const bool has_value = i + 1 < args.size();
        if (a == "--x" && has_value) x = args[++i];
        else if (a == "--y" && has_value) ys = args[++i];
        else if (a == "--ref" && has_value) ref = args[++i];
        else if (a == "--ref-x" && has_value) ref_x = args[++i];
        else if (a == "--ref-y" && has_value) ref_y = args[++i];
        else if (a == "--band" && has_value) band = std::strtod(args[++i].c_str(), nullptr);
        else if (a == "--title" && has_value) title = args[++i];
        else if (a == "--out" && has_value) out = args[++i];
        else if (a.rfind("--", 0) == 0 || !csv.empty())
            throw InputError("command line", "usage: plab plot HISTORY.csv [--x COL] [--y A,B] [--ref REF.csv --ref-y COL "
                                             "[--ref-x COL] [--band FRACTION]] [--title TEXT] [--out FILE.png]");
        else csv = a;
    }
    if (csv.empty()) throw InputError("command line", "plab plot needs a CSV file (e.g. a run's history.csv)");
    if (!(band >= 0 && band < 1)) throw InputError("--band", "error band " + std::to_string(band) + " is outside [0, 1)");
    const Table t = read_csv(csv);
    if (t.names.empty()) throw InputError("command line", csv + " has no header line");
    if (x.empty()) x = t.names[0];
    std::vector<std::string> y_names = ys.empty() ? std::vector<std::string>{} : split(ys, ',');
    if (y_names.empty())
        for (const auto& n : t.names)
            if (n != x) y_names.push_back(n);
    Plot plot;
    plot.title = title.empty() ? std::filesystem::path(csv).string() : title;
    plot.x_label = x;
    plot.y_label = y_names.size() == 1 ? y_names[0] : "";
    const std::vector<double> xv = t.column(x, csv);
    for (const auto& name : y_names) plot.curves.push_back({name, xv, t.column(name, csv), false, 0});
    if (!ref.empty()) {
        const Table r = read_csv(ref);
        if (ref_y.empty()) throw InputError("--ref", "name the reference column with --ref-y");
        const std::string rx = ref_x.empty() ? r.names[0] : ref_x;
        plot.curves.push_back({std::filesystem::path(ref).stem().string() + ": " + ref_y, r.column(rx, ref),
                               r.column(ref_y, ref), true, band});
    }
    if (out.empty()) out = (std::filesystem::path(csv).parent_path() / (std::filesystem::path(csv).stem().string() + ".png")).string();
    write_plot_png(plot, out);
    std::cout << "wrote " << out << "\n";
    return 0;
}

} // namespace plab
