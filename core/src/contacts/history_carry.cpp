#include "contacts/history_carry.hpp"

#include "common/buffers.hpp"

#include <algorithm>

namespace plab {

namespace {
// Row ranges of a rebuild's list worked on by the threads: a fixed count,
// so the work of each does not depend on the thread count.
constexpr std::size_t kRebuildParts = 8;
} // namespace

// The pair search walks the bodies in index order, and ids follow the
// indices: the pairs then arrive ordered by end 1, and sorting each run of
// one end 1 by end 2 (a dozen pairs) gives the same order as one sort of the
// whole list, in a fraction of its time. Bonded pairs kept beyond the range
// (keep_bonded_pairs) come last, and take the full sort.
void sort_by_keys(const CarryContext& c, const ContactSet& set, PairList& pairs) {
    auto key = [&](const std::array<std::int32_t, 2>& p) { return pair_key(c.bodies, c.walls, set.with_wall, p[0], p[1]); };
    auto by_key2 = [&](const auto& a, const auto& b) { return key(a).second < key(b).second; };
    const std::size_t n = pairs.size();
    const bool parallel = n >= c.parallel_min;
    // whether ordered by end 1, and whether a pair comes twice (equal ends, equal keys)
    int unordered = 0;
#pragma omp parallel for schedule(static) reduction(| : unordered) if (parallel)
    for (std::size_t r = 1; r < n; ++r) unordered |= key(pairs[r]).first < key(pairs[r - 1]).first;
    if (unordered) {
        std::sort(pairs.begin(), pairs.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
    } else {
        // ranges that start on a new end 1, so that no run is split
        std::size_t start[kRebuildParts + 1];
        start[0] = 0;
        for (std::size_t part = 1; part <= kRebuildParts; ++part) {
            std::size_t s = std::max(start[part - 1], n * part / kRebuildParts);
            while (s > 0 && s < n && key(pairs[s]).first == key(pairs[s - 1]).first) ++s;
            start[part] = s;
        }
#pragma omp parallel for schedule(static) if (parallel)
        for (std::size_t part = 0; part < kRebuildParts; ++part)
            for (auto a = pairs.begin() + start[part], end = pairs.begin() + start[part + 1]; a != end;) {
                const auto b = std::find_if(a, end, [&](const auto& p) { return key(p).first != key(*a).first; });
                std::sort(a, b, by_key2);
                a = b;
            }
    }
    int twice = 0;
#pragma omp parallel for schedule(static) reduction(| : twice) if (parallel)
    for (std::size_t r = 1; r < n; ++r) twice |= pairs[r] == pairs[r - 1];
    if (twice) pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
}

// A pair listed twice (a bond that is also a candidate) is kept once. The
// work is spread over the threads in kRebuildParts row ranges: on two
// threads the rebuild of an SPH scene was a tenth of the step's time, with
// one thread idle.
bool carry_history(const CarryContext& c, const ModelInstance& inst, ContactSet& set, PairList& pairs,
                   TableBuffers& t) {
    const bool parallel = pairs.size() >= c.parallel_min;
    if (!set.with_wall) {
        const BodyId* id = c.bodies.id.data();
        std::array<std::int32_t, 2>* p = pairs.data();
#pragma omp parallel for schedule(static) if (parallel)
        for (std::size_t r = 0; r < pairs.size(); ++r)
            if (id[p[r][0]] > id[p[r][1]]) std::swap(p[r][0], p[r][1]);  // end 1 has the lower id
    }
    sort_by_keys(c, set, pairs);
    const std::size_t n = pairs.size();
    const int stride = inst.stride;
    // t: this table's own buffers, reused: a rebuild allocates nothing once the lists stop growing
    fill(t.history, n * stride, 0.0);  // (fill: a block too small goes before the new one comes)
    fill(t.e1, n, 0);
    fill(t.e2, n, 0);
    // a wall row's last normal and interior flag say which face of a facet
    // its ball is on (facet_distance): survivors keep them, where the table
    // has them for its rows (not after a snapshot's rows come back)
    const bool sides = set.with_wall && set.normal.size() == 3 * set.size() && set.interior.size() == set.size();
    fill(t.normal, sides ? 3 * n : 0, 0.0);
    fill(t.interior, sides ? n : 0, std::uint8_t(1));
    auto row_key_of = [&](std::size_t k) { return row_key(c.bodies, c.walls, set, k); };
    // the old rows are sorted by the same keys: one merge per range finds
    // the survivors, from the first old row not below the range's first key
#pragma omp parallel for schedule(static) if (parallel)
    for (std::size_t part = 0; part < kRebuildParts; ++part) {
        const std::size_t r0 = n * part / kRebuildParts, r1 = n * (part + 1) / kRebuildParts;
        if (r0 == r1) continue;
        std::size_t old = 0, count = set.size();  // lower bound of the range's first key
        const auto first = pair_key(c.bodies, c.walls, set.with_wall, pairs[r0][0], pairs[r0][1]);
        while (count > 0) {
            const std::size_t half = count / 2;
            if (row_key_of(old + half) < first) { old += half + 1; count -= half + 1; }
            else count = half;
        }
        for (std::size_t r = r0; r < r1; ++r) {
            t.e1[r] = pairs[r][0];
            t.e2[r] = pairs[r][1];
            const auto key = pair_key(c.bodies, c.walls, set.with_wall, pairs[r][0], pairs[r][1]);
            while (old < set.size() && row_key_of(old) < key) ++old;
            double* row = t.history.data() + r * stride;
            if (old < set.size() && row_key_of(old) == key) {
                std::copy_n(set.history.data() + old * stride, stride, row);  // survivor keeps its history
                if (sides) {
                    std::copy_n(set.normal.data() + 3 * old, 3, t.normal.data() + 3 * r);
                    t.interior[r] = set.interior[old];
                }
            } else {
                for (int h = 0; h < stride; ++h) row[h] = inst.desc->history[h].default_value;
            }
        }
    }
    // swapped, not moved: the old list's buffers serve the next rebuild
    set.end1.swap(t.e1);
    set.end2.swap(t.e2);
    set.history.swap(t.history);
    if (c.frees_buffers(n)) {
        release(t.e1);
        release(t.e2);
        release(t.history);
        release(pairs);
    }
    return sides;
}

void take_sides(const CarryContext& c, ContactSet& set, TableBuffers& t) {
    set.normal.swap(t.normal);
    set.interior.swap(t.interior);
    if (c.frees_buffers(set.size())) {
        release(t.normal);
        release(t.interior);
    }
}

void keep_bonded_pairs(const ModelInstance& inst, const ContactSet& set, PairList& pairs) {
    const int slot = inst.desc->persist_slot;
    if (slot < 0) return;
    for (std::size_t k = 0; k < set.size(); ++k)
        if (set.history[k * inst.stride + slot] > 0) pairs.push_back({set.end1[k], set.end2[k]});
}

} // namespace plab
