// Outputs of a run: history CSV, the VTK series (.pvd of .vtp frames,
// vtk_output.cpp) and the run summary JSON. Every file is written
// to a temporary name and renamed, so a killed run never leaves half a file
// — but for history.csv, to which a running run appends its rows (see
// flush_history()).
#include "simulation.hpp"
#include "vtk_output.hpp"

#include "materials.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include <fcntl.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace plab {

namespace {

void write_atomically(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    const fs::path tmp = path.string() + ".tmp";
    {
        std::ofstream f(tmp, std::ios::binary);
        f << text;
        if (!f) throw std::runtime_error("cannot write " + tmp.string());
    }
    fs::rename(tmp, path);
}

// One write(2) of `text` at the end of `path`: a run killed now leaves the
// lines written before it whole.
void append_to(const fs::path& path, const std::string& text) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
    const ssize_t n = fd < 0 ? -1 : ::write(fd, text.data(), text.size());
    if (fd >= 0) ::close(fd);
    if (n != ssize_t(text.size())) throw std::runtime_error("cannot append to " + path.string());
}

std::string csv_rows(const std::vector<std::vector<double>>& rows, std::size_t from) {
    std::ostringstream csv;
    csv << std::setprecision(12);
    for (std::size_t r = from; r < rows.size(); ++r) {
        for (std::size_t c = 0; c < rows[r].size(); ++c) csv << (c ? "," : "") << rows[r][c];
        csv << "\n";
    }
    return csv.str();
}

// Every broken bond: when, where, between which balls, and how.
std::string bond_breaks_csv(const World& w) {
    std::ostringstream csv;
    csv << std::setprecision(12) << "step,time,id1,id2,x,y,z,mode\n";
    for (const BondBreak& b : w.bond_breaks)
        csv << b.step << ',' << b.time << ',' << b.id1 << ',' << b.id2 << ',' << b.point.x() << ',' << b.point.y() << ','
            << b.point.z() << ',' << (b.mode == PLAB_BREAK_TENSION ? "tension" : "shear") << "\n";
    return csv.str();
}

// What makes a model expensive (issue 7): its contacts, the neighbours per
// body, and the stable step its contacts allow on their own (one contact:
// sqrt(m/k) of the lighter end, or the model's direct step limit).
json cost_drivers(const ModelView& inst, const Bodies& B) {
    const std::size_t bodies = B.size();
    std::size_t active = 0, ball_active = 0;
    double stable = kInf;
    for (const ContactTable& s : {inst.balls(), inst.walls()})
        for (std::size_t k = 0; k < s.size(); ++k) {
            if (!s.active(k)) continue;
            ++active;
            ball_active += !s.with_wall();
            // a wall's mass is infinite
            const double m = s.with_wall() ? B.mass[s.end1(k)] : std::min(B.mass[s.end1(k)], B.mass[s.end2(k)]);
            if (s.stiffness(k) > 0) stable = std::min(stable, std::sqrt(m / s.stiffness(k)));
            stable = std::min(stable, s.dt_limit(k));
        }
    json j = {{"model", inst.model()},
              {"candidate_pairs", inst.balls().size() + inst.walls().size()},
              {"active_contacts", active},
              {"neighbours_per_body", bodies ? 2.0 * double(ball_active) / double(bodies) : 0.0}};
    if (stable < kInf) j["stable_dt"] = stable;
    else j["stable_dt"] = nullptr;
    return j;
}

} // namespace

void Simulation::write_vtk_snapshot() {
    const fs::path dir(out_dir_);
    char name[32];
    std::snprintf(name, sizeof name, "%05d", vtk_frames_++);
    std::vector<std::string> parts = {"balls"};
    if (vtk_.any_contacts()) parts.push_back("contacts");
    if (vtk_.walls) parts.push_back("walls");
    if (vtk_.bodies && world_->clumps.size() > 0) parts.push_back("bodies");
    for (const std::string& part : parts) {
        const std::string text = part == "balls"    ? balls_vtp(*world_, vtk_)
                                 : part == "walls"  ? walls_vtp(*world_, vtk_)
                                 : part == "bodies" ? bodies_vtp(*world_, vtk_)
                                                    : contacts_vtp(*world_, vtk_);
        write_atomically(dir / "vtk" / (part + "_" + name + ".vtp"), text);
    }
    vtk_series_.emplace_back(world_->time, name);
    std::ostringstream pvd;
    pvd << std::setprecision(12) << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
    for (const auto& [t, n] : vtk_series_)
        for (std::size_t p = 0; p < parts.size(); ++p)
            pvd << "<DataSet timestep=\"" << t << "\" part=\"" << p << "\" file=\"vtk/" << parts[p] << "_" << n << ".vtp\"/>\n";
    pvd << "</Collection>\n</VTKFile>\n";
    write_atomically(dir / "series.pvd", pvd.str());
}

