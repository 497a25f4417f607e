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
#include "contacts/contact_tables.hpp"
#include "contacts/history_carry.hpp"
#include "contacts/model_instance.hpp"
#include "detection/neighbour_lists.hpp"
#include "detection/range_test.hpp"
#include "forces/force_pipeline.hpp"
#include "integration/clump_motion.hpp"
#include "integration/leapfrog.hpp"
#include "monitor/last_good.hpp"
#include "monitor/monitor.hpp"
#include "passes/passes.hpp"
#include "reduction/reduction.hpp"

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace plab {

class Cycle {
public:
    // The cycle of world `w`, which owns the state the cycle runs on.
    Cycle(World& w, std::shared_ptr<PluginHost> host);
    ~Cycle();
    Cycle(const Cycle&) = delete;
    Cycle& operator=(const Cycle&) = delete;

    World& world;  // the state it runs on (plab_host/world.hpp)

    // ---- what the World's functions of the same names do, and the restart ----
    void step();
    void prepare();
    bool at_last_good() const { return at_last_good_; }
    void mark_dirty() { neighbours.invalidate(); prepared = false; monitor.forget_nominal(); last_good_.drop(); }
    // After a checkpoint replaced the state: the caches derived from it renewed.
    void restored();

    // ---- the kernel's subsystems, each its own header's ----
    std::shared_ptr<PluginHost> host;  // (every world holds it: no model outlives its code)
    AssignmentTable assignment;        // groups and PFC's assignment table (contacts/)
    Instances instances;               // the contact-model instances with their tables (contacts/)
    NeighbourLists neighbours;         // (detection/)
    PassContacts pass_contacts;        // the active contacts the passes see (only when a pass is loaded)
    Passes passes;                     // (passes/; after the contacts they see)
    bool prepared = false;             // forces are those of the current scene (prepare())

private:
    // every table in one list (instance m's balls at 2m, walls at 2m + 1),
    // their history-carry buffers, each body's rows
    ContactTables tables;
    LastGoodState last_good_;
    bool at_last_good_ = false;
    Leapfrog leapfrog_;  // the law of motion; 1/m and 1/I cached by prepare()
    ClumpMotion clump_motion_;  // the clumps' (their pebbles are the leapfrog's balls, held)
    ClumpEnergies clump_energies_;  // of the last step's closing kick

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
    // the tables after a neighbour search (rebuild.cpp)
    void rebuild();
    void install(const CarryContext& carry, ModelInstance& inst, ContactSet& set, PairList& pairs, TableBuffers& t);
    void build_entries();
    void lay_out_columns(const ModelInstance& inst, ContactSet& set);
    // the law of motion's first half and the energies (cycle.cpp)
    DriftInputs drift_inputs() const;
    void kick_and_drift(double dt);
    void take_drift(const DriftResult& r);
    void sum_energies(double dt);
    // the clumps' sums, closing half kick (0: none) and energies after a force pass
    void finish_clumps(double half_dt, double dt);
};

} // namespace plab
