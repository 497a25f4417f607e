// The cycle of the DEM kernel, behind the host API's World
// (plab_host/world.hpp): the contact-model assignment table, contact
// detection, the force pipeline, the reduction, the leapfrog and the
// stability monitor, run in PFC's order on the world's state. Physics lives
// in plug-ins; the cycle computes
// contact geometry once (Yade's Ig2), hands it to each model in batches, and
// sums forces onto bodies in a fixed order so the answer does not depend on
// the thread count.
#pragma once

#include <plab_host/world.hpp>

#include "contacts/assignment.hpp"
#include "contacts/body_contacts.hpp"
#include "contacts/contact_keys.hpp"
#include "contacts/model_instance.hpp"
#include "detection/neighbour_lists.hpp"
#include "detection/range_test.hpp"
#include "forces/geometry.hpp"
#include "forces/packed_tables.hpp"
#include "forces/still_instances.hpp"
#include "integration/leapfrog.hpp"
#include "monitor/last_good.hpp"
#include "monitor/monitor.hpp"
#include "monitor/stability.hpp"
#include "monitor/stiffness_sums.hpp"
#include "reduction/chunked_sums.hpp"

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace plab {

struct DenseBatch;  // forces/packed_batch.hpp: the active rows of one batch, packed for the model

// The body fields a model reads, as its batches take them (abi.h): the
// columns in its `fields_read` order, and which of them hold their
// default at every body (plab_contact_batch::body_fields_at_default).
struct ReadFields {
    static constexpr std::size_t kMax = 16;  // (Cycle::add_instance refuses more)
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

class Cycle {
public:
    // The cycle of world `w`: it runs on w's state, which it
    // holds by reference (the host API's World owns it).
    Cycle(World& w, std::shared_ptr<PluginHost> host);
    ~Cycle();
    Cycle(const Cycle&) = delete;
    Cycle& operator=(const Cycle&) = delete;

    // ---- the world's state (plab_host/world.hpp says what each is) ----
    const int dim;
    Bodies& bodies;
    Walls& walls;
    BodyFields& fields;
    Vec& gravity;
    std::size_t& parallel_min;
    double &fixed_dt, &safety_factor, &time;
    std::uint64_t& step_count;
    double& last_dt;
    std::function<bool()>& contact_forces_wanted;
    std::vector<BondBreak>& bond_breaks;
    std::uint64_t& snapshot_interval;
    std::size_t& lean_rebuild_rows;
    std::function<void()>& on_snapshot;
    Diagnostic& stopped;
    Energies& energies;
    std::array<double, ph_count>& phase_seconds;

    // ---- what the World's functions of the same names do ----
    int add_instance(const std::string& model, std::vector<double> props);
    void assign(int group_a, int group_b, int instance);
    int register_field(const std::string& name, double default_value, const char* unit = nullptr) {
        return fields.add(name, default_value, unit, bodies.size());
    }
    bool field_computed(int f) const;
    void add_pass(const std::string& name, std::vector<double> props);
    StableStep stable_timestep() { return monitor.stable_timestep(); }
    StableStep nominal_timestep() const { return monitor.nominal_timestep(); }
    void step();
    void prepare();
    bool contact_forces_current() const { return contact_forces_kept_; }
    std::size_t bond(int group_a, int group_b, double gap_tolerance);
    std::size_t intact_bonds() const;
    bool at_last_good() const { return at_last_good_; }
    StabilityLimits& stability_limits() { return monitor.detector.limits; }
    std::vector<Eigen::Matrix3d> ball_stress() const;
    double unbalanced_force_ratio() const;
    std::size_t active_contacts() const;
    // Row k of a set at the last force pass (forces/geometry.hpp row_*).
    Vec contact_normal(const ContactSet& s, std::size_t k) const { return row_normal(bodies, s, k); }
    Vec contact_point(const ContactSet& s, std::size_t k) const { return row_point(bodies, s, k); }
    double contact_gap(const ContactSet& s, std::size_t k) const { return row_gap(bodies, s, k); }
    double end_radius(const ContactSet& s, std::size_t k, bool end2) const { return row_end_radius(bodies, s, k, end2); }
    ContactKey row_keys(const ContactSet& s, std::size_t k) const { return row_key(bodies, walls, s, k); }
    std::uint64_t state_hash() const;
    void set_skin(double skin) { neighbours.skin = skin; }
    std::uint64_t rebuilds() const { return neighbours.rebuilds; }
    void mark_dirty() { neighbours.invalidate(); prepared = false; monitor.forget_nominal(); last_good_.drop(); }
    // Whether the ball–ball rows of a model go to it packed (force_sweep):
    // no model of the world has a rates stage and this one accumulates no field.
    bool packs_balls(const ModelInstance& inst) const;
    // After a checkpoint replaced the state: the caches derived from it renewed.
    void restored();

    // ---- the kernel's subsystems, each its own header's ----
    std::shared_ptr<PluginHost> host;  // (every world holds it: no model outlives its code)
    AssignmentTable assignment;        // groups and PFC's assignment table (contacts/)
    Instances instances;               // the contact-model instances with their tables (contacts/)
    std::vector<PassInstance> passes;  // in the order they run
    NeighbourLists neighbours;         // (detection/)
    PassContacts pass_contacts;        // the active contacts the passes see (only when a pass is loaded)
    bool prepared = false;             // forces are those of the current scene (prepare())

private:
    std::vector<std::uint8_t> field_at_default_;  // per field, this force pass (find_fields_at_default)
    std::vector<TableBuffers> table_buffers_;  // per set, in sets_' order
    // per-body lists of contact rows, for the sums taken body by body
    BodyContacts body_contacts_;
    std::vector<ContactSet*> sets_;
    std::vector<const ModelInstance*> set_owner_;
    ChunkedSums sums_;  // the deterministic reduction (reduction/chunked_sums.hpp)
    PackedTables packed_;  // what the packed paths keep per table (forces/packed_tables.hpp)
    bool any_accumulation_ = false;  // a force-stage model accumulates body fields
    bool swept_ = false;             // the last force pass ran force_sweep()
    bool contact_forces_kept_ = true;  // the last force pass wrote the packed rows' forces (contact_forces_wanted)
    bool in_range_marked_ = false;   // mark_ball_rows_in_range() ran at the current positions
    // What mark_ball_rows_in_range() found per ball–ball set: the rows in
    // range of batch b, listed from b * kContactBatch, and their count; on
    // the centre-force path (`listed`, for pack_centre_rows()) their centre
    // distances too.
    std::vector<RowsInRange> in_range_;
    void scatter_rows(std::uint32_t set_index, std::size_t begin, std::size_t end, const Chunk& chunk);
    void scatter_to_chunks(std::uint32_t set_index);
    void force_sweep(std::uint32_t set_index, bool with_geometry);
    StillInstances still_;  // instances of fixed balls only (forces/still_instances.hpp)
    LastGoodState last_good_;  // (monitor/last_good.hpp)
    bool at_last_good_ = false;

public:
    Monitor monitor;  // the stable step, the detector, the stop (monitor/monitor.hpp; after its inputs)

private:
    void take_snapshot();
    void restore_snapshot();
    void advance();

    void rebuild();
    void install(const CarryContext& carry, ModelInstance& inst, ContactSet& set, PairList& pairs, TableBuffers& t);
    void build_entries();
    void fill_pair_constants(ContactSet& set) const;
    void lay_out_columns(const ModelInstance& inst, ContactSet& set);
    void geometry(ModelInstance& inst, ContactSet& set);
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
    int call_model(ModelInstance& inst, ContactSet& set, std::size_t o, std::size_t m, std::uint32_t stage,
                   const ReadFields& fields, bool clear);
    void find_fields_at_default();
    ReadFields read_fields(const ModelInstance& inst) const;
    [[noreturn]] void model_failed(const ModelInstance& inst) const;
    void compute(ModelInstance& inst, ContactSet& set, std::uint32_t stage);
    void rates_stage();
    bool rates_stage_needed(const ModelInstance& inst) const;
    void mark_ball_rows_in_range();  // detection/range_test.cpp
    void mark_set_in_range(std::uint32_t set_index, bool list);
    void accumulate(const ModelInstance& owner, const ContactSet& s, std::uint32_t k, bool is_end2, std::size_t i);
    void record_breaks(ModelInstance& inst, ContactSet& set);
    // closing_kick > 0: reduce() takes the step's closing half kick of that
    // length block by block, right after the block's force sums, while its
    // forces and velocities are in cache (advance(), when no POST_FORCE pass
    // runs between them)
    void force_pass(double closing_kick = 0);
    void damp_body(std::size_t body, Vec& force, Vec& moment, double& local_work) const;
    bool finish_bodies(std::size_t first_body, std::size_t end_body, double& local_work);
    bool bodies_finite(std::size_t first_body, std::size_t end_body);
    bool reduce(double closing_kick);  // true: a body's state may be non-finite (check_finite() looks)
    void run_passes(std::uint32_t phase);
    bool has_passes(std::uint32_t phase) const;
    std::size_t body_blocks() const { return plab::body_blocks(bodies.size()); }
    std::vector<double> block_local_work_;  // per block: work of local and viscous damping (reduce)
    // the law of motion (integration/leapfrog.hpp); 1/m and 1/I cached by
    // prepare() (a change of mass or inertia marks the world dirty)
    Leapfrog leapfrog_;
    DriftInputs drift_inputs() const;
    void kick_and_drift(double dt);
    void take_drift(const DriftResult& r);
    void sum_energies(double dt);
};

} // namespace plab
