// The force pipeline, the force–displacement phase of a cycle: the contact
// geometry of every candidate row, computed once by the host; each model
// called once per batch of rows, every batch packed the same way (the
// active rows only, the inputs and outputs the model declares), by one of
// three packers its kind selects (force_batch); the rates stage and the
// passes that turn its sums into states; the rows' forces scattered into
// the reduction's partial sums; the bonds that broke.
#pragma once

#include <plab_host/bodies.hpp>
#include <plab_host/fields.hpp>
#include <plab_host/walls.hpp>
#include <plab_host/world.hpp>

#include "contacts/assignment.hpp"
#include "contacts/body_contacts.hpp"
#include "contacts/model_instance.hpp"
#include "detection/range_test.hpp"
#include "forces/packed_tables.hpp"
#include "forces/still_instances.hpp"
#include "passes/passes.hpp"
#include "reduction/reduction.hpp"

#include <cstdint>
#include <functional>
#include <vector>

namespace plab {

struct DenseBatch;  // forces/packed_batch.hpp: the active rows of one batch, packed for the model

// The body fields a model reads, as its batches take them (abi.h): the
// columns in its `fields_read` order, and which of them hold their
// default at every body (plab_contact_batch::body_fields_at_default).
struct ReadFields {
    // 32: the SPH solid with hourglass control reads its density, sigma B/rho^2 (9),
    // the artificial stress (6) and the velocity gradient (9), 25 in all
    static constexpr std::size_t kMax = 32;  // (World::add_instance refuses more)
    static_assert(kMax <= 64, "one bit of at_default per field");
    const double* cols[kMax] = {};
    std::uint64_t at_default = 0;
};

// What the pipeline reads and writes.
struct ForceInputs {
    const int dim;
    const Bodies& bodies;
    const Walls& walls;
    BodyFields& fields;
    const AssignmentTable& groups;
    Instances& instances;
    const Passes& passes;
    const std::vector<ContactSet*>& sets;  // every table, instance m's at 2m (balls) and 2m + 1 (walls)
    const std::vector<const ModelInstance*>& set_owner;
    const BodyContacts& body_contacts;
    PassContacts& pass_contacts;
    std::vector<BondBreak>& bond_breaks;
    const double& time;
    const std::uint64_t& step_count;
    const double& last_dt;
    const std::size_t& parallel_min;
};

class ForcePipeline {
public:
    ForcePipeline(const ForceInputs& in, Reduction& reduction) : in_(in), reduction_(reduction) {}

    PackedTables packed;  // what the packed paths keep per table, their step limits among it

    // The contact forces at the current positions. `run_passes(phase)` runs
    // the passes of a phase: those of RATES_DONE run here, between a rates
    // stage and the forces.
    void run(const std::function<void(std::uint32_t)>& run_passes);
    // Whether the last run() summed the rows into the reduction's chunks
    // already (its sweeps did).
    bool rows_summed() const { return swept_; }
    // After a rebuild: what the packed paths kept of the old rows forgotten.
    void forget_rows();

    // Whether the ball–ball rows of a model go to it packed: no model of the
    // world has a rates stage over full columns, and this one accumulates
    // no field (or only a rates stage's, which is skipped).
    bool packs_balls(const ModelInstance& inst) const;
    // False for a field that only a skipped rates stage would fill.
    bool field_computed(int field) const;
    // Whether the packed ball–ball rows' forces are written at the next
    // run() (World::contact_forces_wanted), and were at the last.
    void write_contact_forces(bool wanted) { contact_forces_kept_ = wanted; }
    bool contact_forces_kept() const { return contact_forces_kept_; }
    // Whether the passes' contact distances hold at these positions (the
    // range test listed them).
    bool pass_distances_current() const { return in_range_marked_; }

private:
    void geometry(ModelInstance& inst, ContactSet& set);
    // How a table's rows reach its model (packer_of).
    enum class Packer : std::uint8_t { ball_pair, centre_pair, table };
    Packer packer_of(const ModelInstance& inst, const ContactSet& set) const;
    void force_sweep(std::uint32_t set_index);
    int force_batch(Packer packer, ModelInstance& inst, std::uint32_t set_index, std::size_t o, std::size_t m,
                    const ReadFields& fields, const Chunk& chunk, bool& exceeded);
    void rates_stage(const std::function<void(std::uint32_t)>& run_passes);
    bool rates_stage_needed(const ModelInstance& inst) const;
    void compute(ModelInstance& inst, ContactSet& set, std::uint32_t stage);
    int call_on_table(ModelInstance& inst, ContactSet& set, std::size_t o, std::size_t m, std::uint32_t stage,
                      const ReadFields& fields, bool clear);
    [[noreturn]] void model_failed(const ModelInstance& inst) const;
    void record_breaks(ModelInstance& inst, ContactSet& set);
    void find_fields_at_default();
    ReadFields read_fields(const ModelInstance& inst) const;
    // the range test (detection/range_test.cpp)
    void mark_ball_rows_in_range();
    void mark_set_in_range(std::uint32_t set_index, bool list);
    std::size_t range_test_rows(const ModelInstance& inst, std::uint32_t set_index, std::size_t begin,
                                std::size_t end, std::uint32_t* row, double* distance);
    // the packed paths (packed_batch.cpp; centre_force_batch.cpp for a model
    // with PLAB_MODEL_FORCE_AT_CENTRES)
    bool pack_ball_rows(const ModelInstance& inst, std::uint32_t set_index, std::size_t begin, std::size_t end,
                        DenseBatch& d);
    void unpack_rows(std::uint32_t set_index, const ModelInstance& inst, const DenseBatch& d, std::size_t begin,
                     const Chunk& chunk);
    bool pack_centre_rows(const ModelInstance& inst, std::uint32_t set_index, std::size_t begin, std::size_t end,
                          DenseBatch& d);
    void unpack_centre_rows(std::uint32_t set_index, const ModelInstance& inst, const DenseBatch& d,
                            std::size_t begin, const Chunk& chunk);

    ForceInputs in_;
    Reduction& reduction_;
    std::vector<std::uint8_t> field_at_default_;  // per field, this force pass (find_fields_at_default)
    StillInstances still_;                        // instances of fixed balls only
    bool swept_ = false;                          // the last run() ran force_sweep()
    bool contact_forces_kept_ = true;             // the last run() wrote the packed rows' forces
    bool in_range_marked_ = false;                // mark_ball_rows_in_range() ran at the current positions
    // What mark_ball_rows_in_range() found per ball–ball set: the rows in
    // range of batch b, listed from b * kContactBatch, and their count; on
    // the centre-force path (`listed`, for pack_centre_rows()) their centre
    // distances too.
    std::vector<RowsInRange> in_range_;
};

} // namespace plab
