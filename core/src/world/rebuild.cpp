// The contact tables after a neighbour search: the new candidates installed
// with their history, their columns laid out for the models, the per-body
// lists and the reduction's chunks made for them.
#include "world/cycle.hpp"

#include "common/buffers.hpp"

#include <algorithm>
#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace plab {

// A set's columns for its rows, packed or full as the world's models want
// (ForcePipeline::packs_balls): after a rebuild, a restore, or a pass that needs the full
// columns back.
void Cycle::lay_out_columns(const ModelInstance& inst, ContactSet& set) {
    set.packed = !set.with_wall && forces.packs_balls(inst);
    set.resize_columns(set.size(), int(inst.fields_accumulated.size()));
}


// The radii and masses of the ends, for a model that reads the full columns
// (a packed set's go to its model packed, from the bodies).
void Cycle::fill_pair_constants(ContactSet& set) const {
    if (set.packed) return;
    for (std::size_t r = 0; r < set.size(); ++r) {
        const std::int32_t i = set.end1[r], j = set.end2[r];
        const double ri = bodies.radius[i], mi = bodies.mass[i];
        const double rj = set.with_wall ? 0.0 : bodies.radius[j], mj = set.with_wall ? kInf : bodies.mass[j];
        set.radius1[r] = ri;
        set.radius2[r] = rj;
        set.mass1[r] = mi;
        set.mass2[r] = mj;
        set.eff_mass[r] = set.with_wall ? mi : mi * mj / (mi + mj);  // a wall has infinite mass
        set.eff_radius[r] = set.with_wall ? ri : ri * rj / (ri + rj);
    }
}

void Cycle::rebuild() {
    std::size_t rows = 0;
    for (const auto& inst : instances) rows += inst->balls.size() + inst->walls.size();
    const bool lean = rows > lean_rebuild_rows;
    if (lean) {  // the columns are laid out anew, zeroed, and build_entries() makes these
        for (auto& inst : instances)
            for (ContactSet* s : {&inst->balls, &inst->walls}) s->release_columns();
        body_contacts_.release();
        reduction.chunks.release();
    }
    neighbours.find_pairs(bodies, walls, assignment, instances, parallel_min, step_count, lean);
    table_buffers_.resize(2 * instances.size());  // as sets_: instance m's balls at 2m, walls at 2m + 1
    const CarryContext carry{bodies, walls, parallel_min, lean, lean_rebuild_rows};
    for (std::size_t m = 0; m < instances.size(); ++m) {
        ModelInstance& inst = *instances[m];
        keep_bonded_pairs(inst, inst.balls, neighbours.ball_pairs(m));
        keep_bonded_pairs(inst, inst.walls, neighbours.wall_pairs(m));
        install(carry, inst, inst.balls, neighbours.ball_pairs(m), table_buffers_[2 * m]);
        install(carry, inst, inst.walls, neighbours.wall_pairs(m), table_buffers_[2 * m + 1]);
    }
    neighbours.built(bodies);
    build_entries();
#ifdef __GLIBC__
    // A lean rebuild frees and makes blocks of megabytes. glibc keeps freed
    // blocks in its heap (its mmap threshold rises to the largest block
    // freed, so later ones come from the heap, which shrinks only from its
    // top), and their pages would stay resident: ~15 MB on a settled pile of
    // 1e5 balls. malloc_trim() gives the free pages back.
    if (lean) malloc_trim(0);
#endif
}

// A table's rows become the new candidates, with their history carried by
// key (contacts/history_carry.hpp), its columns laid out for them.
void Cycle::install(const CarryContext& carry, ModelInstance& inst, ContactSet& set, PairList& pairs,
                    TableBuffers& t) {
    const bool sides = carry_history(carry, inst, set, pairs, t);
    lay_out_columns(inst, set);
    if (sides) take_sides(carry, set, t);
    fill_pair_constants(set);
}

// Per-body lists of the contact rows touching each body, in (set, row)
// order: the reduction walks them, so sums do not depend on threads.
void Cycle::build_entries() {
    sets_.clear();
    set_owner_.clear();
    for (auto& inst : instances) {
        sets_.push_back(&inst->balls);
        set_owner_.push_back(inst.get());
        sets_.push_back(&inst->walls);
        set_owner_.push_back(inst.get());
    }
    // The rows of a packed centre-force set (SPH) are left out: their
    // stiffness is zero (nothing to add to sum_stiffness()), and a packed
    // set accumulates no field that a per-body sum would read.
    std::vector<std::uint8_t> listed(sets_.size());
    for (std::uint32_t si = 0; si < sets_.size(); ++si)
        listed[si] = !(sets_[si]->packed && (set_owner_[si]->desc->flags & PLAB_MODEL_FORCE_AT_CENTRES));
    body_contacts_.build(sets_, listed, bodies.size());
    reduction.build();
    forces.forget_rows();  // (rows of the old list)
}

// The radii and masses of the ends from the bodies, whatever a checkpoint
// held (files written before they were kept for inactive rows lack them);
// the nominal step recomputed from the state, as the uninterrupted run did.
void Cycle::restored() {
    monitor.forget_nominal();
    last_good_.drop();
    for (auto& inst : instances)
        for (ContactSet* s : {&inst->balls, &inst->walls}) fill_pair_constants(*s);
    build_entries();
}

} // namespace plab
