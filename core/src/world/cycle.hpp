// The cycle of the DEM kernel, behind the host API's World
// (plab_host/world.hpp): it holds the kernel's subsystems — the assignment
// table and the model instances with their contact tables, the neighbour
// lists, the force pipeline, the reduction, the leapfrog, the monitor — and
// runs their phases in PFC's order on the world's state. Physics lives in
// plug-ins; the force pipeline computes contact geometry once (Yade's Ig2)
// and hands it to each model in batches, and the reduction sums forces onto
// bodies in a fixed order, so the answer does not depend on the thread count.
#pragma once

#include <plab_host/world.hpp>

#include "contacts/assignment.hpp"
#include "contacts/body_contacts.hpp"
#include "contacts/history_carry.hpp"
#include "contacts/model_instance.hpp"
#include "detection/neighbour_lists.hpp"
#include "detection/range_test.hpp"
#include "forces/force_pipeline.hpp"
#include "integration/leapfrog.hpp"
#include "monitor/last_good.hpp"
#include "monitor/monitor.hpp"
#include "reduction/reduction.hpp"

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace plab {

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
    bool field_computed(int f) const { return forces.field_computed(f); }
    void add_pass(const std::string& name, std::vector<double> props);
    StableStep stable_timestep() { return monitor.stable_timestep(); }
    StableStep nominal_timestep() const { return monitor.nominal_timestep(); }
    void step();
    void prepare();
    bool contact_forces_current() const { return forces.contact_forces_kept(); }
    std::size_t bond(int group_a, int group_b, double gap_tolerance);
    std::size_t intact_bonds() const;
    bool at_last_good() const { return at_last_good_; }
    StabilityLimits& stability_limits() { return monitor.detector.limits; }
    std::vector<Eigen::Matrix3d> ball_stress() const;
    double unbalanced_force_ratio() const;
    std::size_t active_contacts() const;
    std::uint64_t state_hash() const;
    void set_skin(double skin) { neighbours.skin = skin; }
    std::uint64_t rebuilds() const { return neighbours.rebuilds; }
    void mark_dirty() { neighbours.invalidate(); prepared = false; monitor.forget_nominal(); last_good_.drop(); }
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
    // the contact tables in one list, instance m's balls at 2m, walls at 2m + 1
    std::vector<ContactSet*> sets_;
    std::vector<const ModelInstance*> set_owner_;
    std::vector<TableBuffers> table_buffers_;  // per table: the carry of history across a rebuild
    BodyContacts body_contacts_;               // per body: its rows, for the sums taken body by body
    LastGoodState last_good_;
    bool at_last_good_ = false;
    Leapfrog leapfrog_;  // the law of motion; 1/m and 1/I cached by prepare()

public:
    Reduction reduction;  // (after the tables it reads)
    ForcePipeline forces;
    Monitor monitor;  // the stable step, the detector, the stop (after the packed step limits it reads)

private:
    void take_snapshot();
    void restore_snapshot();
    void advance();
    // closing_kick > 0: the reduction takes the step's closing half kick of
    // that length block by block (advance(), when no POST_FORCE pass runs
    // between them)
    void force_pass(double closing_kick = 0);
    void run_passes(std::uint32_t phase);
    bool has_passes(std::uint32_t phase) const;
    // the tables after a neighbour search (rebuild.cpp)
    void rebuild();
    void install(const CarryContext& carry, ModelInstance& inst, ContactSet& set, PairList& pairs, TableBuffers& t);
    void build_entries();
    void fill_pair_constants(ContactSet& set) const;
    void lay_out_columns(const ModelInstance& inst, ContactSet& set);
    // the law of motion's first half and the energies (cycle.cpp)
    DriftInputs drift_inputs() const;
    void kick_and_drift(double dt);
    void take_drift(const DriftResult& r);
    void sum_energies(double dt);
};

} // namespace plab
