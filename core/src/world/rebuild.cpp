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



void Cycle::rebuild() {
    std::size_t rows = 0;
    for (const auto& inst : instances) rows += inst->balls.size() + inst->walls.size();
    const bool lean = rows > world.lean_rebuild_rows;
    if (lean) {  // the columns are laid out anew, zeroed, and build_entries() makes these
        for (auto& inst : instances)
            for (ContactSet* s : {&inst->balls, &inst->walls}) s->release_columns();
        tables.body_contacts.release();
        reduction.chunks.release();
    }
    // balls that left a periodic cell come back on the other side here, at a
    // rebuild only: between rebuilds the geometry takes minimum images, and
    // the drift's displacement since the build stays continuous
    if (world.bodies.cell.any()) {
        Bodies& B = world.bodies;
        for (std::size_t i = 0; i < B.size(); ++i) B.position[i] = B.cell.wrap(B.position[i], &B.velocity[i]);
    }
    neighbours.find_pairs(world.bodies, world.walls, assignment, instances, world.parallel_min, world.step_count, lean);
    tables.buffers.resize(2 * instances.size());  // as tables.sets: instance m's balls at 2m, walls at 2m + 1
    const CarryContext carry{world.bodies, world.walls, world.parallel_min, lean, world.lean_rebuild_rows};
    for (std::size_t m = 0; m < instances.size(); ++m) {
        ModelInstance& inst = *instances[m];
        keep_bonded_pairs(inst, inst.balls, neighbours.ball_pairs(m));
        keep_bonded_pairs(inst, inst.walls, neighbours.wall_pairs(m));
        install(carry, inst, inst.balls, neighbours.ball_pairs(m), tables.buffers[2 * m]);
        install(carry, inst, inst.walls, neighbours.wall_pairs(m), tables.buffers[2 * m + 1]);
    }
    neighbours.built(world.bodies);
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
    fill_pair_constants(world.bodies, set);
}

// Per-body lists of the contact rows touching each body, in (table, row)
// order (the reduction walks them, so sums do not depend on threads); the
// reduction's chunks for the rows; what the packed paths kept forgotten.
void Cycle::build_entries() {
    tables.list(instances, world.bodies.size());
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
        for (ContactSet* s : {&inst->balls, &inst->walls}) fill_pair_constants(world.bodies, *s);
    build_entries();
}

} // namespace plab