json Simulation::summary() const {
    const World& w = *world_;
    json s;
    s["finished"] = finished_;  // false in the summaries written at checkpoints
    s["dimension"] = w.dim;
    s["bodies"] = w.bodies.size();
    s["steps"] = w.step_count;
    s["simulated_time"] = w.time;
    s["wall_seconds"] = run_.wall_seconds;
    s["cpu_seconds"] = run_.cpu_seconds;
    s["particle_steps_per_second"] = run_.particle_steps_per_second;
    s["contacts"] = active_contacts(w);
    s["neighbour_rebuilds"] = rebuilds(w);
    const StableStep st = stable_timestep(w);
    s["timestep"] = {{"mode", w.fixed_dt > 0 ? "fixed" : "automatic"},
                     {"last_dt", w.last_dt},
                     {"critical", st.critical},
                     {"limited_by", st.limited_by},
                     {"safety_factor", w.safety_factor}};
    if (!timestep_note_.empty()) s["timestep"]["note"] = timestep_note_;
    if (!materials_->speed_of_sound_report().empty()) s["speed_of_sound"] = materials_->speed_of_sound_report();
    if (!structures_.empty()) s["structures"] = structures_;
    const Energies& e = w.energies;
    s["energies"] = {{"kinetic", e.kinetic}, {"strain", e.strain}, {"body_work", e.body},
                     {"boundary_work", e.boundary}, {"slip", e.slip}, {"dashpot", e.dashpot},
                     {"local_damping", e.local_damping}, {"bond_break", e.bond_break}, {"balance", e.balance()}};
    s["bonds"] = {{"intact", intact_bonds(w)}, {"broken", w.bond_breaks.size()}};
    json phases;
    for (int p = 0; p < ph_count; ++p) phases[phase_names[p]] = w.phase_seconds[p];
    s["phase_seconds"] = phases;
    json models = json::array();
    for (std::size_t m = 0; m < w.model_count(); ++m) models.push_back(cost_drivers(w.model(m), w.bodies));
    s["models"] = models;
    if (!w.stopped.quantity.empty()) {
        const Diagnostic& d = w.stopped;
        s["stopped"] = {{"quantity", d.quantity}, {"subject", d.subject}, {"step", d.step}, {"time", d.time},
                        {"detail", d.detail}, {"likely_cause", d.cause}, {"last_good_step", w.step_count},
                        {"message", d.message()}};
    }
    if (!metrics_.is_null()) s["metrics"] = metrics_;
    if (!history_cols_.empty()) {
        json units = json::object();  // plab plot labels its axes with these
        for (const auto& c : history_cols_) units[c.name] = c.unit;
        s["history_units"] = units;
    }
    std::ostringstream hash;
    hash << std::hex << state_hash(w);
    s["state_hash"] = hash.str();
    return s;
}

// The rows not yet in history.csv are appended to it; the file is written
// whole when it does not hold this run's rows (a new run or output folder,
// a restart, rows cleared by a `histories` command).
void Simulation::flush_history() {
    history_flushed_ = std::chrono::steady_clock::now();
    if (out_dir_.empty() || history_cols_.empty()) return;
    const fs::path path = fs::path(out_dir_) / "history.csv";
    if (history_stale_ || history_on_disk_ > history_rows_.size()) {
        std::string header;
        for (std::size_t c = 0; c < history_cols_.size(); ++c) header += (c ? "," : "") + history_cols_[c].name;
        write_atomically(path, header + "\n" + csv_rows(history_rows_, 0));
        history_stale_ = false;
    } else if (history_on_disk_ < history_rows_.size()) {
        append_to(path, csv_rows(history_rows_, history_on_disk_));
    }
    history_on_disk_ = history_rows_.size();
}

