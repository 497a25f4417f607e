// The deterministic reduction of contact forces onto bodies. Each contact
// table's rows are cut into chunks of whole batches, their number a function
// of the row count only (never of the threads). A chunk adds its active
// rows' forces and moments, in row order, into its own slots over the bodies
// it touches, and the bodies take the chunks' slots in chunk order: the same
// sums for any thread count.
#pragma once

#include <plab_host/bodies.hpp>

#include "contacts/contact_set.hpp"

#include <cstdint>
#include <vector>

namespace plab {

// The doubles of a slot in use: only what can be nonzero, so that the
// chunks clear, scatter into and add no more than that. 3D: force, then
// moment; 2D: fx, fy and the moment about z. Forces only (the centre-force
// path, no moments): 3D fx, fy, fz; 2D fx, fy.
constexpr std::size_t slot_doubles(int dim, bool forces_only) {
    return dim == 2 ? (forces_only ? 2 : 3) : (forces_only ? 3 : 6);
}
constexpr std::size_t kSlotDoubles = 6;  // the room of a slot (the widest layout)
inline void add_to_slot_2d(double* slot, double fx, double fy, double mz) {
    slot[0] += fx;
    slot[1] += fy;
    slot[2] += mz;
}
inline void add_to_slot_3d(double* slot, const Vec& f, const Vec& m) {
    for (int c = 0; c < 3; ++c) { slot[c] += f[c]; slot[3 + c] += m[c]; }
}
inline void add_to_slot(int dim, double* slot, const Vec& f, const Vec& m) {
    if (dim == 2) add_to_slot_2d(slot, f[0], f[1], m[2]);
    else add_to_slot_3d(slot, f, m);
}

struct Chunk {
    std::uint32_t set;
    std::size_t begin, end;  // rows
    std::int32_t lo, hi;     // bodies touched (hi < lo: none)
    std::size_t offset;      // into the slots
    // Bodies with a slot: every body lo..hi, or, for a `listed` chunk
    // (ball–wall rows touch a few balls spread over all of them), only the
    // balls it touches, ascending, row k's ball at listed_slot(set)[k].
    std::size_t slots = 0;
    // the last sweep added forces alone (the centre-force path, which has
    // no moments): its slots are slot_doubles(dim, true) wide
    bool forces_only = false;
    // every slot holds zero: add_to_bodies() clears what it takes (its
    // lines are then in cache, a separate fill would load them again), so
    // the next sweep need not clear the chunk
    bool zeroed = true;
    bool listed = false;
    std::size_t first_listed = 0;
};

class ChunkedSums {
public:
    // Chunks for the tables (in the world's set order) after a rebuild.
    void build(const std::vector<ContactSet*>& sets, std::size_t parallel_min);
    void release();  // the slots freed (a lean rebuild); build() makes them anew

    std::uint32_t first_chunk(std::uint32_t set) const { return set_chunks_[set]; }
    std::uint32_t end_chunk(std::uint32_t set) const { return set_chunks_[set + 1]; }
    Chunk& chunk(std::uint32_t c) { return chunks_[c]; }
    double* slots(const Chunk& ch) { return partial_.data() + ch.offset; }
    // a listed chunk's slot of each row of its set
    const std::uint32_t* listed_slot(std::uint32_t set) const { return listed_slot_[set].data(); }
    // Before a sweep adds into chunk ch (and before it sets the chunk's
    // width): the slots the last sweep wrote, at its width, to zero, unless
    // add_to_bodies() left them so.
    void clear(Chunk& ch, int dim);
    // Bodies [i0, i1): force = gravity and applied loads plus the chunks'
    // slots in chunk order, each slot cleared as it is taken.
    void add_to_bodies(Bodies& bodies, const Vec& gravity, std::size_t i0, std::size_t i1);
    void all_taken();  // after add_to_bodies() over every body: every chunk zeroed

private:
    std::vector<std::int32_t> chunk_bodies_;
    std::vector<std::vector<std::uint32_t>> listed_slot_;
    std::vector<Chunk> chunks_;
    std::vector<std::uint32_t> set_chunks_;  // chunks of set si: [set_chunks_[si], set_chunks_[si + 1])
    std::vector<double> partial_;
    void list_chunk_bodies(const ContactSet& s, Chunk& ch);
};

} // namespace plab
