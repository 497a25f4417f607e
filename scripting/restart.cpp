// Checkpoint and restart of a whole run (docs/restart.md): the plug-ins it
// needs, the scene it was started from, the world's state
// (core/src/io/checkpoint.cpp), the command sequence with the progress of the
// current command, and the output counters. A restart rebuilds the scene's
// structure (plug-ins, groups, model instances, passes, commands) from the
// stored scene with any --set applied, then replaces the state by the file's.
#include "simulation.hpp"

#include <plab_host/checkpoint.hpp>

#include <csignal>
#include <filesystem>
#include <sstream>

#include <spdlog/spdlog.h>

namespace fs = std::filesystem;

namespace plab {

namespace {

volatile std::sig_atomic_t g_stop_signal = 0;

extern "C" void on_stop_signal(int sig) { g_stop_signal = sig; }

// The plug-in libraries a run used: scene name, file, ABI version, and what
// the world takes from each (so a missing one is named with its purpose).
struct PluginUse {
    std::string name, file;
    std::uint32_t abi = 0;
    std::string provides;
};

std::vector<PluginUse> plugins_used(const json& scene, const std::string& scene_dir, const PluginHost& host,
                                    const World& w) {
    std::vector<PluginUse> out;
    if (!scene.contains("plugins")) return out;
    for (const auto& p : scene["plugins"]) {
        PluginUse u;
        u.name = p.get<std::string>();
        u.file = host.resolve(u.name, scene_dir);
        u.abi = PLAB_ABI_VERSION;  // this plab's (it loads no newer minor and no other major)
        for (const auto& lib : host.libraries())
            if (fs::equivalent(lib.path, u.file)) {
                for (const auto& m : lib.models) u.provides += (u.provides.empty() ? "" : ", ") + ("model " + m);
                for (const auto& q : lib.passes) u.provides += (u.provides.empty() ? "" : ", ") + ("pass " + q);
            }
        out.push_back(u);
    }
    (void)w;
    return out;
}

// A plug-in ABI version as people say it: "2.0"; "1 (version 7)" for ABI 1,
// which numbered its versions 1 to 7 (abi.h).
std::string abi_text(std::uint32_t v) {
    if (v >> 16 == 0) return "1 (version " + std::to_string(v) + ")";
    return std::to_string(v >> 16) + "." + std::to_string(v & 0xffffu);
}

// Loads every plug-in the checkpoint names, or says which one is missing
// and what the saved state needs it for.
void load_plugins_of(CheckpointReader& in, PluginHost& host, const std::string& scene_dir) {
    in.section("plugins");
    const std::uint64_t n = in.u64();
    for (std::uint64_t i = 0; i < n; ++i) {
        PluginUse u;
        u.name = in.str();
        u.file = in.str();
        u.abi = in.u32();
        u.provides = in.str();
        const std::string what = "plug-in '" + u.name + "' (" + (u.provides.empty() ? "no models" : u.provides) +
                                 "; written with " + u.file + ", plug-in ABI " + abi_text(u.abi) + ")";
        // (as the host loads plug-ins: the same major version, a minor no
        // newer than this plab's, whose additions change no checkpoint)
        if (u.abi >> 16 != PLAB_ABI_MAJOR || (u.abi & 0xffffu) > PLAB_ABI_MINOR)
            in.fail("it needs " + what + " but this plab speaks plug-in ABI " + abi_text(PLAB_ABI_VERSION));
        std::string file;
        try {
            file = host.resolve(u.name, scene_dir);
        } catch (const PluginError& e) {
            in.fail("it needs " + what + ", which is not found now: " + e.what());
        }
        try {
            host.load(file);
        } catch (const PluginError& e) {
            in.fail("it needs " + what + ", which does not load now: " + e.what());
        }
    }
}

// ---- --set on restart ------------------------------------------------------

const char* const kChangeableOnRestart =
    "timestep.*, gravity, contact_models.N.properties, contact_models.N.calibrate, contact_models.N.max_overlap, "
    "passes.N.properties, stability.*, domain, histories.*, output.*, metrics.*, description, and the commands "
    "the run has not begun";

// The keys of a --set PATH=VALUE (apply_override has checked it).
std::vector<std::string> set_keys(const std::string& assignment) {
    std::vector<std::string> keys;
    std::stringstream ss(assignment.substr(0, assignment.find('=')));
    for (std::string k; std::getline(ss, k, '.');) keys.push_back(k);
    return keys;
}

std::string set_path(const std::vector<std::string>& keys) {
    std::string path = "scene";
    for (const auto& k : keys) path += "." + k;
    return path;
}

// Why a --set of `keys` would not take effect on restart (the state it
// changes is restored from the checkpoint), or "" when it does. Commands
// are judged once the checkpoint says which one the run is in.
std::string restored_instead(const std::vector<std::string>& keys) {
    const std::string& top = keys[0];
    for (const char* free : {"timestep", "gravity", "stability", "domain", "histories", "output", "metrics", "description",
                             "validation"})
        if (top == free) return "";
    const std::string second = keys.size() > 2 ? keys[2] : "";
    if (top == "contact_models") {
        if (second == "properties" || second == "calibrate" || second == "max_overlap") return "";
        return "the contact-model assignment is restored from the checkpoint";
    }
    if (top == "passes") return second == "properties" ? "" : "the passes are restored from the checkpoint";
    if (top == "commands") return keys.size() > 1 ? "" : "the run's list of commands is restored from the checkpoint";
    if (top == "bodies") return "the bodies are restored from the checkpoint";
    if (top == "walls") return "the walls are restored from the checkpoint";
    if (top == "plugins") return "the plug-ins are the checkpoint's";
    if (top == "dimension") return "the state restored from the checkpoint has its dimension";
    if (top == "materials") return "the bodies' masses are restored from the checkpoint; set the properties a material fills instead";
    if (top == "variables") return "the stored scene has its variables substituted; set the paths that use them instead";
    if (top == "skin") return "the neighbour lists are restored from the checkpoint, built with the skin it ran with";
    return "";  // not a scene key: the loader names it
}

void refuse_on_restart(const std::vector<std::string>& keys, const std::string& why) {
    throw InputError(set_path(keys), "cannot be changed on restart (" + why + "); changeable on restart: " +
                                         kChangeableOnRestart);
}

bool sets_gravity(const std::vector<std::string>& sets) {
    for (const auto& s : sets)
        if (set_keys(s)[0] == "gravity") return true;
    return false;
}

// A --set of output.dir (or of the whole output, with a dir) moves the
// outputs; else they go where the run wrote them.
bool sets_output_dir(const std::vector<std::string>& sets, const json& scene) {
    for (const auto& s : sets) {
        const auto keys = set_keys(s);
        if (keys == std::vector<std::string>{"output", "dir"}) return true;
        if (keys == std::vector<std::string>{"output"} && scene["output"].contains("dir")) return true;
    }
    return false;
}

} // namespace

// SIGHUP too: a closed terminal or a dropped ssh session stops the run as
// SIGTERM does, with its checkpoint, instead of killing it with nothing saved
void install_stop_handlers() {
    std::signal(SIGINT, on_stop_signal);
    std::signal(SIGTERM, on_stop_signal);
    std::signal(SIGHUP, on_stop_signal);
}
int stop_signal() { return g_stop_signal; }
void request_stop(int signal) { g_stop_signal = signal; }
void clear_stop() { g_stop_signal = 0; }

std::string Simulation::checkpoint_path() const { return (fs::path(out_dir_) / "checkpoint.plab").string(); }

void Simulation::set_checkpoint_every(double seconds) {
    checkpoint_every_ = seconds;
    next_checkpoint_time_ = world_->time + seconds;
}

void Simulation::save_checkpoint(const std::string& path) const { write_checkpoint(path, run_state_bytes()); }

// A checkpoint file: plug-ins and scene, the world as it is now, and the
// run's own sections given as bytes (now, or kept from the last good state).
void Simulation::write_checkpoint(const std::string& path, const std::string& run_state) const {
    CheckpointWriter out = CheckpointWriter::to_file(path);
    write_plugins_and_scene(out);
    save_world(*world_, out);
    out.append(run_state);
    out.commit();
}

std::string Simulation::run_state_bytes() const {
    CheckpointWriter out;
    write_run_state(out);
    return out.take();
}

std::string Simulation::last_good_path() const { return (fs::path(out_dir_) / "last_good.plab").string(); }

// The run's last good state is the world's own snapshot (World::step()
// restores it when a step fails); beside it the run keeps, at the instant
// the world takes it, the small part of a checkpoint that is its own
// (commands' progress, outputs). When the run goes unstable the checkpoint
// is written from the restored world and that part: no second copy of the
// world is held in memory.
void Simulation::keep_last_good() {
    if (out_dir_.empty() || world_->snapshot_interval == 0) return;
    last_good_run_state_ = run_state_bytes();
}

std::string Simulation::write_last_good() const {
    if (!at_last_good(*world_) || last_good_run_state_.empty()) return "";
    write_checkpoint(last_good_path(), last_good_run_state_);
    return last_good_path();
}

void Simulation::write_plugins_and_scene(CheckpointWriter& out) const {
    const auto used = plugins_used(scene_, scene_dir_, *host_, *world_);
    out.section("plugins");
    out.u64(used.size());
    for (const PluginUse& u : used) {
        out.str(u.name);
        out.str(u.file);
        out.u32(u.abi);
        out.str(u.provides);
    }
    out.section("scene");
    out.str(scene_dir_);
    out.str(out_dir_);
    out.str(scene_.dump());
}

void Simulation::write_run_state(CheckpointWriter& out) const {
    out.section("commands");
    out.u64(commands_.size());
    out.u64(next_command_);
    out.u8(command_started_);
    out.u64(command_start_step_);
    out.f64(command_end_time_);
    out.u64(command_breaks_before_);

    out.section("outputs");
    out.u64(history_cols_.size());
    for (const auto& c : history_cols_) out.str(c.name);
    out.u64(history_rows_.size());
    for (const auto& row : history_rows_) out.column(row);
    out.u64(std::uint64_t(vtk_frames_));
    out.f64(next_vtk_time_);
    out.u64(vtk_series_.size());
    for (const auto& [t, name] : vtk_series_) {
        out.f64(t);
        out.str(name);
    }
    out.u64(std::uint64_t(png_frames_));
    out.f64(next_png_time_);
    out.f64(checkpoint_every_);
    out.f64(next_checkpoint_time_);
    flows_.save(out);
    out.section("end");
}

std::unique_ptr<Simulation> Simulation::restart(const std::string& path, const std::vector<std::string>& sets,
                                                std::shared_ptr<PluginHost> host) {
    if (!host) host = std::make_shared<PluginHost>();
    CheckpointReader in(path);
    // the scene section comes after the plug-ins: read ahead for its folder
    // (relative plug-in paths resolve against it)
    CheckpointReader ahead(path);
    ahead.section("plugins");
    for (std::uint64_t n = ahead.u64(), i = 0; i < n; ++i) { ahead.str(); ahead.str(); ahead.u32(); ahead.str(); }
    ahead.section("scene");
    const std::string scene_dir = ahead.str();
    load_plugins_of(in, *host, scene_dir);

    in.section("scene");
    in.str();
    const std::string out_dir = in.str();
    json scene;
    try {
        scene = json::parse(in.str());
    } catch (const json::exception& e) {
        in.fail(std::string("the stored scene does not parse: ") + e.what());
    }
    for (const auto& s : sets) {
        apply_override(scene, s);
        if (const std::string why = restored_instead(set_keys(s)); !why.empty()) refuse_on_restart(set_keys(s), why);
    }
    auto sim = std::make_unique<Simulation>(scene, scene_dir, host);
    if (!sets_output_dir(sets, scene)) sim->out_dir_ = out_dir;
    const Vec gravity = sim->world().gravity;  // the scene's, with any --set

    load_world(sim->world(), in);
    if (sets_gravity(sets)) {  // from this step on, as a set command would
        sim->world().gravity = gravity;
        sim->world().mark_dirty();
    }
    sim->load_run_state(in);
    sim->check_command_sets(sets);
    for (const auto& s : sets) {
        const std::size_t eq = s.find('=');
        json value = json::parse(s.substr(eq + 1), nullptr, false);
        if (value.is_discarded()) value = s.substr(eq + 1);
        sim->restart_log_.push_back("restart: set " + s.substr(0, eq) + " = " + value.dump());
    }
    sim->resumed_ = true;
    return sim;
}

// The commands up to the one the run is in have been run (or are running):
// a --set of them would change nothing.
void Simulation::check_command_sets(const std::vector<std::string>& sets) const {
    const std::size_t first = next_command_ + (command_started_ ? 1 : 0);
    for (const auto& s : sets) {
        const auto keys = set_keys(s);
        if (keys[0] != "commands") continue;
        const std::size_t k = std::stoul(keys[1]);
        if (k >= first) continue;
        refuse_on_restart(keys, std::string(k < next_command_ ? "the run has done this command" : "the run is in this command") +
                                    (first < commands_.size() ? "; commands." + std::to_string(first) + " on can change"
                                                              : "; no command is left to change"));
    }
}

// The run's own sections: the progress of its commands and its outputs.
void Simulation::load_run_state(CheckpointReader& in) {
    in.section("commands");
    if (in.u64() != commands_.size())
        in.fail("the scene now has " + std::to_string(commands_.size()) +
                " commands, the run had a different number (a --set changed the command list?)");
    next_command_ = in.u64();
    command_started_ = in.u8() != 0;
    command_start_step_ = in.u64();
    command_end_time_ = in.f64();
    command_breaks_before_ = in.u64();
    if (next_command_ > commands_.size()) in.fail("the next command is past the end of the list");
    for (std::size_t k = 0; k < next_command_; ++k)
        if (commands_[k].replayed_on_restart) commands_[k].apply(*world_);

    in.section("outputs");
    std::vector<std::string> columns(in.u64());
    for (auto& c : columns) c = in.str();
    std::vector<std::string> now;
    for (const auto& c : history_cols_) now.push_back(c.name);
    const std::uint64_t n_rows = in.u64();
    std::vector<std::vector<double>> rows;
    for (std::uint64_t r = 0; r < n_rows; ++r) rows.push_back(in.column<double>());
    if (columns == now) history_rows_ = std::move(rows);
    else if (!columns.empty()) restart_log_.push_back("restart: the history columns differ from the checkpoint's: the rows start anew");
    vtk_frames_ = int(in.u64());
    next_vtk_time_ = in.f64();
    vtk_series_.resize(in.u64());
    for (auto& [t, name] : vtk_series_) {
        t = in.f64();
        name = in.str();
    }
    png_frames_ = int(in.u64());
    next_png_time_ = in.f64();
    checkpoint_every_ = in.f64();
    next_checkpoint_time_ = in.f64();
    if (in.format() >= 5) flows_.load(in);  // (format 4: no inlets or outlets)
    else if (!flows_.empty()) in.fail("the scene has inlets or outlets, which a checkpoint of format 4 does not keep");
    in.section("end");
    in.finish();
}

} // namespace plab
