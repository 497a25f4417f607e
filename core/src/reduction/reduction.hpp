// The reduction: each body's force and moment from gravity, its applied
// loads and its contacts' forces, summed in a fixed order (chunked_sums.hpp),
// then the body fields its models accumulate, PFC's local and viscous
// damping, and the walls' force and moment from their contacts.
#pragma once

#include <plab_host/bodies.hpp>
#include <plab_host/energies.hpp>
#include <plab_host/fields.hpp>
#include <plab_host/walls.hpp>

#include "contacts/body_contacts.hpp"
#include "contacts/model_instance.hpp"
#include "integration/leapfrog.hpp"
#include "reduction/chunked_sums.hpp"

#include <vector>

namespace plab {

// What the reduction reads and writes: the world's bodies, walls and fields,
// and the contact tables.
struct ReductionInputs {
    const int dim;
    Bodies& bodies;
    Walls& walls;
    BodyFields& fields;
    const Vec& gravity;
    const Instances& instances;
    const std::vector<ContactSet*>& sets;  // every table, instance m's at 2m (balls) and 2m + 1 (walls)
    const std::vector<const ModelInstance*>& set_owner;
    const BodyContacts& body_contacts;
    Energies& energies;  // takes the damping's work
    const double& last_dt;
    const std::size_t& parallel_min;
};

class Reduction {
public:
    explicit Reduction(const ReductionInputs& in) : in_(in) {}

    ChunkedSums chunks;  // the partial sums per chunk of rows
    // After a rebuild: the chunks for the tables, and whether a force-stage
    // model accumulates body fields (finish_bodies() then sums them).
    void build();

    // What each active row of [begin, end) of table `set` adds to its two
    // bodies, into the partial sums of its chunk, and the batch's energies.
    void scatter_rows(std::uint32_t set, std::size_t begin, std::size_t end, const Chunk& chunk);
    // Every chunk of a table so (the rows of a force pass without sweeps).
    void scatter_to_chunks(std::uint32_t set);
    // Contact row k's contributions to the fields its model accumulates, for
    // body i at end 1 or end 2.
    void accumulate(const ModelInstance& owner, const ContactSet& s, std::uint32_t k, bool is_end2, std::size_t i);
    // The bodies' sums, block by block; `rows_summed`: the sweeps scattered
    // the rows already. closing_kick > 0: the step's closing half kick of
    // that length, block by block, right after the block's sums, while its
    // forces and velocities are in cache. True when a body's state may be
    // non-finite (Monitor::check_finite() looks).
    bool reduce(double closing_kick, bool rows_summed, Leapfrog& leapfrog);

private:
    void damp_body(std::size_t body, Vec& force, Vec& moment, double& local_work) const;
    bool finish_bodies(std::size_t first_body, std::size_t end_body, double& local_work);
    bool bodies_finite(std::size_t first_body, std::size_t end_body);
    void sum_wall_loads();

    ReductionInputs in_;
    bool any_accumulation_ = false;         // a force-stage model accumulates body fields
    std::vector<double> block_local_work_;  // per block: work of local and viscous damping
};

} // namespace plab
