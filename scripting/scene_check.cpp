// `plab check SCENE.json`: what a scene will do, without running it — its
// groups and bodies, which model acts between which groups, the timestep
// and what limits it, the length of each command, the outputs and their
// size on disk.
#include "simulation.hpp"
#include "generators.hpp"

#include "materials.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

namespace plab {

namespace {

// Bytes of one ball in one ASCII VTK frame (positions, velocities, radius,
// id, group, fields: ~0.2 MB per 1000 balls, issue 35's measurement).
constexpr double kVtkBytesPerBall = 200;

std::string megabytes(double bytes) {
    char s[32];
    std::snprintf(s, sizeof s, bytes < 1e6 ? "%.2g MB" : "%.0f MB", bytes / 1e6);
    return s;
}

void print_groups(std::ostream& out, const World& w) {
    struct Tally { std::size_t count = 0; double r_min = kInf, r_max = 0, mass = 0; };
    std::map<int, Tally> by_group;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        Tally& t = by_group[w.bodies.group[i]];
        ++t.count;
        t.r_min = std::min(t.r_min, w.bodies.radius[i]);
        t.r_max = std::max(t.r_max, w.bodies.radius[i]);
        t.mass += w.bodies.mass[i];
    }
    out << "bodies: " << w.bodies.size() << " balls\n";
    for (const auto& [g, t] : by_group)
        out << "  group " << w.group_names()[std::size_t(g)] << ": " << t.count << " balls, radius " << short_number(t.r_min)
            << (t.r_max > t.r_min ? "-" + short_number(t.r_max) : "") << " m, mass " << short_number(t.mass) << " kg\n";
    out << "walls: " << w.walls.walls.size() << " (" << w.walls.facets.size() << " facets)\n";
}

void print_contact_models(std::ostream& out, const World& w) {
    out << "contact models (group pair: model and properties):\n";
    const std::size_t n = w.group_names().size();
    std::vector<bool> has_balls(n, false);
    for (std::size_t i = 0; i < w.bodies.size(); ++i) has_balls[std::size_t(w.bodies.group[i])] = true;
    for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = a; b < n; ++b) {
            const int k = w.assigned(int(a), int(b));
            if (k < 0 || !(has_balls[a] || has_balls[b])) continue;  // (walls never touch walls)
            const ModelView m = w.model(std::size_t(k));
            const std::vector<double>& props = m.properties();
            out << "  " << w.group_names()[a] << " - " << w.group_names()[b] << ": " << m.model();
            for (std::size_t p = 0; p < props.size(); ++p)
                out << (p ? ", " : " (") << m.desc().properties[p].key << " "
                    << property_value_text(m.desc().properties[p], props[p], w.group_names()) << (p + 1 == props.size() ? ")" : "");
            out << "\n";
        }
}

// Each material's speed of sound and what set it (materials.hpp).
void print_speed_of_sound(std::ostream& out, const json& report) {
    for (const json& e : report) {
        out << "speed of sound: material " << e["material"].get<std::string>() << " c0 = "
            << short_number(e["speed_of_sound"].get<double>()) << " m/s (" << e["rule"].get<std::string>();
        if (e.contains("from"))
            out << "; expected max speed " << e["from"].get<std::string>() << "; c0 = "
                << short_number(e["mach_factor"].get<double>()) << " x it";
        out << ")\n";
    }
}

} // namespace

void Simulation::check_report(std::ostream& out) {
    World& w = *world_;
    out << "dimension: " << w.dim << "D, gravity " << short_number(w.gravity.norm()) << " m/s2\n";
    print_groups(out, w);
    print_contact_models(out, w);
    print_speed_of_sound(out, materials_->speed_of_sound_report());
    const auto [dt, set_by] = planned_timestep();
    out << "timestep: " << short_number(dt) << " s (" << set_by << ")\n";
    double steps = 0, time = 0;
    out << "commands:\n";
    for (const Command& c : commands_) {
        out << "  " << c.path << ": ";
        if (c.kind == Command::cycle) { out << long(c.value) << " steps\n"; steps += c.value; time += c.value * dt; }
        else if (c.kind == Command::solve_time) {
            out << "solve for " << short_number(c.value) << " s, about " << short_number(c.value / dt) << " steps"
                << (c.stop_on_bond_break ? " (or until the first bond breaks)" : "") << "\n";
            steps += c.value / dt;
            time += c.value;
        } else if (c.kind == Command::solve_ratio) out << "solve to ratio " << short_number(c.value) << ", at most " << c.max_cycles << " steps\n";
        else out << "a change of state or an output\n";
    }
    out << "  in all: about " << short_number(steps) << " steps to t = " << short_number(time) << " s (ratio solves not counted)\n";
    out << "outputs" << (out_dir_.empty() ? " (no folder: none written)" : " in " + out_dir_) << ":\n";
    if (!history_cols_.empty() && history_every_ > 0)
        out << "  history.csv: " << history_cols_.size() << " columns every " << history_every_ << " steps, about "
            << short_number(steps / double(history_every_) + 1) << " rows\n";
    if (vtk_.interval > 0) {
        const double frames = time / vtk_.interval + 1;
        out << "  VTK every " << short_number(vtk_.interval) << " s: about " << short_number(frames) << " frames, "
            << megabytes(frames * double(w.bodies.size()) * kVtkBytesPerBall) << " of balls\n";
    }
    if (png_interval_ > 0)
        out << "  PNG every " << short_number(png_interval_) << " s: about " << short_number(time / png_interval_ + 1) << " frames\n";
}

} // namespace plab
