// Contact detection: a cell linked list builds Verlet lists of candidate
// pairs within (activity range + skin); the lists are rebuilt when a body has
// moved half a skin. Candidates are kept per model instance, sorted by the ids
// of their ends, and history is carried from the old list by that key.
#include "world.hpp"

#include "buffers.hpp"
#include "error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace plab {

bool ContactSet::keeps(std::uint32_t io_bit) const {
    if (!packed) return true;
    // no moment, no stiffness; step limits per batch (World::batch_limits_)
    if (model_flags & PLAB_MODEL_FORCE_AT_CENTRES) return false;
    const bool written = !(model_io & PLAB_IO_DECLARED) || (model_io & io_bit);
    return io_bit == 0 || written;
}

void ContactSet::resize_columns(std::size_t n, int n_acc) {
    forces_zero = false;  // (dt_limit below holds zeros, not kInf)
    fill(active, n, std::uint8_t(0));
    fill(interior, with_wall ? n : 0, std::uint8_t(1));
    fill(force, 3 * n, 0.0);
    // outputs the model writes; the others not kept at all (keeps())
    const struct { std::vector<double>* col; std::size_t width; std::uint32_t bit; } outputs[] = {
        {&moment1, 3, PLAB_IO_MOMENTS}, {&moment2, 3, PLAB_IO_MOMENTS}, {&k_t, 1, 0},
        {&k_r, 1, PLAB_IO_STIFFNESS_ROTATIONAL}, {&dt_limit, 1, PLAB_IO_DT_LIMIT}};
    for (const auto& o : outputs) {
        if (keeps(o.bit)) fill(*o.col, o.width * n, 0.0);
        else release(*o.col);
    }
    // what only the model reads, or only per-batch sums need: none when packed
    const std::size_t m = packed ? 0 : n;
    for (auto* v : {&normal, &point, &rel_velocity, &rel_angular_velocity}) fill(*v, 3 * m, 0.0);
    for (auto* v : {&gap, &distance, &radius1, &radius2, &mass1, &mass2, &eff_mass, &eff_radius, &strain, &slip,
                    &dashpot, &break_energy})
        fill(*v, m, 0.0);
    if (packed)  // not kept at all
        for (auto* v : {&normal, &point, &rel_velocity, &rel_angular_velocity, &gap, &distance, &radius1, &radius2,
                        &mass1, &mass2, &eff_mass, &eff_radius, &strain, &slip, &dashpot, &break_energy})
            release(*v);
    acc1.resize(std::size_t(n_acc));
    acc2.resize(std::size_t(n_acc));
    for (auto* acc : {&acc1, &acc2})
        for (auto& a : *acc) fill(a, n, 0.0);
}

std::vector<std::pair<const char*, std::vector<double>*>> ContactSet::double_columns() {
    return {{"normal", &normal}, {"gap", &gap}, {"distance", &distance}, {"rel_velocity", &rel_velocity},
            {"rel_angular_velocity", &rel_angular_velocity}, {"point", &point}, {"radius1", &radius1},
            {"radius2", &radius2}, {"mass1", &mass1}, {"mass2", &mass2}, {"eff_mass", &eff_mass},
            {"eff_radius", &eff_radius}, {"force", &force}, {"moment1", &moment1}, {"moment2", &moment2},
            {"strain", &strain}, {"slip", &slip}, {"dashpot", &dashpot}, {"k_t", &k_t}, {"k_r", &k_r},
            {"dt_limit", &dt_limit}, {"break_energy", &break_energy}};
}

void ContactSet::release_columns() {
    release(active);
    // a wall set's normal and interior flags say which face of a facet each
    // row's ball is on: install_pairs() carries them to the new rows
    if (!with_wall) release(interior);
    for (auto& [name, col] : double_columns())
        if (!with_wall || col != &normal) release(*col);
    release(batch_energy);
    for (auto* acc : {&acc1, &acc2})
        for (auto& a : *acc) release(a);
}

namespace {

// Candidate cut-off between two bodies for an instance, centre to centre.
double cutoff(const ModelInstance& inst, double r1, double r2, double skin) {
    if (inst.desc->range_kind == PLAB_RANGE_DISTANCE) return inst.range + skin;
    return r1 + r2 + std::max(inst.range, 0.0) + skin;
}

} // namespace

// From the largest displacement drift() found (none known: rebuild).
bool World::displacement_exceeds_skin() const {
    if (max_drift2_ < 0) return true;
    const double s = effective_skin();
    const double max_disp = std::sqrt(max_drift2_);
    // two bodies closing on each other, or a body and a moving wall
    return 2.0 * max_disp > s || max_disp + wall_motion_since_build_ > s;
}

