// A JSON scene turned into a World and a command sequence, and run.
// The scene format is documented in docs/scene-format.md.
#pragma once

#include "body_flows.hpp"
#include "generators.hpp"
#include "json_reader.hpp"
#include "pictures.hpp"
#include "progress.hpp"
#include "servo.hpp"
#include "vtk_output.hpp"

#include <plab_host/world.hpp>

#include <chrono>
#include <ctime>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace plab {

class Materials;
class CheckpointReader;
class CheckpointWriter;

// Applies "a.b.0.c=value" to a scene: the value is read as JSON when it
// parses (numbers, arrays, true/false), else as a string. The path must
// exist up to its last key (a typo is an error, not a new key).
void apply_override(json& scene, const std::string& assignment);
// A scene file: a regular file below PLAB_MAX_SCENE_BYTES (256 MiB), JSON
// nested at most 64 deep; errors name the file and the JSON path.
json read_scene_file(const std::string& path);
json parse_scene_text(const std::string& text, const std::string& name);

struct HistoryColumn {
    std::string name;
    std::string unit;  // quantity_unit(); "" for an expression
    std::function<double(const World&)> sample;
    // set for a column computed from the row's earlier columns ("expression")
    std::function<double(const std::vector<double>& row)> derive;
};

struct Command {
    enum Kind { cycle, solve_time, solve_ratio, set, output } kind;
    std::string path;  // for messages
    double value = 0;  // cycles, time, or ratio
    long max_cycles = 0;
    bool stop_on_bond_break = false;  // solve: stop after the step in which the first bond breaks
    std::function<void(World&)> apply;  // for `set`
    bool replayed_on_restart = false;    // a `set` that changes the run's own state (a servo), not the world's
};

struct RunSummary {
    std::uint64_t steps = 0;
    double simulated_time = 0, wall_seconds = 0, cpu_seconds = 0;
    double particle_steps_per_second = 0;
};

class Simulation {
public:
    // `scene_dir` resolves relative plug-in paths; `host` may be shared
    // between simulations (libraries stay loaded).
    Simulation(const json& scene, const std::string& scene_dir = ".", std::shared_ptr<PluginHost> host = nullptr);
    ~Simulation();

    World& world() { return *world_; }
    const World& world() const { return *world_; }
    const json& scene() const { return scene_; }

    // Output folder; empty: write nothing (tests).
    void set_output_dir(const std::string& dir) {
        out_dir_ = dir;
        out_dir_from_ = "--out";
        history_stale_ = true;
    }
    void set_quiet(bool q) { quiet_ = q; }
    // Runs every command of the scene in order.
    void run();
    // Runs n cycles, sampling histories and writing outputs as configured.
    void cycle(long n);

    // Recorded histories: column names and rows.
    const std::vector<HistoryColumn>& history_columns() const { return history_cols_; }
    const std::vector<std::vector<double>>& history_rows() const { return history_rows_; }
    std::vector<double> history(const std::string& name) const;

    json summary() const;
    void write_vtk_snapshot();
    // What the scene will do, without running it (`plab check`, scene_check.cpp).
    void check_report(std::ostream& out);

    // ---- checkpoint and restart (restart.cpp, docs/restart.md) ----
    // The complete state of the run — world, the remaining commands and the
    // progress of the current one, output counters — written atomically.
    void save_checkpoint(const std::string& path) const;
    // The run saved in a checkpoint, ready to continue with run(); `sets`
    // (PATH=VALUE) change the scene it was started from, from the restart
    // step on: a set of what the checkpoint restores (bodies, walls, the
    // commands run so far, ...) is refused by path. run() logs each change.
    // Throws CheckpointError or InputError saying exactly why it cannot load.
    static std::unique_ptr<Simulation> restart(const std::string& path, const std::vector<std::string>& sets = {},
                                               std::shared_ptr<PluginHost> host = nullptr);
    // A checkpoint to checkpoint_path() every `seconds` of simulated time (0: never).
    void set_checkpoint_every(double seconds);
    // --watch: OUT/watch.png, the state now, every few seconds of wall time
    // (2D scenes), drawn as output.png draws its frames.
    void set_watch();
    std::string checkpoint_path() const;
    const std::string& output_dir() const { return out_dir_; }
    // run() returned early because of SIGINT/SIGTERM (see stop_signal());
    // the checkpoint and the outputs are written.
    bool interrupted() const { return interrupted_; }

private:
    json scene_;
    std::string scene_dir_, out_dir_;
    bool quiet_ = false;
    std::shared_ptr<PluginHost> host_;
    std::unique_ptr<World> world_;
    std::unique_ptr<Materials> materials_;  // scene.materials, used while loading
    std::vector<Command> commands_;
    std::vector<HistoryColumn> history_cols_;
    std::vector<std::vector<double>> history_rows_;
    long history_every_ = 0;
    bool history_at_end_ = false;  // histories.at_end: a row of the final state as well
    VtkOptions vtk_;  // output.vtk (or output.vtk_interval)
    std::string vtk_interval_path_ = "scene.output.vtk.interval";  // for messages
    double next_vtk_time_ = 0;
    int vtk_frames_ = 0;
    std::vector<std::pair<double, std::string>> vtk_series_;
    double png_interval_ = 0, next_png_time_ = 0;  // output.png: 2D snapshots
    int png_frames_ = 0;
    SnapshotOptions png_;
    double last_png_time_ = -kInf;
    // "range": "run": the run's range so far, and the frames to draw again in
    // the final one (png_output.cpp), within a memory budget
    bool png_run_range_ = true;
    double png_range_[2] = {kInf, -kInf};
    struct KeptFrame {
        SnapshotFrame frame;
        std::string path;
        double drawn_lo, drawn_hi;
    };
    std::vector<KeptFrame> png_kept_;
    std::size_t png_kept_bytes_ = 0;
    static constexpr std::size_t kPngKeptBytes = std::size_t(1) << 30;
    void write_png_snapshot();
    void redraw_png_series();
    bool watch_ = false;
    std::chrono::steady_clock::time_point watch_written_{};
    static constexpr std::chrono::seconds kWatchInterval{3};
    void write_watch_png();
    RunSummary run_;
    json metrics_;  // evaluated `metrics` of the scene (metrics.cpp)
    std::string timestep_note_;
    std::chrono::steady_clock::time_point started_;
    Progress progress_;

