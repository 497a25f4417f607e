// The DEM kernel: bodies, walls, the contact-model assignment table, contact
// detection, and the cycle in PFC order. Physics lives in plug-ins; the world
// computes contact geometry once (Yade's Ig2), hands it to each model in
// batches, and sums forces onto bodies in a fixed order so the answer does
// not depend on the thread count.
#pragma once

#include "bodies.hpp"
#include "plugin_host.hpp"
#include "stability.hpp"
#include "types.hpp"
#include "walls.hpp"

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace plab {

// Candidate pairs of one model instance and one kind (ball–ball or ball–wall),
// with their history and the columns of the contact batch. Rows are sorted by
// the ids of the two ends (World::row_keys); history is carried across
// rebuilds by that key.
// The partial-sum slot layouts (World::slot_width): 2D fx, fy and the
// moment about z; 3D force, then moment. Forces only (the centre-force
// path): 2D fx, fy; 3D force.
constexpr std::size_t slot_doubles(int dim, bool forces_only) {
    return dim == 2 ? (forces_only ? 2 : 3) : (forces_only ? 3 : 6);
}
inline void add_to_slot_2d(double* slot, double fx, double fy, double mz) {
    slot[0] += fx;
    slot[1] += fy;
    slot[2] += mz;
}
inline void add_to_slot_3d(double* slot, const Vec& f, const Vec& m) {
    for (int c = 0; c < 3; ++c) { slot[c] += f[c]; slot[3 + c] += m[c]; }
}

struct ContactSet {
    bool with_wall = false;
    std::vector<std::int32_t> end1, end2;
    std::vector<double> history;
    // geometry (inputs of the batch). Ball–ball rows of models that take the
    // dense path (force_sweep) keep active, gap, normal and point up to date
    // for every reader; their distance, rel_velocity, rel_angular_velocity,
    // strain, slip, dashpot and break_energy columns are not written (the
    // model gets them packed, dense_batch.hpp) and hold stale values. Those
    // of a PLAB_MODEL_FORCE_AT_CENTRES model (centre_force_batch.cpp) write
    // back force and dt_limit only: moments, stiffness and energies stay
    // zero. A `packed` set (World::packs_balls: dense, and no model of the
    // world runs a rates stage over the full columns) does not even allocate distance, rel_velocity,
    // rel_angular_velocity, radius1, radius2, mass1, mass2, eff_mass,
    // eff_radius, strain, slip, dashpot and break_energy, nor gap, normal
    // and point: readers recompute those three from the positions
    // (World::contact_gap/contact_normal/contact_point), and take the radii
    // from the bodies (World::end_radius). ~200 B per row less.
    bool packed = false;
    std::vector<std::uint8_t> active, interior;
    std::vector<double> normal, gap, distance, rel_velocity, rel_angular_velocity, point;
    std::vector<double> radius1, radius2, mass1, mass2, eff_mass, eff_radius;
    // outputs
    std::vector<double> force, moment1, moment2, strain, slip, dashpot, k_t, k_r, dt_limit, break_energy;
    std::vector<std::vector<double>> acc1, acc2;
    // per batch of kContactBatch rows: strain, slip, dashpot, bond-break
    // energy and wall power of the active rows (World::scatter_rows)
    std::vector<double> batch_energy;
    bool overlap_exceeded = false;  // an active contact overlaps beyond its model's max_overlap (geometry())
    bool forces_zero = false;       // force zero and no step limit in every row (World::hold_still)

    std::size_t size() const { return end1.size(); }
    void resize_columns(std::size_t n, int n_accumulated);
    void release_columns();  // every per-row column but the ends and history (and a wall set's sides), freed
    // The per-row columns of doubles (all but ends, flags and history), by
    // name: checkpoints save them by name, release_columns() frees them.
    std::vector<std::pair<const char*, std::vector<double>*>> double_columns();

    // The owning model's io and flags (abi.h; set once, World::add_instance).
    // A packed set does not keep the output columns its model never writes:
    // a model that declares its io and not PLAB_IO_MOMENTS has no moment
    // columns (48 B per row), and so on; a centre-force model (SPH) keeps
    // only force and dt_limit. Readers take the neutral value of a column
    // not kept, through these accessors.
    std::uint32_t model_io = 0, model_flags = 0;
    bool keeps(std::uint32_t io_bit) const;  // PLAB_IO_MOMENTS, _STIFFNESS_ROTATIONAL, _DT_LIMIT, or 0 for k_t
    double k_t_at(std::size_t k) const { return k_t.empty() ? 0.0 : k_t[k]; }
    double k_r_at(std::size_t k) const { return k_r.empty() ? 0.0 : k_r[k]; }
    double dt_limit_at(std::size_t k) const { return dt_limit.empty() ? kInf : dt_limit[k]; }
    Vec moment1_at(std::size_t k) const { return moment1.empty() ? Vec(Vec::Zero()) : Vec(&moment1[3 * k]); }
    Vec moment2_at(std::size_t k) const { return moment2.empty() ? Vec(Vec::Zero()) : Vec(&moment2[3 * k]); }
};

struct DenseBatch;  // dense_batch.hpp: the active rows of one batch, packed for the model

// Rows per call of a model (one C ABI call per batch). Batches are fixed row
// ranges, never per thread, so sums taken per batch are thread-count free.
constexpr std::size_t kContactBatch = 512;
constexpr std::size_t kBatchEnergies = 5;  // ContactSet::batch_energy per batch

struct ModelInstance {
    std::string model;
    const plab_contact_model_desc* desc = nullptr;
    std::vector<double> props;
    void* state = nullptr;
    double range = 0;  // activity range (gap or distance, see desc->range_kind)
    int stride = 0;    // history doubles per contact
    double max_overlap = kInf;  // stability: overlap limit, fraction of the smaller radius (1)
    std::vector<int> fields_read, fields_accumulated;  // world field indices
    ContactSet balls, walls;

    // By name, for measurements: a history slot's index and a property's
    // value (std::out_of_range when the model has none of that name).
    int history_slot(const std::string& name) const;
    double property(const std::string& name) const;
    // whether the model reads optional input / writes optional output
    // `bit` (PLAB_IO_*): all of them unless it declared which (abi.h, ABI 5)
    bool uses(std::uint32_t bit) const { return !(desc->io & PLAB_IO_DECLARED) || (desc->io & bit); }
};

// The body fields a model reads, as its batches take them (abi.h): the
// columns in its `fields_read` order, and which of them hold their
// default at every body (plab_contact_batch::body_fields_at_default).
struct ReadFields {
    static constexpr std::size_t kMax = 16;  // (World::add_instance refuses more)
    static_assert(kMax <= 64, "one bit of at_default per field");
    const double* cols[kMax] = {};
    std::uint64_t at_default = 0;
};

struct PassInstance {
    const plab_pass_desc* desc = nullptr;
    std::vector<double> props;
    void* state = nullptr;
    std::vector<int> fields;
};

// Cumulative energies (J), PFC's energy bookkeeping. With no damping and no
// friction kinetic + strain - body - boundary stays constant.
struct Energies {
    double kinetic = 0;       // state: translational + rotational
    double strain = 0;        // state: stored in contact springs
    double body = 0;          // work done by gravity
    double boundary = 0;      // work done by walls, applied loads and fixed velocities
    double slip = 0;          // dissipated by friction
    double dashpot = 0;       // dissipated by contact dashpots
    double local_damping = 0; // dissipated by local and viscous body damping
    double bond_break = 0;    // elastic energy released by breaking bonds
    double balance() const { return kinetic + strain - body - boundary + slip + dashpot + local_damping + bond_break; }
};

// A bond that broke (thesis §3.3.3): where, when, and in which mode.
struct BondBreak {
    std::uint64_t step = 0;
    double time = 0;
    BodyId id1 = 0, id2 = 0;
    Vec point = Vec::Zero();
    int mode = 0;  // PLAB_BREAK_TENSION / PLAB_BREAK_SHEAR
    std::string model;
};

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
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    const int dim;
    Bodies bodies;
    Walls walls;
    Vec gravity = Vec::Zero();
    double skin = -1;  // neighbour skin, m; < 0: a quarter of the mean radius
    std::size_t parallel_min = kParallelMin;  // shorter loops run on one thread

    // ---- groups and the contact-model assignment table (PFC's CMAT) ----
    int group_index(const std::string& name);   // creates on first use
    int find_group(const std::string& name) const;  // -1 when unknown
    const std::vector<std::string>& group_names() const { return groups_; }
    // Creates an instance of a loaded model with property values (in the
    // model's declaration order); returns its index.
    int add_instance(const std::string& model, std::vector<double> props);
    // Assigns an instance (or -1: no contact, no cost) to a pair of groups.
    void assign(int group_a, int group_b, int instance);
    int assigned(int group_a, int group_b) const;
    const std::vector<std::unique_ptr<ModelInstance>>& instances() const { return instances_; }

    // ---- per-body fields registered by plug-ins ----
    int field_index(const std::string& name) const;
    // A field's unit is the first non-empty unit a plug-in declares for it.
    int register_field(const std::string& name, double default_value, const char* unit = nullptr);
    const std::string& field_unit(int index) const { return field_units_[index]; }
    std::vector<double>& field(int index) { return fields_[index]; }
    const std::vector<double>& field(int index) const { return fields_[index]; }
    const std::vector<std::string>& field_names() const { return field_names_; }
    // False for a field that only a skipped rates stage would fill (no pass
    // or model reads it, rates_stage_needed): it holds zeros, so outputs
    // leave it out rather than write zeros as if they were values.
    bool field_computed(int f) const;

    void add_pass(const std::string& name, std::vector<double> props);

    // ---- time stepping ----
    double fixed_dt = 0;         // > 0: fixed step; 0: automatic
    double safety_factor = 0.8;  // automatic step = safety * critical
    double time = 0;
    std::uint64_t step_count = 0;
    double last_dt = 0;

    // Critical step from the contacts of the last force pass and from a
    // nominal contact per assigned group pair (before any contact exists).
    StableStep stable_timestep();
    StableStep nominal_timestep();
    // One cycle: timestep, law of motion, detection, pre-force passes,
    // force–displacement, reduction, post-force passes, integration.
    void step();
    // Forces at the current state (first call, or after the scene changed).
    void prepare();
    // Whether anything reads the contact forces of the step being taken
    // (outputs, histories, stress, the unbalanced-force ratio): asked by
    // step() once the step's time and count are set, before its forces.
    // When it says no, the packed ball–ball rows' force columns are not
    // written that step (a stream of 24 bytes per contact in range, 4-5 %
    // of a step): they keep the forces of the last step that wrote them,
    // and contact_forces_current() is false until the next one does. A
    // batch with a non-finite force is written all the same (the
    // diagnostic names the contact). Unset, as for any caller that reads
    // the columns itself: every step writes them. prepare() always does.
    std::function<bool()> contact_forces_wanted;
    bool contact_forces_current() const { return contact_forces_kept_; }

    // ---- bonds ----
    // Marks every contact between the two groups whose surface gap is at
    // most `gap_tolerance` as bonded, for models with a persist slot
    // (PFC's `contact method bond gap`). Returns the number of bonds made.
    std::size_t bond(int group_a, int group_b, double gap_tolerance);
    std::size_t intact_bonds() const;
    std::vector<BondBreak> bond_breaks;

    // ---- last good state ----
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
    // Whether the world is back at its last-good snapshot after a step
    // failed (until the next step).
    bool at_last_good() const { return at_last_good_; }

    // ---- the instability detector (stability.cpp) ----
    StabilityLimits stability;
    Diagnostic stopped;  // what stopped the last step (quantity empty: nothing)

    // ---- measurements ----
    Energies energies;
    // Per-ball average stress (tension positive), PFC's measurement:
    // sigma = (1/V) sum over contacts of r_c ⊗ f_c, with f_c the contact
    // force on the ball and V its volume (area × unit thickness in 2D).
    std::vector<Eigen::Matrix3d> ball_stress() const;
    double unbalanced_force_ratio() const;  // mean unbalanced / mean contact force
    std::size_t active_contacts() const;
    // Normal (end 1 to end 2) and contact point of row k of a set at the
    // last force pass: a packed set's are recomputed from the positions and
    // the gap with the force pass's arithmetic (the same bits, as long as no
    // ball moved since), any other set's are read from its columns.
    Vec contact_normal(const ContactSet& s, std::size_t k) const;
    Vec contact_point(const ContactSet& s, std::size_t k) const;
    double contact_gap(const ContactSet& s, std::size_t k) const;  // (the same: the range test's arithmetic)
    // The radius of row k's end 1 or end 2 (a wall's: 0), from the bodies:
    // a packed set keeps no radius columns, and a ball's radius changes
    // only with the scene, which rebuilds the lists (mark_dirty()).
    double end_radius(const ContactSet& s, std::size_t k, bool end2) const {
        return end2 ? (s.with_wall ? 0.0 : bodies.radius[s.end2[k]]) : bodies.radius[s.end1[k]];
    }
    // A row's key: the ball id of end 1 and the ball or facet id of end 2.
    // Derived from the ends, not stored (16 B per row): balls and facets are
    // only ever appended, so an index names the same body at every rebuild.
    std::pair<BodyId, BodyId> pair_keys(bool with_wall, std::int32_t end1, std::int32_t end2) const {
        return {bodies.id[end1], with_wall ? walls.facets[end2].id : bodies.id[end2]};
    }
    std::pair<BodyId, BodyId> row_keys(const ContactSet& s, std::size_t k) const {
        return pair_keys(s.with_wall, s.end1[k], s.end2[k]);
    }
    std::uint64_t state_hash() const;       // FNV-1a over positions, velocities, spins
    std::array<double, ph_count> phase_seconds{};
    std::uint64_t rebuilds = 0;
    // After a change of the bodies, walls or models: lists, caches and the
    // last good state are renewed (a snapshot never spans a change).
    void mark_dirty() { need_rebuild_ = true; prepared_ = false; nominal_valid_ = false; snapshot_.valid = false; }

private:
    friend struct WorldCheckpoint;  // checkpoint.cpp saves and restores the private state below
    std::shared_ptr<PluginHost> host_;
    std::vector<std::string> groups_;
    std::vector<int> cmat_;  // groups × groups → instance, -1 none
    std::vector<std::unique_ptr<ModelInstance>> instances_;
    std::vector<PassInstance> passes_;
    std::vector<std::string> field_names_;
    std::vector<std::vector<double>> fields_;
    std::vector<double> field_defaults_;
    std::vector<std::string> field_units_;
    std::vector<std::uint8_t> field_at_default_;  // per field, this force pass (find_fields_at_default)

    // detection state
    bool need_rebuild_ = true;
    bool prepared_ = false;
    bool nominal_valid_ = false;
    StableStep nominal_cache_;
    std::vector<Vec> position_at_build_;
    double wall_motion_since_build_ = 0;
    // per-body list of (set, row, side) for the deterministic reduction
    struct Entry { std::uint32_t set; std::uint32_t row; };  // row's top bit: body is end 2
    std::vector<std::uint32_t> entry_start_;
    std::vector<Entry> entries_;
    std::vector<ContactSet*> sets_;
    std::vector<const ModelInstance*> set_owner_;
    // The deterministic reduction. Each set's rows are cut into chunks of
    // whole batches, their number a function of the row count only (never of
    // the threads). A chunk adds its active rows' forces and moments, in row
    // order, into its own partial array over the bodies it touches (lo..hi,
    // kSlotDoubles per body: force, moment), and reduce() adds the partials
    // to each body in chunk order: the same sums for any thread count.
    static constexpr std::size_t kSlotDoubles = 6;
    // The doubles of a slot in use: only what can be nonzero, so that the
    // chunks clear, scatter into and add no more than that (the block stays
    // sized for kSlotDoubles). 3D: force, moment; 2D: fx, fy and the moment
    // about z (finish_bodies() drops the rest). No moment on the
    // centre-force path: 3D fx, fy, fz; 2D fx, fy.
    std::size_t slot_width(bool forces_only) const { return slot_doubles(dim, forces_only); }
    void add_to_slot(double* slot, const Vec& f, const Vec& m) const {
        if (dim == 2) add_to_slot_2d(slot, f[0], f[1], m[2]);
        else add_to_slot_3d(slot, f, m);
    }
    struct Chunk {
        std::uint32_t set;
        std::size_t begin, end;  // rows
        std::int32_t lo, hi;     // bodies touched (hi < lo: none)
        std::size_t offset;      // into partial_fm_
        // Bodies with a slot in partial_fm_: every body lo..hi, or, for a
        // `listed` chunk (ball–wall rows touch a few balls spread over all
        // of them), only the balls it touches: chunk_bodies_[first_listed..]
        // ascending, row k's ball at slot listed_slot_[set][k].
        std::size_t slots = 0;
        // the last sweep added forces alone (the centre-force path, which
        // has no moments): its slots are slot_width(true) doubles wide
        bool forces_only = false;
        // every slot holds zero: add_chunk_sums() clears what it takes
        // (its lines are then in cache, a separate fill would load them
        // again), so the next sweep need not clear the chunk
        bool zeroed = true;
        bool listed = false;
        std::size_t first_listed = 0;
    };
    std::vector<std::int32_t> chunk_bodies_;
    std::vector<std::vector<std::uint32_t>> listed_slot_;
    std::vector<Chunk> chunks_;
    std::vector<std::uint32_t> set_chunks_;  // chunks of set si: [set_chunks_[si], set_chunks_[si + 1])
    std::vector<double> partial_fm_;
    // Per set and batch, for the outputs moment1, moment2, k_t, k_r,
    // dt_limit: the value every row of the batch holds in the set's column,
    // when they all hold the same (zero moments, a constant stiffness). The
    // dense path then skips writing an unchanged output back (unpack_rows).
    struct HeldOutputs { double value[5]; std::uint8_t uniform[5]; };
    std::vector<std::vector<HeldOutputs>> held_;
    // per set and row: the row may hold history other than the defaults (it
    // was active at the last force pass, or came with its history from the
    // last list): only such rows need their history reset when out of range
    std::vector<std::vector<std::uint8_t>> live_;
    void build_chunks();
    void list_chunk_bodies(Chunk& ch);
    bool any_accumulation_ = false;  // a force-stage model accumulates body fields
    bool swept_ = false;             // the last force pass ran force_sweep()
    bool contact_forces_kept_ = true;  // the last force pass wrote the packed rows' forces (contact_forces_wanted)
    bool in_range_marked_ = false;   // mark_ball_rows_in_range() ran at the current positions
    // What mark_ball_rows_in_range() found per ball–ball set: the rows in
    // range of batch b, listed from b * kContactBatch, and their count; on
    // the centre-force path (`listed`, for pack_centre_rows()) their centre
    // distances too.
    struct RowsInRange { std::vector<std::uint32_t> row, count; std::vector<double> distance; bool listed = false; };
    // The step limits (abi.h, dt_limit) of set si's centre-force sweep, per
    // batch: the least over its rows and the first row that has it, which
    // is all stable_timestep() takes from them. A per-pair limit (SPH's CFL)
    // is seldom uniform, and writing it row by row into a column as long as
    // the candidate list cost a cache miss per pair. Empty: the set's
    // dt_limit column holds its limits (cleared at every force pass and
    // rebuild, so never older than the rows).
    struct BatchLimit { double dt; std::uint32_t row; };
    std::vector<std::vector<BatchLimit>> batch_limits_;
    void clear_batch_limits() {
        batch_limits_.resize(sets_.size());
        for (auto& b : batch_limits_) b.clear();
    }
    std::vector<RowsInRange> in_range_;
    void scatter_rows(std::uint32_t set_index, std::size_t begin, std::size_t end, const Chunk& chunk);
    void scatter_to_chunks(std::uint32_t set_index);
    void force_sweep(std::uint32_t set_index, bool with_geometry);
    // Per model instance: every ball of the groups it pairs has every DOF
    // fixed (SPH boundary particles), found at each force pass; then no
    // centre force of its ball–ball rows moves anything (force_sweep).
    std::vector<std::uint8_t> still_instance_, still_group_;
    void find_still_instances();
    bool still_centre_set(std::uint32_t set_index) const;
    static void hold_still(ContactSet& set);
    // per-body stiffness sums of the last force pass, summed on demand
    mutable std::vector<double> k_trans_, k_rot_;
    mutable bool stiffness_valid_ = false;
    void sum_stiffness() const;
    // active contacts for passes (built only when a pass is loaded)
    std::vector<std::int32_t> pc_end1_, pc_end2_;
    std::vector<std::uint8_t> pc_wall_;
    std::vector<double> pc_distance_;  // their centre distances (mark_ball_rows_in_range(): abi.h, ABI 6)
    std::vector<std::size_t> batch_at_;  // append_pass_contacts(): each batch's first place in the list

    // the kept copy: the contact rows whose history is not the model's
    // default, by ends; the others, and all geometry, come back with the
    // rebuild of restore_snapshot()
    struct SetState {
        std::vector<std::int32_t> end1, end2;
        std::vector<double> history;
    };
    struct Snapshot {
        bool valid = false;
        std::vector<Vec> position, velocity, angular_velocity;
        Walls walls;
        std::vector<std::vector<double>> fields;
        Energies energies;
        double time = 0, last_dt = 0;
        std::uint64_t step_count = 0;
        std::size_t bond_breaks = 0;
        std::vector<SetState> sets;  // per instance: balls, walls
    } snapshot_;
    bool at_last_good_ = false;
    StableStep snapshot_stable_;  // stable step at the last good state, for the likely cause
    // the energy balance and domain the detector compares with (stability.cpp)
    struct StabilityBaseline {
        double balance = 0, body = 0, boundary = 0, dissipated = 0, stored = 0, potential = 0, max_work = 0;
        Vec lo = Vec::Constant(-kInf), hi = Vec::Constant(kInf);
    } baseline_;
    bool left_domain_ = false;  // a position left the domain or is not finite (drift())
    void set_stability_baseline();
    void detect_instability();
    void check_domain_and_finite();
    void check_energy();
    void check_overlaps();
    void overlap_stop(const ModelInstance& inst, const ContactSet& s);
    std::string contact_name(const ModelInstance& inst, const ContactSet& s, std::size_t k) const;
    std::string timestep_assessment() const;
    std::string contact_groups(const ContactSet& s, std::size_t k) const;
    std::string stiffest_model(std::size_t ball) const;
    [[noreturn]] void stop(Diagnostic d);
    Diagnostic pass_diagnostic(const std::string& pass, const std::string& message) const;
    void take_snapshot();
    void restore_snapshot();
    void advance();

    double effective_skin() const;
    void resize_fields();
    void rebuild();
    void build_ball_pairs(std::vector<std::vector<std::array<std::int32_t, 2>>>& out);
    void build_wall_pairs(std::vector<std::vector<std::array<std::int32_t, 2>>>& out) const;
    // buffers of rebuild() and install_pairs(), kept between rebuilds
    // (freed after a lean one)
    struct RebuildScratch {
        std::vector<std::vector<std::array<std::int32_t, 2>>> ball_pairs, wall_pairs;
        std::vector<std::vector<std::vector<std::array<std::int32_t, 2>>>> block_pairs;  // build_ball_pairs()
        // Per set, in sets_' order: the buffers its next list is built in
        // (the old list's, after the swap). One pair per set, never shared:
        // a shared pair would pass the big list's buffers on to every small
        // or empty set in turn, and each would keep a big one.
        struct SetBuffers {
            std::vector<std::int32_t> e1, e2;
            std::vector<double> history;
            std::vector<double> normal;          // ball–wall rows: the side each survivor is on
            std::vector<std::uint8_t> interior;  // (facet_distance, force_pass.cpp)
        };
        std::vector<SetBuffers> sets;
    };
    RebuildScratch rebuild_scratch_;
    void install_pairs(ModelInstance& inst, ContactSet& set, std::vector<std::array<std::int32_t, 2>>& pairs,
                       RebuildScratch::SetBuffers& t, bool lean);
    void sort_by_keys(const ContactSet& set, std::vector<std::array<std::int32_t, 2>>& pairs) const;
    void build_entries();
    void fill_pair_constants(ContactSet& set) const;
    // whether the ball–ball rows of a model go to it packed (force_sweep): no
    // model of the world has a rates stage and this one accumulates no field
    bool packs_balls(const ModelInstance& inst) const;
    void lay_out_columns(const ModelInstance& inst, ContactSet& set);
    // the largest squared displacement since the last build, taken by
    // drift() while the positions are at hand (-1: no reference positions)
    double max_drift2_ = -1;
    bool displacement_exceeds_skin() const;
    void geometry(ModelInstance& inst, ContactSet& set);
    bool geometry_rows(const ModelInstance& inst, ContactSet& set, std::size_t begin, std::size_t end);
    bool ball_geometry_rows(const ModelInstance& inst, ContactSet& set, std::size_t begin, std::size_t end);
    bool wall_geometry_rows(const ModelInstance& inst, ContactSet& set, std::size_t begin, std::size_t end);
    std::size_t range_test_rows(const ModelInstance& inst, std::uint32_t set_index, std::size_t begin,
                                std::size_t end, std::uint32_t* row, double* distance);
    bool pack_ball_rows(const ModelInstance& inst, std::uint32_t set_index, std::size_t begin, std::size_t end,
                        DenseBatch& d);
    void unpack_rows(std::uint32_t set_index, const ModelInstance& inst, const DenseBatch& d, std::size_t begin,
                     const Chunk& chunk);
    // the same for a model with PLAB_MODEL_FORCE_AT_CENTRES (centre_force_batch.cpp)
    bool pack_centre_rows(const ModelInstance& inst, std::uint32_t set_index, std::size_t begin, std::size_t end,
                          DenseBatch& d);
    void unpack_centre_rows(std::uint32_t set_index, const ModelInstance& inst, const DenseBatch& d,
                            std::size_t begin, const Chunk& chunk);
    void write_back(double* column, std::size_t width, const double* dense, const DenseBatch& d, std::size_t begin,
                    std::size_t end, HeldOutputs& held, int which);
    static void hold_value(double* column, std::size_t width, double value, std::size_t begin, std::size_t end,
                           HeldOutputs& held, int which);
    int call_model(ModelInstance& inst, ContactSet& set, std::size_t o, std::size_t m, std::uint32_t stage,
                   const ReadFields& fields, bool clear);
    void find_fields_at_default();
    ReadFields read_fields(const ModelInstance& inst) const;
    [[noreturn]] void model_failed(const ModelInstance& inst) const;
    void resolve_wall_features(ContactSet& set);
    void compute(ModelInstance& inst, ContactSet& set, std::uint32_t stage);
    void rates_stage();
    bool rates_stage_needed(const ModelInstance& inst) const;
    void mark_ball_rows_in_range();  // pass_contacts.cpp
    void mark_set_in_range(std::uint32_t set_index, std::size_t* listed);
    void append_pass_contacts(std::uint32_t set_index, std::size_t& listed);
    // The pass-contact columns at n rows. mark_ball_rows_in_range() refills
    // them every cycle without emptying them first (resizing an emptied
    // vector would clear the whole list, ~2 MB on the dam break, only to
    // overwrite it): it grows them as it lists and shrinks them at the end.
    void resize_pass_contacts(std::size_t n);
    void accumulate(const ModelInstance& owner, const ContactSet& s, std::uint32_t k, bool is_end2, std::size_t i);
    void build_pass_contacts();
    void record_breaks(ModelInstance& inst, ContactSet& set);
    void keep_bonded_pairs(const ModelInstance& inst, const ContactSet& set,
                           std::vector<std::array<std::int32_t, 2>>& pairs) const;
    // closing_kick > 0: reduce() takes the step's closing half kick of that
    // length block by block, right after the block's force sums, while its
    // forces and velocities are in cache (advance(), when no POST_FORCE pass
    // runs between them)
    void force_pass(double closing_kick = 0);
    void damp_body(std::size_t body, Vec& force, Vec& moment, double& local_work) const;
    void add_chunk_sums(std::size_t first_body, std::size_t end_body);
    void clear_chunk(Chunk& ch);
    bool finish_bodies(std::size_t first_body, std::size_t end_body, double& local_work);
    bool bodies_finite(std::size_t first_body, std::size_t end_body);
    bool reduce(double closing_kick);  // true: a body's state may be non-finite (check_finite() looks)
    void run_passes(std::uint32_t phase);
    bool has_passes(std::uint32_t phase) const;
    // The per-body loops work on fixed blocks of bodies; a sum over the
    // bodies is taken per block and the blocks added in order, so it does
    // not depend on the thread count.
    static constexpr std::size_t kBodyBlock = 1024;
    std::size_t body_blocks() const { return (bodies.size() + kBodyBlock - 1) / kBodyBlock; }
    // 1/m and 1/I of every body, for the kicks; set by prepare() (a change
    // of mass or inertia marks the world dirty, as any scene change does)
    std::vector<double> inv_mass_, inv_inertia_;
    void cache_inverse_masses();
    // per block: kinetic energy at the synchronised velocities and the work
    // of applied loads and fixed-DOF reactions over the last step, from the
    // closing kick (kick(h, true)) or body_energies()
    std::vector<double> block_kinetic_, block_boundary_;
    std::vector<double> block_local_work_;  // per block: work of local and viscous damping (reduce)
    // per block, from the drift: work of gravity, largest squared
    // displacement since the build, a position out of
    // the domain or not finite
    std::vector<double> block_body_work_, block_max_drift2_;
    std::vector<std::uint8_t> block_out_;
    struct DriftCorrection {
        bool on = false;
        std::array<const double*, 3> field{};
    };
    DriftCorrection drift_correction();
    void prepare_body_blocks();
    void kick_block_of_bodies(std::size_t block, double half_dt, bool closing);
    void kick(double half_dt, bool closing = false);
    void kick_and_drift(double dt);
    void body_energies(double dt);
    void drift(double dt);
    void drift_block(std::size_t block, double dt, const DriftCorrection& corr);
    void finish_drift();
    void check_finite();
    std::string non_finite_contact(std::size_t body) const;
    void sum_energies(double dt);
};

} // namespace plab