void World::build_ball_pairs(std::vector<std::vector<std::array<std::int32_t, 2>>>& out) {
    const std::size_t n = bodies.size();
    if (n < 2 || instances_.empty()) return;
    const double s = effective_skin();
    double r_max = 0;
    for (double r : bodies.radius) r_max = std::max(r_max, r);
    double cell = 0;
    for (const auto& inst : instances_) cell = std::max(cell, cutoff(*inst, r_max, r_max, s));
    if (cell <= 0) return;

    Vec lo = bodies.position[0], hi = lo;
    for (const Vec& p : bodies.position) { lo = lo.cwiseMin(p); hi = hi.cwiseMax(p); }
    if (!(hi - lo).allFinite())  // a run blowing up: stop it here, before the grid overflows
        throw RunError("non-finite ball positions at step " + std::to_string(step_count) +
                       " (extent " + std::to_string((hi - lo).norm()) + " m); likely cause: a timestep above the stable limit");
    std::array<long, 3> dims{1, 1, 1};
    // coarsen the grid if it would have far more cells than bodies (counted
    // in doubles: a scattered run must not overflow the cell count)
    for (;;) {
        double total = 1;
        for (int c = 0; c < dim; ++c) total *= std::floor((hi[c] - lo[c]) / cell) + 1;
        if (total <= double(8 * n + 64)) break;
        cell *= 1.5;
    }
    for (int c = 0; c < dim; ++c) dims[c] = std::max(1L, long((hi[c] - lo[c]) / cell) + 1);
    auto cell_of = [&](const Vec& p, int c) { return std::min(dims[c] - 1, long((p[c] - lo[c]) / cell)); };
    auto flat = [&](long x, long y, long z) { return (z * dims[1] + y) * dims[0] + x; };
    const long n_cells = dims[0] * dims[1] * dims[2];
    std::vector<std::int32_t> start(n_cells + 1, 0), items(n), home(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Vec& p = bodies.position[i];
        home[i] = std::int32_t(flat(cell_of(p, 0), cell_of(p, 1), dim == 3 ? cell_of(p, 2) : 0));
        ++start[home[i] + 1];
    }
    std::partial_sum(start.begin(), start.end(), start.begin());
    {
        std::vector<std::int32_t> next(start.begin(), start.end() - 1);  // each cell's next free slot
        for (std::size_t i = 0; i < n; ++i) items[next[home[i]]++] = std::int32_t(i);
    }
    const int ng = int(groups_.size());
    const long zr = dim == 3 ? 1 : 0;
    // blocks of bodies list their pairs apart (threads take whole blocks),
    // then the lists are joined in block order: the order of one walk over
    // the bodies, for any thread count
    constexpr std::size_t block = 1024;
    const std::size_t n_blocks = (n + block - 1) / block;
    auto& block_pairs = rebuild_scratch_.block_pairs;  // [block][model]: cleared, not freed
    block_pairs.resize(n_blocks);
#pragma omp parallel for schedule(dynamic) if (n >= parallel_min)
    for (std::size_t b = 0; b < n_blocks; ++b) {
        auto& lists = block_pairs[b];
        lists.resize(out.size());
        for (auto& l : lists) l.clear();
        // the grid in this thread's locals: push_back() may allocate, after
        // which anything shared between the threads is read again
        const std::array<long, 3> d = dims;
        const Vec origin = lo;
        const double size = cell;
        const std::int32_t *first = start.data(), *item = items.data();
        auto cell_at = [&](const Vec& p, int c) { return std::min(d[c] - 1, long((p[c] - origin[c]) / size)); };
        for (std::size_t i = b * block; i < std::min(n, (b + 1) * block); ++i) {
            const Vec& pi = bodies.position[i];
            const long cx = cell_at(pi, 0), cy = cell_at(pi, 1), cz = zr ? cell_at(pi, 2) : 0;
            for (long z = std::max(0L, cz - zr); z <= std::min(d[2] - 1, cz + zr); ++z)
                for (long y = std::max(0L, cy - 1); y <= std::min(d[1] - 1, cy + 1); ++y)
                    for (long x = std::max(0L, cx - 1); x <= std::min(d[0] - 1, cx + 1); ++x) {
                        const long c = (z * d[1] + y) * d[0] + x;
                        for (std::int32_t t = first[c]; t < first[c + 1]; ++t) {
                            const std::int32_t j = item[t];
                            if (std::size_t(j) <= i) continue;
                            const int inst = cmat_[bodies.group[i] * ng + bodies.group[j]];
                            if (inst < 0) continue;
                            const double cut = cutoff(*instances_[inst], bodies.radius[i], bodies.radius[j], s);
                            if ((bodies.position[j] - pi).squaredNorm() <= cut * cut)
                                lists[inst].push_back({std::int32_t(i), j});
                        }
                    }
        }
    }
    for (std::size_t m = 0; m < out.size(); ++m) {
        std::size_t total = 0;
        for (const auto& lists : block_pairs) total += lists[m].size();
        clear_for(out[m], total);  // (out[m] is empty: rebuild() cleared it)
        for (const auto& lists : block_pairs) out[m].insert(out[m].end(), lists[m].begin(), lists[m].end());
    }
}

