#include "reduction/chunked_sums.hpp"

#include "common/buffers.hpp"

#include <algorithm>
#include <limits>
#include <type_traits>

namespace plab {

// A ball–wall chunk's partial sums over only the balls it touches (a few
// thousand rows touch balls spread over all of them): its slots are its
// balls in ascending order. The sums per body are the same as over lo..hi.
void ChunkedSums::list_chunk_bodies(const ContactSet& s, Chunk& ch) {
    const auto first = std::ptrdiff_t(chunk_bodies_.size());
    for (std::size_t k = ch.begin; k < ch.end; ++k) chunk_bodies_.push_back(s.end1[k]);
    std::sort(chunk_bodies_.begin() + first, chunk_bodies_.end());
    chunk_bodies_.erase(std::unique(chunk_bodies_.begin() + first, chunk_bodies_.end()), chunk_bodies_.end());
    std::vector<std::uint32_t>& slot = listed_slot_[ch.set];
    slot.resize(s.size());
    for (std::size_t k = ch.begin; k < ch.end; ++k)
        slot[k] = std::uint32_t(std::lower_bound(chunk_bodies_.begin() + first, chunk_bodies_.end(), s.end1[k]) -
                                (chunk_bodies_.begin() + first));
    ch.listed = true;
    ch.first_listed = std::size_t(first);
    ch.slots = chunk_bodies_.size() - std::size_t(first);
}

// Chunks of about eight batches each, so that two threads share a set
// evenly, at most 16 per set (below).
void ChunkedSums::build(const std::vector<ContactSet*>& sets, std::size_t parallel_min) {
    // At most 16 chunks per set: enough to share among the threads, and a
    // chunk's partial array spans its bodies plus the reach of its rows'
    // second ends (a layer of the packing), so more chunks cost memory:
    // 64 took ~170 B per ball on a settled pile of 1e5 balls.
    constexpr std::size_t batches_per_chunk = 8, max_chunks = 16;
    chunks_.clear();
    set_chunks_.assign(1, 0);
    chunk_bodies_.clear();
    listed_slot_.assign(sets.size(), {});
    for (std::uint32_t si = 0; si < sets.size(); ++si) {
        const ContactSet& s = *sets[si];
        const std::size_t n_batches = (s.size() + kContactBatch - 1) / kContactBatch;
        const std::size_t n_chunks = std::min(max_chunks, (n_batches + batches_per_chunk - 1) / batches_per_chunk);
        for (std::size_t c = 0; c < n_chunks; ++c)
            chunks_.push_back({si, kContactBatch * (n_batches * c / n_chunks),
                               std::min(s.size(), kContactBatch * (n_batches * (c + 1) / n_chunks)),
                               std::numeric_limits<std::int32_t>::max(), -1, 0});
        set_chunks_.push_back(std::uint32_t(chunks_.size()));
    }
    // the bodies each chunk's rows touch, a chunk per thread at a time
    std::size_t rows = 0;
    for (const ContactSet* s : sets) rows += s->size();
#pragma omp parallel for schedule(dynamic) if (rows >= parallel_min)
    for (std::size_t c = 0; c < chunks_.size(); ++c) {
        Chunk& ch = chunks_[c];
        const ContactSet& s = *sets[ch.set];
        for (std::size_t k = ch.begin; k < ch.end; ++k) {
            ch.lo = std::min(ch.lo, s.end1[k]);
            ch.hi = std::max(ch.hi, s.end1[k]);
            if (s.with_wall) continue;
            ch.lo = std::min(ch.lo, s.end2[k]);
            ch.hi = std::max(ch.hi, s.end2[k]);
        }
        ch.slots = ch.hi >= ch.lo ? std::size_t(ch.hi - ch.lo + 1) : 0;
    }
    std::size_t offset = 0;
    for (Chunk& ch : chunks_) {
        if (sets[ch.set]->with_wall && ch.slots > 0) list_chunk_bodies(*sets[ch.set], ch);
        ch.offset = offset;
        offset += kSlotDoubles * ch.slots;
    }
    fill(partial_, offset, 0.0);
}

void ChunkedSums::release() { plab::release(partial_); }

void ChunkedSums::all_taken() {
    for (Chunk& ch : chunks_) ch.zeroed = true;
}

namespace {
template <int D> using Int = std::integral_constant<int, D>;

// A chunk's slot added to a body's force f and moment m (the layout of
// add_to_slot(), slot_doubles()), then cleared for the next sweep.
template <int Dim, bool ForcesOnly>
inline void take_slot(Vec& f, Vec& m, double* slot) {
    constexpr std::size_t width = slot_doubles(Dim, ForcesOnly);
    if (Dim == 3) {
        f += Vec(slot);
        if (!ForcesOnly) m += Vec(slot + 3);
    } else {
        f.x() += slot[0];
        f.y() += slot[1];
        if (!ForcesOnly) m.z() += slot[2];
    }
    for (std::size_t c = 0; c < width; ++c) slot[c] = 0.0;
}
} // namespace

void ChunkedSums::add_to_bodies(Bodies& bodies, const Vec& gravity, std::size_t i0, std::size_t i1) {
    // column addresses in locals: Eigen's vector stores may alias anything
    Vec* force = bodies.force.data();
    Vec* moment = bodies.moment.data();
    const double* mass = bodies.mass.data();
    const Vec g = gravity;
    if (bodies.has_applied_loads()) {
        const Vec *applied_f = bodies.applied_force.data(), *applied_m = bodies.applied_moment.data();
        for (std::size_t i = i0; i < i1; ++i) {
            force[i] = mass[i] * g + applied_f[i];
            moment[i] = applied_m[i];
        }
    } else {
        for (std::size_t i = i0; i < i1; ++i) {
            force[i] = mass[i] * g;
            moment[i] = Vec::Zero();
        }
    }
    const auto take = [&](const Chunk& ch, auto d, auto forces_only) {
        constexpr int Dim = decltype(d)::value;
        constexpr bool F = decltype(forces_only)::value;
        double* p = partial_.data() + ch.offset;
        constexpr std::size_t width = slot_doubles(Dim, F);
        if (ch.listed) {  // its balls in [i0, i1), ascending
            const std::int32_t* first = chunk_bodies_.data() + ch.first_listed;
            const std::int32_t* q0 = std::lower_bound(first, first + ch.slots, std::int32_t(i0));
            const std::int32_t* q1 = std::lower_bound(q0, first + ch.slots, std::int32_t(i1));
            for (const std::int32_t* q = q0; q < q1; ++q)
                take_slot<Dim, F>(force[*q], moment[*q], p + width * std::size_t(q - first));
            return;
        }
        const std::size_t c0 = std::max(i0, std::size_t(std::max(ch.lo, 0))), c1 = std::min(i1, std::size_t(ch.hi + 1));
        for (std::size_t i = c0; i < c1; ++i) take_slot<Dim, F>(force[i], moment[i], p + width * (i - std::size_t(ch.lo)));
    };
    for (const Chunk& ch : chunks_) {
        if (bodies.dim == 3) ch.forces_only ? take(ch, Int<3>{}, std::true_type{}) : take(ch, Int<3>{}, std::false_type{});
        else ch.forces_only ? take(ch, Int<2>{}, std::true_type{}) : take(ch, Int<2>{}, std::false_type{});
    }
}

void ChunkedSums::clear(Chunk& ch, int dim) {
    if (!ch.zeroed) std::fill_n(partial_.data() + ch.offset, slot_doubles(dim, ch.forces_only) * ch.slots, 0.0);
    ch.zeroed = false;
}

} // namespace plab
