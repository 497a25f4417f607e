#include "detection/neighbour_lists.hpp"

#include <plab_host/errors.hpp>

#include "common/buffers.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace plab {

namespace {

// Candidate cut-off between two bodies for an instance, centre to centre.
double cutoff(const ModelInstance& inst, double r1, double r2, double skin) {
    if (inst.desc->range_kind == PLAB_RANGE_DISTANCE) return inst.range + skin;
    return r1 + r2 + std::max(inst.range, 0.0) + skin;
}

} // namespace

double NeighbourLists::effective_skin(const Bodies& bodies) const {
    if (skin >= 0) return skin;
    double sum = 0;
    for (double r : bodies.radius) sum += r;
    return bodies.size() ? 0.25 * sum / double(bodies.size()) : 0.0;
}

// From the largest displacement the drift found (none known: rebuild).
bool NeighbourLists::stale(const Bodies& bodies) const {
    if (invalidated_ || max_drift2_ < 0) return true;
    const double s = effective_skin(bodies);
    const double max_disp = std::sqrt(max_drift2_);
    // two bodies closing on each other (across a sheared boundary, also by
    // the cell's slide since the build), or a body and a moving wall
    return 2.0 * max_disp + slid_since_build(bodies.cell) > s || max_disp + wall_motion_ > s;
}

// How far the image across a sheared y boundary has slid along x since the
// build (the offset is kept modulo L_x: the nearest difference).
double NeighbourLists::slid_since_build(const PeriodicCell& cell) const {
    if (!cell.sheared) return 0.0;
    const double d = cell.shear_offset - offset_at_build_, L = cell.length(0);
    return std::fabs(d - L * std::nearbyint(d / L));
}

void NeighbourLists::find_pairs(const Bodies& bodies, const Walls& walls, const AssignmentTable& table,
                                const Instances& instances, std::size_t parallel_min, std::uint64_t step,
                                bool lean) {
    ball_pairs_.resize(instances.size());
    wall_pairs_.resize(instances.size());
    for (auto* lists : {&ball_pairs_, &wall_pairs_})
        for (auto& l : *lists) l.clear();
    find_ball_pairs(bodies, table, instances, parallel_min, step);
    if (lean) release(block_pairs_);  // joined into ball_pairs_
    find_wall_pairs(bodies, walls, table, instances);
}

void NeighbourLists::built(const Bodies& bodies) {
    position_at_build_ = bodies.position;
    offset_at_build_ = bodies.cell.shear_offset;
    wall_motion_ = 0;
    invalidated_ = false;
    ++rebuilds;
}

void NeighbourLists::restore(Saved s) {
    invalidated_ = s.invalidated;
    position_at_build_ = std::move(s.position_at_build);
    wall_motion_ = s.wall_motion;
}

void NeighbourLists::find_ball_pairs(const Bodies& bodies, const AssignmentTable& table, const Instances& instances,
                                     std::size_t parallel_min, std::uint64_t step) {
    auto& out = ball_pairs_;
    const int dim = bodies.dim;
    const std::size_t n = bodies.size();
    if (bodies.cell.any()) return find_ball_pairs_periodic(bodies, table, instances, parallel_min);
    if (n < 2 || instances.empty()) return;
    const double s = effective_skin(bodies);
    double r_max = 0;
    for (double r : bodies.radius) r_max = std::max(r_max, r);
    double cell = 0;
    for (const auto& inst : instances) cell = std::max(cell, cutoff(*inst, r_max, r_max, s));
    if (cell <= 0) return;

    Vec lo = bodies.position[0], hi = lo;
    for (const Vec& p : bodies.position) { lo = lo.cwiseMin(p); hi = hi.cwiseMax(p); }
    if (!(hi - lo).allFinite())  // a run blowing up: stop it here, before the grid overflows
        throw RunError("non-finite ball positions at step " + std::to_string(step) +
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
    const int ng = table.group_count();
    const int* cmat = table.table().data();  // (a local: the pair loop reads it per candidate)
    const long zr = dim == 3 ? 1 : 0;
    // blocks of bodies list their pairs apart (threads take whole blocks),
    // then the lists are joined in block order: the order of one walk over
    // the bodies, for any thread count
    constexpr std::size_t block = 1024;
    const std::size_t n_blocks = (n + block - 1) / block;
    auto& block_pairs = block_pairs_;  // [block][model]: cleared, not freed
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
        // the pebbles of one clump never touch (null: no clump in the world)
        const std::int32_t* clump = bodies.clump.size() == n ? bodies.clump.data() : nullptr;
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
                            const int inst = cmat[bodies.group[i] * ng + bodies.group[j]];
                            if (inst < 0) continue;
                            if (clump && clump[i] >= 0 && clump[i] == clump[j]) continue;
                            const double cut = cutoff(*instances[inst], bodies.radius[i], bodies.radius[j], s);
                            if ((bodies.position[j] - pi).squaredNorm() <= cut * cut)
                                lists[inst].push_back({std::int32_t(i), j});
                        }
                    }
        }
    }
    for (std::size_t m = 0; m < out.size(); ++m) {
        std::size_t total = 0;
        for (const auto& lists : block_pairs) total += lists[m].size();
        clear_for(out[m], total);  // (out[m] is empty: find_pairs() cleared it)
        for (const auto& lists : block_pairs) out[m].insert(out[m].end(), lists[m].begin(), lists[m].end());
    }
}