void World::build_wall_pairs(std::vector<std::vector<std::array<std::int32_t, 2>>>& out) const {
    if (walls.facets.empty() || instances_.empty()) return;
    const double s = effective_skin();
    const int ng = int(groups_.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Vec& p = bodies.position[i];
        for (std::size_t f = 0; f < walls.facets.size(); ++f) {
            const Facet& facet = walls.facets[f];
            const int inst = cmat_[bodies.group[i] * ng + walls.walls[facet.wall].group];
            if (inst < 0) continue;
            double dist;
            if (facet.kind == FacetKind::plane) dist = (p - facet.a).dot(facet.b);  // signed: behind is inside
            else dist = (closest_point(facet, p).point - p).norm();
            if (dist <= cutoff(*instances_[inst], bodies.radius[i], 0.0, s)) out[inst].push_back({std::int32_t(i), std::int32_t(f)});
        }
    }
}

// A bonded pair stays a candidate however far its ends have moved apart.
void World::keep_bonded_pairs(const ModelInstance& inst, const ContactSet& set,
                              std::vector<std::array<std::int32_t, 2>>& pairs) const {
    const int slot = inst.desc->persist_slot;
    if (slot < 0) return;
    for (std::size_t k = 0; k < set.size(); ++k)
        if (set.history[k * inst.stride + slot] > 0) pairs.push_back({set.end1[k], set.end2[k]});
}

namespace {
// Row ranges of a rebuild's list worked on by the threads: a fixed count,
// so the work of each does not depend on the thread count.
constexpr std::size_t kRebuildParts = 8;
} // namespace

