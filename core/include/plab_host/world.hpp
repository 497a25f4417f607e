// The host API's world: what a host (the `plab` program, a test, later the
// Python module and the MPI driver) builds, runs and observes. The world
// holds the state a host sets and reads — bodies, walls, body fields,
// gravity, the clock, the measurements — and the cycle (core/src, opaque
// here) that the kernel runs on it: detection, the force pipeline,
// reduction, integration, the stability monitor. Physics lives in plug-ins, loaded by a
// PluginHost (plab_host/plugins.hpp).
#pragma once

#include <plab_host/bodies.hpp>
#include <plab_host/clumps.hpp>
#include <plab_host/contacts.hpp>
#include <plab_host/energies.hpp>
#include <plab_host/fields.hpp>
#include <plab_host/plugins.hpp>
#include <plab_host/stability.hpp>
#include <plab_host/types.hpp>
#include <plab_host/walls.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace plab {

class Cycle;  // core/src/world/cycle.hpp

// A bond that broke (thesis §3.3.3): where, when, and in which mode.
struct BondBreak {
    std::uint64_t step = 0;
    double time = 0;
    BodyId id1 = 0, id2 = 0;
    Vec point = Vec::Zero();
    int mode = 0;  // PLAB_BREAK_TENSION / PLAB_BREAK_SHEAR
    std::string model;
};

// The phases of one cycle, in order (World::phase_seconds).
enum Phase { ph_timestep, ph_motion, ph_detection, ph_pre_force, ph_force, ph_reduction, ph_post_force, ph_integrate, ph_stability, ph_count };
extern const char* const phase_names[ph_count];

struct StableStep {
    double critical = kInf;  // min sqrt(m/k), sqrt(I/k_r), dt limits
    std::string limited_by;  // which model/body/constraint set it
};

class World {
public:
    World(int dim, std::shared_ptr<PluginHost> host);
    ~World();

    const int dim;
    Bodies bodies;
    Clumps clumps;  // rigid bodies; their pebbles are balls of `bodies`
    Walls walls;
    BodyFields fields;  // per-body fields registered by plug-ins
    Vec gravity = Vec::Zero();
    std::size_t parallel_min = kParallelMin;  // shorter loops run on one thread

    // ---- groups and the contact-model assignment table (PFC's CMAT) ----
    int group_index(const std::string& name);  // creates on first use
    int find_group(const std::string& name) const;  // -1 when unknown
    const std::vector<std::string>& group_names() const;
    // Creates an instance of a loaded model with property values (in the
    // model's declaration order); returns its index.
    int add_instance(const std::string& model, std::vector<double> props);
    // Assigns an instance (or -1: no contact, no cost) to a pair of groups.
    void assign(int group_a, int group_b, int instance);
    int assigned(int group_a, int group_b) const;
    // The model instances, in the order add_instance() made them.
    std::size_t model_count() const;
    ModelView model(std::size_t instance) const;
    // Stability: an active contact of the instance that overlaps more than
    // this fraction of the smaller radius stops the run.
    void set_max_overlap(std::size_t instance, double fraction_of_radius);

    // Registers a field at every body (BodyFields::add).
    int register_field(const std::string& name, double default_value, const char* unit = nullptr);
    void add_pass(const std::string& name, std::vector<double> props);
    void set_skin(double skin);  // m; < 0: a quarter of the mean radius

    // ---- time stepping ----
    double fixed_dt = 0;         // > 0: fixed step; 0: automatic
    double safety_factor = 0.8;  // automatic step = safety * critical
    double time = 0;
    std::uint64_t step_count = 0;
    double last_dt = 0;

    // One cycle: timestep, law of motion, detection, pre-force passes,
    // force–displacement, reduction, post-force passes, integration.
    void step();
    // Forces at the current state (first call, or after the scene changed).
    void prepare();
    // After a change of the bodies, walls or models: lists, caches and the
    // last good state are renewed (a snapshot never spans a change).
    void mark_dirty();
    // Whether anything reads the contact forces of the step being taken
    // (outputs, histories, stress, the unbalanced-force ratio): asked by
    // step() once the step's time and count are set, before its forces.
    // When it says no, the packed ball–ball rows' force columns are not
    // written that step (a stream of 24 bytes per contact in range, 4-5 %
    // of a step): they keep the forces of the last step that wrote them,
    // and contact_forces_current() is false until the next one does. A
    // batch with a non-finite force is written all the same (the
    // diagnostic names the contact). Unset: every step writes them.
    // prepare() always does.
    std::function<bool()> contact_forces_wanted;