namespace {

// The neighbour cells of cell x along one axis of n cells: x - 1, x, x + 1
// clamped to the grid, or, along a periodic axis, taken modulo n (each
// once: a periodic axis of one or two cells has fewer than three).
int neighbour_cells(long x, long n, bool periodic, long out[3]) {
    int count = 0;
    for (long o = -1; o <= 1; ++o) {
        long c = x + o;
        if (periodic) c = (c % n + n) % n;
        else if (c < 0 || c >= n) continue;
        bool seen = false;
        for (int k = 0; k < count; ++k) seen |= out[k] == c;
        if (!seen) out[count++] = c;
    }
    return count;
}

// The grid rows (along y) around a ball at p and, in each, the columns
// (along x) to search. In a sheared cell a row across the y boundary holds
// balls whose images slid along x by the offset: its columns are those
// around p moved back by the offset (the grid is at least a cut-off wide,
// so one column either side still covers the range). In a grid of fewer
// than three rows a row may be both across the boundary and not: every
// column is searched (nx -1).
struct RowsAround {
    long y[3];
    long x[3][3];
    int nx[3];
};
int rows_around(const PeriodicCell& pc, const Vec& p, const std::array<long, 3>& dims, const Vec& size, const Vec& lo,
                RowsAround& out) {
    auto column = [&](double x) {
        if (pc.periodic[0]) x -= pc.length(0) * std::floor((x - lo[0]) / pc.length(0));
        return std::max(0L, std::min(dims[0] - 1, long((x - lo[0]) / size[0])));
    };
    const long cy = std::max(0L, std::min(dims[1] - 1, long((p[1] - lo[1]) / size[1])));
    const int ny = neighbour_cells(cy, dims[1], pc.periodic[1], out.y);
    for (int r = 0; r < ny; ++r) {
        if (pc.sheared && dims[1] < 3) { out.nx[r] = -1; continue; }
        double shift = 0;  // the slide of the row's images seen from p
        if (pc.sheared) shift = out.y[r] == 0 && cy == dims[1] - 1 ? pc.shear_offset
                                : out.y[r] == dims[1] - 1 && cy == 0 ? -pc.shear_offset : 0.0;
        out.nx[r] = neighbour_cells(column(p[0] - shift), dims[0], pc.periodic[0], out.x[r]);
    }
    return ny;
}

} // namespace

// Refuses a periodic cell narrower than twice the largest candidate
// cut-off along a periodic axis: a pair would then be in range at two
// images, and the minimum image would no longer be the contact.
void check_periodic_cell(const PeriodicCell& cell, int dim, double cut) {
    static const char* axis[] = {"x", "y", "z"};
    for (int c = 0; c < dim; ++c) {
        if (!cell.periodic[c] || cell.length(c) >= 2.0 * cut) continue;
        throw InputError("scene.domain.periodic", "the periodic cell (domain.max - domain.min) is " +
                         std::to_string(cell.length(c)) + " m wide along " + axis[c] +
                         "; valid: at least 2 x (largest activity range + skin) = " + std::to_string(2.0 * cut) +
                         " m (two of the largest balls, the model's range and the skin)");
    }
}