// Replace a set's rows by new candidate pairs, carrying history by key
// (a pair listed twice — a bond that is also a candidate — is kept once).
// The work is spread over the threads in kRebuildParts row ranges: on two
// threads the rebuild of an SPH scene was a tenth of the step's time, with
// one thread idle.
void World::install_pairs(ModelInstance& inst, ContactSet& set, std::vector<std::array<std::int32_t, 2>>& pairs,
                          RebuildScratch::SetBuffers& t, bool lean) {
    const bool parallel = pairs.size() >= parallel_min;
    if (!set.with_wall) {
        const BodyId* id = bodies.id.data();
        std::array<std::int32_t, 2>* p = pairs.data();
#pragma omp parallel for schedule(static) if (parallel)
        for (std::size_t r = 0; r < pairs.size(); ++r)
            if (id[p[r][0]] > id[p[r][1]]) std::swap(p[r][0], p[r][1]);  // end 1 has the lower id
    }
    sort_by_keys(set, pairs);
    const std::size_t n = pairs.size();
    const int stride = inst.stride;
    // t: this set's own buffers, reused: a rebuild allocates nothing once the lists stop growing
    fill(t.history, n * stride, 0.0);  // (fill: a block too small goes before the new one comes)
    fill(t.e1, n, 0);
    fill(t.e2, n, 0);
    // a wall row's last normal and interior flag say which face of a facet
    // its ball is on (facet_distance): survivors keep them, where the set
    // has them for its rows (not after a snapshot's rows come back)
    const bool sides = set.with_wall && set.normal.size() == 3 * set.size() && set.interior.size() == set.size();
    fill(t.normal, sides ? 3 * n : 0, 0.0);
    fill(t.interior, sides ? n : 0, std::uint8_t(1));
    // the old rows are sorted by the same keys: one merge per range finds
    // the survivors, from the first old row not below the range's first key
#pragma omp parallel for schedule(static) if (parallel)
    for (std::size_t part = 0; part < kRebuildParts; ++part) {
        const std::size_t r0 = n * part / kRebuildParts, r1 = n * (part + 1) / kRebuildParts;
        if (r0 == r1) continue;
        std::size_t old = 0, count = set.size();  // lower bound of the range's first key
        const auto first = pair_keys(set.with_wall, pairs[r0][0], pairs[r0][1]);
        while (count > 0) {
            const std::size_t half = count / 2;
            if (row_keys(set, old + half) < first) { old += half + 1; count -= half + 1; }
            else count = half;
        }
        for (std::size_t r = r0; r < r1; ++r) {
            t.e1[r] = pairs[r][0];
            t.e2[r] = pairs[r][1];
            const auto key = pair_keys(set.with_wall, pairs[r][0], pairs[r][1]);
            while (old < set.size() && row_keys(set, old) < key) ++old;
            double* row = t.history.data() + r * stride;
            if (old < set.size() && row_keys(set, old) == key) {
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
    const bool free_buffers = lean || n > lean_rebuild_rows;
    if (free_buffers) {  // the old rows and the pairs go before the columns come
        release(t.e1);
        release(t.e2);
        release(t.history);
        release(pairs);
    }
    lay_out_columns(inst, set);
    if (sides) {
        set.normal.swap(t.normal);
        set.interior.swap(t.interior);
        if (free_buffers) {
            release(t.normal);
            release(t.interior);
        }
    }
    fill_pair_constants(set);
}

// A set's columns for its rows, packed or full as the world's models want
// (packs_balls): after a rebuild, a restore, or a pass that needs the full
// columns back.
void World::lay_out_columns(const ModelInstance& inst, ContactSet& set) {
    set.packed = !set.with_wall && packs_balls(inst);
    set.resize_columns(set.size(), int(inst.fields_accumulated.size()));
}

// `pairs` sorted in place by their keys (row_keys: end 1, then end 2), each
// pair once. build_ball_pairs() walks the bodies in index order, and ids
// follow the indices: the pairs then arrive ordered by end 1, and sorting
// each run of one end 1 by end 2 (a dozen pairs) gives the same order as one
// sort of the whole list, in a fraction of its time. Bonded pairs kept
// beyond the range (keep_bonded_pairs) come last, and take the full sort.
void World::sort_by_keys(const ContactSet& set, std::vector<std::array<std::int32_t, 2>>& pairs) const {
    auto key = [&](const std::array<std::int32_t, 2>& p) { return pair_keys(set.with_wall, p[0], p[1]); };
    auto by_key2 = [&](const auto& a, const auto& b) { return key(a).second < key(b).second; };
    const std::size_t n = pairs.size();
    const bool parallel = n >= parallel_min;
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

// A set is packed when force_sweep() takes the dense path for it: no rates
// stage runs over full columns (force_pass(): swept_), and its model
// accumulates nothing or only sums of a rates stage, which is skipped.
bool World::packs_balls(const ModelInstance& inst) const {
    for (const auto& other : instances_)
        if (other->desc->rates_stage && rates_stage_needed(*other)) return false;
    return inst.fields_accumulated.empty() || inst.desc->rates_stage;
}

// The radii and masses of the ends, for a model that reads the full columns
// (a packed set's go to its model packed, from the bodies).
void World::fill_pair_constants(ContactSet& set) const {
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

void World::rebuild() {
    std::size_t rows = 0;
    for (const auto& inst : instances_) rows += inst->balls.size() + inst->walls.size();
    const bool lean = rows > lean_rebuild_rows;
    if (lean) {  // install_pairs() lays the columns out anew, zeroed, and build_entries() makes these
        for (auto& inst : instances_)
            for (ContactSet* s : {&inst->balls, &inst->walls}) s->release_columns();
        release(entries_);
        release(partial_fm_);
    }
    auto& ball_pairs = rebuild_scratch_.ball_pairs;  // cleared, not freed: the next rebuild fills as many
    auto& wall_pairs = rebuild_scratch_.wall_pairs;
    ball_pairs.resize(instances_.size());
    wall_pairs.resize(instances_.size());
    for (auto* lists : {&ball_pairs, &wall_pairs})
        for (auto& l : *lists) l.clear();
    build_ball_pairs(ball_pairs);
    if (lean) release(rebuild_scratch_.block_pairs);  // joined into ball_pairs
    build_wall_pairs(wall_pairs);
    auto& buffers = rebuild_scratch_.sets;  // as sets_: instance m's balls at 2m, walls at 2m + 1
    buffers.resize(2 * instances_.size());
    for (std::size_t m = 0; m < instances_.size(); ++m) {
        keep_bonded_pairs(*instances_[m], instances_[m]->balls, ball_pairs[m]);
        keep_bonded_pairs(*instances_[m], instances_[m]->walls, wall_pairs[m]);
        install_pairs(*instances_[m], instances_[m]->balls, ball_pairs[m], buffers[2 * m], lean);
        install_pairs(*instances_[m], instances_[m]->walls, wall_pairs[m], buffers[2 * m + 1], lean);
    }
    position_at_build_ = bodies.position;
    wall_motion_since_build_ = 0;
    need_rebuild_ = false;
    ++rebuilds;
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

// Per-body lists of the contact rows touching each body, in (set, row)
// order: the reduction walks them, so sums do not depend on threads.
void World::build_entries() {
    sets_.clear();
    set_owner_.clear();
    for (auto& inst : instances_) {
        sets_.push_back(&inst->balls);
        set_owner_.push_back(inst.get());
        sets_.push_back(&inst->walls);
        set_owner_.push_back(inst.get());
    }
    // The rows of a packed centre-force set (SPH) are left out: their
    // stiffness is zero (nothing to add to sum_stiffness()), and a packed
    // set accumulates no field that a per-body sum would read.
    auto listed = [this](std::uint32_t si) {
        return !(sets_[si]->packed && (set_owner_[si]->desc->flags & PLAB_MODEL_FORCE_AT_CENTRES));
    };
    const std::size_t n = bodies.size();
    entry_start_.assign(n + 1, 0);
    for (std::uint32_t si = 0; si < sets_.size(); ++si) {
        const ContactSet* s = sets_[si];
        if (!listed(si)) continue;
        for (std::size_t k = 0; k < s->size(); ++k) {
            ++entry_start_[s->end1[k] + 1];
            if (!s->with_wall) ++entry_start_[s->end2[k] + 1];
        }
    }
    std::partial_sum(entry_start_.begin(), entry_start_.end(), entry_start_.begin());
    fill(entries_, std::size_t(entry_start_[n]), Entry{});
    std::vector<std::uint32_t> next(entry_start_.begin(), entry_start_.end() - 1);  // each body's next free entry
    constexpr std::uint32_t end2_bit = 1u << 31;
    for (std::uint32_t si = 0; si < sets_.size(); ++si) {
        const ContactSet* s = sets_[si];
        if (!listed(si)) continue;
        for (std::uint32_t k = 0; k < s->size(); ++k) {
            entries_[next[s->end1[k]]++] = {si, k};
            if (!s->with_wall) entries_[next[s->end2[k]]++] = {si, k | end2_bit};
        }
    }
    build_chunks();
    clear_batch_limits();  // (rows of the old list)
    any_accumulation_ = false;
    for (auto& inst : instances_) any_accumulation_ |= !inst->desc->rates_stage && !inst->fields_accumulated.empty();
}

// A ball–wall chunk's partial sums over only the balls it touches (a few
// thousand rows touch balls spread over all of them): its slots are its
// balls in ascending order. The sums per body are the same as over lo..hi.
void World::list_chunk_bodies(Chunk& ch) {
    const ContactSet& s = *sets_[ch.set];
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

// Chunks of the deterministic reduction (world.hpp): about eight batches
// each, so that two threads share a set evenly, at most 16 per set (below).
void World::build_chunks() {
    // At most 16 chunks per set: enough to share among the threads, and a
    // chunk's partial array spans its bodies plus the reach of its rows'
    // second ends (a layer of the packing), so more chunks cost memory:
    // 64 took ~170 B per ball on a settled pile of 1e5 balls.
    constexpr std::size_t batches_per_chunk = 8, max_chunks = 16;
    chunks_.clear();
    set_chunks_.assign(1, 0);
    chunk_bodies_.clear();
    listed_slot_.assign(sets_.size(), {});
    for (std::uint32_t si = 0; si < sets_.size(); ++si) {
        const ContactSet& s = *sets_[si];
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
    for (const ContactSet* s : sets_) rows += s->size();
#pragma omp parallel for schedule(dynamic) if (rows >= parallel_min)
    for (std::size_t c = 0; c < chunks_.size(); ++c) {
        Chunk& ch = chunks_[c];
        const ContactSet& s = *sets_[ch.set];
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
        if (sets_[ch.set]->with_wall && ch.slots > 0) list_chunk_bodies(ch);
        ch.offset = offset;
        offset += kSlotDoubles * ch.slots;
    }
    fill(partial_fm_, offset, 0.0);
    // the columns were just made or loaded: nothing is known to be uniform,
    // and any row may hold history
    held_.resize(sets_.size());
    live_.resize(sets_.size());
    for (std::uint32_t si = 0; si < sets_.size(); ++si) {
        held_[si].assign((sets_[si]->size() + kContactBatch - 1) / kContactBatch, HeldOutputs{});
        live_[si].assign(sets_[si]->size(), 1);
    }
}

} // namespace plab