    // ---- bonds ----
    // Marks every contact between the two groups whose surface gap is at
    // most `gap_tolerance` as bonded, for models with a persist slot
    // (PFC's `contact method bond gap`). Returns the number of bonds made.
    std::size_t bond(int group_a, int group_b, double gap_tolerance);
    std::vector<BondBreak> bond_breaks;

    // ---- last good state and the instability detector ----
    // Every `snapshot_interval` steps (0: never) the world keeps a copy of its
    // state; a step that goes unstable restores it before the RunError
    // leaves step(), so outputs and the caller see the last good state.
    std::uint64_t snapshot_interval = 100;
    // Above this many candidate rows a rebuild keeps nothing twice: the
    // columns, entries and partial sums go before the new lists are built,
    // the scratch after (a big world rebuilds every hundred steps or so, and
    // the memory matters: the kept scratch would be ~20 MB beside the 94 MiB
    // peak of a settled pile of 1e5 balls; smaller worlds, such as the SPH
    // scene that rebuilds every few steps, keep their buffers, so the cycle
    // allocates nothing). Results are the same bits either way.
    std::size_t lean_rebuild_rows = std::size_t(1) << 18;
    // Called whenever the world has taken its last-good snapshot: whoever
    // keeps state beside the world (a Simulation's outputs) keeps theirs
    // for the same instant.
    std::function<void()> on_snapshot;
    StabilityLimits& stability_limits();
    Diagnostic stopped;  // what stopped the last step (quantity empty: nothing)

    // ---- measurements (more below, as functions of the world) ----
    Energies energies;
    std::array<double, ph_count> phase_seconds{};  // wall time per phase, summed over the steps

    // The kernel's cycle, run on this state (opaque to hosts; the
    // checkpoint and the kernel's own tests reach it).
    const std::unique_ptr<Cycle> cycle;
};

// ---- observing a world ----
// Critical step from the contacts of the last force pass, and from a
// nominal contact per assigned group pair (before any contact exists).
// Adds a clump and its pebbles to the world (Clumps::add); returns its index.
std::size_t add_clump(World& w, const ClumpSpec& spec);
// Removes the balls flagged in `gone` (one flag per body; a clump's pebble
// is refused: std::invalid_argument), keeping the others' order, ids and
// contact history; returns how many went. The next step rebuilds the
// contact lists (World::mark_dirty). Balls are added with Bodies::add and
// mark_dirty().
std::size_t remove_bodies(World& w, const std::vector<std::uint8_t>& gone);

StableStep stable_timestep(const World& w);
StableStep nominal_timestep(const World& w);
std::uint64_t state_hash(const World& w);  // FNV-1a over positions, velocities, spins
// Per-ball average stress (tension positive), PFC's measurement:
// sigma = (1/V) sum over contacts of r_c ⊗ f_c, with f_c the contact
// force on the ball and V its volume (area × unit thickness in 2D).
std::vector<Eigen::Matrix3d> ball_stress(const World& w);
double unbalanced_force_ratio(const World& w);  // mean unbalanced / mean contact force
std::size_t active_contacts(const World& w);
std::size_t intact_bonds(const World& w);
std::uint64_t rebuilds(const World& w);  // of the neighbour lists, since the start
// False for a field that only a skipped rates stage would fill (no pass or
// model reads it): it holds zeros, so outputs leave it out rather than
// write zeros as if they were values.
bool field_computed(const World& w, int field);
// Whether the last force pass wrote the packed rows' forces
// (World::contact_forces_wanted).
bool contact_forces_current(const World& w);
// Whether the world is back at its last-good snapshot after a step failed
// (until the next step).
bool at_last_good(const World& w);

} // namespace plab