    void load(const Node& root);
    void load_plugins(const Node& n);
    void load_bodies(const Node& n);
    void load_walls(const Node& n);
    void load_contact_models(const Node& n);
    void load_passes(const Node& n);
    void load_stability(const Node& n);
    void load_timestep(const Node& n);
    void load_histories(const Node& n);
    void load_output(const Node& n);
    void load_png_output(const Node& n);
    void load_commands(const Node& n);
    std::function<void(World&)> load_set(const Node& n);
    std::function<void(World&, const std::vector<int>&)> velocity_profile(const Node& n, int dim) const;
    std::function<void(World&)> load_bond(const Node& n);
    // Balls chosen by group, id and/or region, evaluated when a command runs.
    std::function<std::vector<int>(const World&)> select(const Node& n, const World& w) const;
    // command progress, so a checkpoint taken mid-command resumes it exactly
    std::size_t next_command_ = 0;
    bool command_started_ = false;
    std::uint64_t command_start_step_ = 0;
    double command_end_time_ = 0;  // solve time: absolute end
    std::size_t command_breaks_before_ = 0;
    double checkpoint_every_ = 0, next_checkpoint_time_ = 0;
    bool resumed_ = false, interrupted_ = false;
    bool run_command(const Command& c);  // false: stopped by a signal before it completed
    // the run's own sections of a checkpoint (commands, outputs) at the
    // world's last-good snapshot (runs with outputs; World::on_snapshot)
    std::string last_good_run_state_;
    std::vector<std::string> restart_log_;  // what a restart's --set changed, logged when the run starts
    void load_run_state(CheckpointReader& in);
    void check_command_sets(const std::vector<std::string>& sets) const;
    void write_plugins_and_scene(CheckpointWriter& out) const;
    void write_run_state(CheckpointWriter& out) const;
    std::string run_state_bytes() const;
    void write_checkpoint(const std::string& path, const std::string& run_state) const;
    std::string last_good_path() const;
    void keep_last_good();
    std::string write_last_good() const;  // its path, or "" when none is kept
    void after_step();
    struct PlannedStep {
        double dt;
        std::string set_by;
    };
    PlannedStep planned_timestep();
    void check_run_length();
    void make_output_dir() const;
    std::vector<double> sample_history_row() const;
    // what after_step() writes at the world's step and time
    struct DueOutputs {
        bool history, vtk, png, checkpoint;
        bool any() const { return history || vtk || png || checkpoint; }
    };
    DueOutputs due_after_step() const;
    void update_run_figures();
    void finish_run();
    void write_outputs() const;  // bond_breaks.csv, summary.json
    void remove_stale_temporaries() const;
    // history.csv: the rows of history_rows_ it holds; whether it must be
    // written whole; when rows were last written (flush_history())
    std::size_t history_on_disk_ = 0;
    bool history_stale_ = true;
    std::chrono::steady_clock::time_point history_flushed_{};
    static constexpr std::chrono::seconds kHistoryFlushInterval{2};
    void flush_history();
    bool history_flush_due() const;
    std::clock_t cpu_started_ = 0;
    bool finished_ = false;  // run() ended, not stopped by a signal (summary.json: "finished")
    void check_domain(const std::string& where, std::size_t first) const;
    void load_periodic_axes(const Node& n);
    void load_shear(const Node& n);
    void start_shear();
    Vec domain_min_ = Vec::Constant(-kInf), domain_max_ = Vec::Constant(kInf);
    bool shear_start_affine_ = true;  // domain.shear.initial_velocity
    GeneratorLimits limits_;
    std::vector<Servo> servos_;  // scene.servos: walls driven to a target stress before each step
    BodyFlows flows_;            // scene.inlets and scene.outlets: balls added and removed before each step
    std::vector<LatticeCells> lattices_;  // the scene's lattices, for calibrate.density
    json structures_ = json::array();     // what the lattices and calibrations did (summary.json "structures")
    void calibrate_density(const Node& cal, const std::vector<int>* sides);
    void check_calibrated_lattice(const Node& cal, const LatticeCells& c, const std::string& group) const;
    std::string out_dir_from_ = "scene.output.dir";  // who named out_dir_, for messages
};

// SIGINT/SIGTERM: the handler only records the signal; the run finishes
// the current step, writes a checkpoint and its outputs, and returns.
void install_stop_handlers();
int stop_signal();  // 0, or the signal that asked the run to stop
void request_stop(int signal);  // as if `signal` had arrived (tests)
void clear_stop();

} // namespace plab