bool Simulation::history_flush_due() const {
    return std::chrono::steady_clock::now() - history_flushed_ >= kHistoryFlushInterval;
}

// The break log and the summary; a run writes them at each checkpoint and
// when it ends (history.csv: flush_history()).
void Simulation::write_outputs() const {
    const fs::path dir(out_dir_);
    if (!world_->bond_breaks.empty() || intact_bonds(*world_) > 0)
        write_atomically(dir / "bond_breaks.csv", bond_breaks_csv(*world_));
    write_atomically(dir / "summary.json", summary().dump(2) + "\n");
}

// A run killed while writing a file leaves its temporary copy; the next run
// into the folder removes those of the files it writes.
void Simulation::remove_stale_temporaries() const {
    if (out_dir_.empty()) return;
    const fs::path dir(out_dir_);
    std::vector<fs::path> stale;
    for (const char* name : {"checkpoint.plab", "last_good.plab", "history.csv", "summary.json", "bond_breaks.csv", "series.pvd", "watch.png"})
        if (fs::exists(dir / (std::string(name) + ".tmp"))) stale.push_back(dir / (std::string(name) + ".tmp"));
    for (const auto& [sub, ext] : {std::pair<const char*, const char*>{"vtk", ".vtp.tmp"}, {"png", ".png.tmp"}}) {
        std::error_code ec;
        for (fs::directory_iterator it(dir / sub, ec), end; !ec && it != end; it.increment(ec)) {
            const std::string name = it->path().filename().string();
            if (name.size() > std::strlen(ext) && name.compare(name.size() - std::strlen(ext), std::string::npos, ext) == 0)
                stale.push_back(it->path());
        }
    }
    for (const auto& p : stale) {
        std::error_code ec;
        fs::remove(p, ec);
        if (!quiet_) spdlog::info("removed {}, left by a run killed while writing it", p.string());
    }
}

void apply_override(json& scene, const std::string& assignment) {
    const auto eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0)
        throw InputError("--set " + assignment, "expected PATH=VALUE, e.g. contact_models.0.properties.kn=1e6");
    const std::string path = assignment.substr(0, eq), text = assignment.substr(eq + 1);
    json value = json::parse(text, nullptr, false);
    if (value.is_discarded()) value = text;
    json* node = &scene;
    std::string walked = "scene";
    std::stringstream ss(path);
    std::string key;
    std::vector<std::string> keys;
    while (std::getline(ss, key, '.')) keys.push_back(key);
    if (path.find_first_of("[]") != std::string::npos) {  // a JSONPath habit: a[0] would be made a key "a[0]"
        std::string dotted;
        for (char ch : path) dotted += ch == '[' ? '.' : ch == ']' ? '\0' : ch;
        dotted.erase(std::remove(dotted.begin(), dotted.end(), '\0'), dotted.end());
        throw InputError("--set " + assignment, "PATH takes array indices as dot-separated numbers: " + dotted + "=" + text);
    }
    for (std::size_t i = 0; i < keys.size(); ++i) {
        const bool last = i + 1 == keys.size();
        const std::string& k = keys[i];
        if (node->is_array()) {
            char* end = nullptr;
            const long idx = std::strtol(k.c_str(), &end, 10);
            // strtol reads "" as 0: an empty segment ("a..b") must not mean index 0
            if (k.empty() || *end || idx < 0 || std::size_t(idx) >= node->size())
                throw InputError(walked + "." + k, "--set " + path + ": index \"" + k + "\" is not within [0, " +
                                                       std::to_string(node->size()) + ")");
            node = &(*node)[std::size_t(idx)];
        } else if (node->is_object()) {
            // a missing key is made (an object on the way), as the loader then
            // refuses any key it does not know, by its path
            if (!node->contains(k) && !last) (*node)[k] = json::object();
            node = &(*node)[k];
        } else {
            throw InputError(walked, "--set " + path + ": cannot descend into " + show(*node));
        }
        walked += "." + k;
    }
    *node = value;
}

} // namespace plab