// find_ball_pairs() in a periodic cell: the grid spans the cell exactly
// along a periodic axis (positions were wrapped into it at this rebuild),
// its cells wrap around, and a pair's distance is its minimum image's.
void NeighbourLists::find_ball_pairs_periodic(const Bodies& bodies, const AssignmentTable& table,
                                              const Instances& instances, std::size_t parallel_min) {
    auto& out = ball_pairs_;
    const int dim = bodies.dim;
    const std::size_t n = bodies.size();
    const PeriodicCell& pc = bodies.cell;
    if (n == 0 || instances.empty()) return;
    const double s = effective_skin(bodies);
    double r_max = 0;
    for (double r : bodies.radius) r_max = std::max(r_max, r);
    double cut_max = 0;
    for (const auto& inst : instances) cut_max = std::max(cut_max, cutoff(*inst, r_max, r_max, s));
    if (cut_max <= 0) return;
    check_periodic_cell(pc, dim, cut_max);
    if (n < 2) return;
    Vec lo = bodies.position[0], hi = lo;
    for (const Vec& p : bodies.position) { lo = lo.cwiseMin(p); hi = hi.cwiseMax(p); }
    if (!(hi - lo).allFinite()) throw RunError("non-finite ball positions in the periodic cell");
    std::array<long, 3> dims{1, 1, 1};
    Vec size = Vec::Constant(cut_max);
    for (double grow = 1;; grow *= 1.5) {
        double total = 1;
        for (int c = 0; c < dim; ++c) {
            if (pc.periodic[c]) { lo[c] = pc.lo[c]; hi[c] = pc.hi[c]; }
            const double extent = hi[c] - lo[c];
            dims[c] = pc.periodic[c] ? std::max(1L, long(extent / (grow * cut_max)))
                                     : std::max(1L, long(extent / (grow * cut_max)) + 1);
            size[c] = pc.periodic[c] ? extent / double(dims[c]) : grow * cut_max;
            total *= double(dims[c]);
        }
        if (total <= double(8 * n + 64)) break;
    }
    auto cell_at = [&](const Vec& p, int c) { return std::max(0L, std::min(dims[c] - 1, long((p[c] - lo[c]) / size[c]))); };
    const long n_cells = dims[0] * dims[1] * dims[2];
    std::vector<std::int32_t> start(n_cells + 1, 0), items(n), home(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Vec& p = bodies.position[i];
        home[i] = std::int32_t((( dim == 3 ? cell_at(p, 2) : 0) * dims[1] + cell_at(p, 1)) * dims[0] + cell_at(p, 0));
        ++start[home[i] + 1];
    }
    std::partial_sum(start.begin(), start.end(), start.begin());
    {
        std::vector<std::int32_t> next(start.begin(), start.end() - 1);
        for (std::size_t i = 0; i < n; ++i) items[next[home[i]]++] = std::int32_t(i);
    }
    const int ng = table.group_count();
    const int* cmat = table.table().data();
    constexpr std::size_t block = 1024;
    const std::size_t n_blocks = (n + block - 1) / block;
    auto& block_pairs = block_pairs_;
    block_pairs.resize(n_blocks);
#pragma omp parallel for schedule(dynamic) if (n >= parallel_min)
    for (std::size_t b = 0; b < n_blocks; ++b) {
        auto& lists = block_pairs[b];
        lists.resize(out.size());
        for (auto& l : lists) l.clear();
        const std::int32_t* clump = bodies.clump.size() == n ? bodies.clump.data() : nullptr;
        for (std::size_t i = b * block; i < std::min(n, (b + 1) * block); ++i) {
            const Vec& pi = bodies.position[i];
            RowsAround rows;
            const int ny = rows_around(pc, pi, dims, size, lo, rows);
            long zs[3] = {0, 0, 0};
            const int nz = dim == 3 ? neighbour_cells(cell_at(pi, 2), dims[2], pc.periodic[2], zs) : 1;
            for (int z = 0; z < nz; ++z)
                for (int y = 0; y < ny; ++y)
                    for (long x = 0, nx = rows.nx[y] < 0 ? dims[0] : rows.nx[y]; x < nx; ++x) {
                        const long c = (zs[z] * dims[1] + rows.y[y]) * dims[0] + (rows.nx[y] < 0 ? x : rows.x[y][x]);
                        for (std::int32_t t = start[c]; t < start[c + 1]; ++t) {
                            const std::int32_t j = items[t];
                            if (std::size_t(j) <= i) continue;
                            const int inst = cmat[bodies.group[i] * ng + bodies.group[j]];
                            if (inst < 0) continue;
                            if (clump && clump[i] >= 0 && clump[i] == clump[j]) continue;
                            const double cut = cutoff(*instances[inst], bodies.radius[i], bodies.radius[j], s);
                            if ((pc.image(pi, bodies.position[j]) - pi).squaredNorm() <= cut * cut)
                                lists[inst].push_back({std::int32_t(i), j});
                        }
                    }
        }
    }
    for (std::size_t m = 0; m < out.size(); ++m) {
        std::size_t total = 0;
        for (const auto& lists : block_pairs) total += lists[m].size();
        clear_for(out[m], total);
        for (const auto& lists : block_pairs) out[m].insert(out[m].end(), lists[m].begin(), lists[m].end());
    }
}

void NeighbourLists::find_wall_pairs(const Bodies& bodies, const Walls& walls, const AssignmentTable& table,
                                     const Instances& instances) {
    auto& out = wall_pairs_;
    if (walls.facets.empty() || instances.empty()) return;
    const double s = effective_skin(bodies);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const Vec& p = bodies.position[i];
        for (std::size_t f = 0; f < walls.facets.size(); ++f) {
            const Facet& facet = walls.facets[f];
            const int inst = table.assigned(bodies.group[i], walls.walls[facet.wall].group);
            if (inst < 0) continue;
            double dist;
            if (facet.kind == FacetKind::plane) dist = (p - facet.a).dot(facet.b);  // signed: behind is inside
            else dist = (closest_point(facet, p).point - p).norm();
            if (dist <= cutoff(*instances[inst], bodies.radius[i], 0.0, s)) out[inst].push_back({std::int32_t(i), std::int32_t(f)});
        }
    }
}

} // namespace plab
