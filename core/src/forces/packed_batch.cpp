// Range test, packing and unpacking of ball–ball rows for the dense batch
// (forces/packed_batch.hpp). The geometry is ball_pair_kinematics(), as in
// ball_ball_geometry() (forces/geometry.cpp); the sums are those of
// scatter_rows(), so results are the same bit for bit.
#include "forces/packed_batch.hpp"
#include "forces/row_lists.hpp"
#include "forces/tangential_history.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

namespace plab {

namespace {
inline std::uint64_t bits(double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
}
} // namespace

namespace {
// The candidate loop of range_test_rows(), with the model's range kind and
// whether it keeps bonds fixed at compile time: no test of either per row,
// and fewer live values (the loop kept seven column addresses on the stack).
struct RangeRows {
    const std::int32_t *end1, *end2;
    const double *radius, *history;  // radius: the bodies' (a packed set keeps none per row)
    const Vec* x;
    double* gap_col;  // null: the set keeps no gaps (packed)
    std::uint8_t *active_col, *live;
    bool plane;  // a 2D world: every z is zero, so is its square
    const PeriodicCell* cell;  // null: no periodic axis
};
// In two loops: the geometry and flags of every row first, then the lists.
// In one loop the list stores waited for their addresses, the counts, which
// wait for each row's square root: the rows no longer overlapped.
// Forget: the model keeps history, so the rows that just left the range
// are listed (idle) to have it reset; a model without history (SPH) needs
// neither that list nor the live flags.
template <bool ByDistance, bool Bonds, bool Forget>
std::size_t test_rows(const RangeRows& c, const RangeTest& in_range, std::size_t begin, std::size_t end,
                      std::uint32_t* row, double* distance, std::uint32_t* idle, std::size_t& n_idle) {
    const std::size_t n = end - begin;  // at most kContactBatch
    double dist_of[kContactBatch];
    std::uint8_t in[kContactBatch];
    // squared distances first, then their square roots in a loop of their
    // own: there they are taken a vector at a time (one vsqrtpd for 8 rows
    // on AVX-512), not one row at a time behind each row's gathers
    if (c.cell)  // a periodic cell: the minimum image's distance
        for (std::size_t r = 0; r < n; ++r) {
            const std::size_t k = begin + r;
            const Vec& a = c.x[c.end1[k]];
            dist_of[r] = (c.cell->image(a, c.x[c.end2[k]]) - a).squaredNorm();
        }
    else if (c.plane)  // (the same bits: the square of z adds zero)
        for (std::size_t r = 0; r < n; ++r) {
            const std::size_t k = begin + r;
            const Vec &a = c.x[c.end1[k]], &b = c.x[c.end2[k]];
            const double dx = b.x() - a.x(), dy = b.y() - a.y();
            dist_of[r] = dx * dx + dy * dy;
        }
    else
        for (std::size_t r = 0; r < n; ++r) {
            const std::size_t k = begin + r;
            dist_of[r] = (c.x[c.end2[k]] - c.x[c.end1[k]]).squaredNorm();
        }
    for (std::size_t r = 0; r < n; ++r) dist_of[r] = std::sqrt(dist_of[r]);
    for (std::size_t r = 0; r < n; ++r) {
        const std::size_t k = begin + r;
        const double dist = dist_of[r];
        const double g = surface_gap(dist, c.radius[c.end1[k]], c.radius[c.end2[k]]);
        const bool active = in_range.in<ByDistance, Bonds>(c.history, k, dist, g);
        if (c.gap_col) c.gap_col[k] = g;  // (the centre distance of a ball–ball row is read by the model only)
        in[r] = active;
    }
    // The flags in loops of their own (whole vectors of bytes), then the
    // lists (row_lists.hpp).
    std::copy_n(in, n, c.active_col + begin);
    if (Forget) {
        std::uint8_t left[kContactBatch];  // just left the range: history to forget
        for (std::size_t r = 0; r < n; ++r) left[r] = !in[r] & (c.live[begin + r] != 0);
        std::copy_n(in, n, c.live + begin);
        n_idle += list_flagged_rows(left, n, std::uint32_t(begin), idle + n_idle);
    }
    const std::size_t n_active = list_flagged_rows(in, n, std::uint32_t(begin), row, dist_of, distance);
    return n_active;
}
} // namespace

// Rows [begin, end) of set si, at most one batch: the range test of every
// candidate (gap and the active flag stay in the set's columns, for every
// reader), the rows in range listed in `row` with their centre distance
// (`distance`, where given; the gap is distance - r1 - r2), and the history of
// rows that left the range back to its declared defaults (a separated
// contact is forgotten, as the adapter's batch loop did; a row that stays
// out of range keeps them). Returns how many rows are in range.
std::size_t ForcePipeline::range_test_rows(const ModelInstance& inst, std::uint32_t si, std::size_t begin, std::size_t end,
                                   std::uint32_t* row, double* distance) {
    ContactSet& s = *in_.sets[si];
    const RangeTest in_range(inst);
    const std::size_t stride = std::size_t(inst.stride);
    // raw pointers: the byte stores below (flags) may alias anything, so
    // the compiler would otherwise reload every column's address per row
    const RangeRows c{s.end1.data(), s.end2.data(), in_.bodies.radius.data(), s.history.data(),
                      in_.bodies.position.data(), s.packed ? nullptr : s.gap.data(), s.active.data(), packed[si].live.data(),
                      in_.dim == 2, in_.bodies.cell.any() ? &in_.bodies.cell : nullptr};
    std::uint32_t idle[kContactBatch];
    double unused[kContactBatch];  // where an output the caller does not take goes
    if (!distance) distance = unused;
    std::size_t n_idle = 0, n_active;
    const bool bonds = in_range.persist >= 0, forget = stride > 0;  // (a bond is kept in the history)
    const auto test = [&](auto by_distance) {
        constexpr bool D = decltype(by_distance)::value;
        if (bonds) return test_rows<D, true, true>(c, in_range, begin, end, row, distance, idle, n_idle);
        return forget ? test_rows<D, false, true>(c, in_range, begin, end, row, distance, idle, n_idle)
                      : test_rows<D, false, false>(c, in_range, begin, end, row, distance, idle, n_idle);
    };
    n_active = in_range.by_distance ? test(std::true_type{}) : test(std::false_type{});
    for (std::size_t r = 0; r < n_idle; ++r)
        for (std::size_t h = 0; h < stride; ++h) s.history[idle[r] * stride + h] = inst.desc->history[h].default_value;
    return n_active;
}

namespace {
// ball_pair_kinematics() in the plane: a 2D world's positions and
// velocities have z = 0 and its spins only a z component (its implicit
// fixity), so only the other components are worked out, with the same
// arithmetic (w x a in x is 0*0 - w_z a_y, in y w_z a_x - 0*0).
// (xj_, vj: ball j's centre and velocity, or its minimum image's)
inline PairKinematics ball_pair_kinematics_2d(const Bodies& B, std::int32_t i, std::int32_t j, const Vec& xj_, const Vec& vj,
                                              double ri, double dist, double gap) {
    const double xi = B.position[i].x(), yi = B.position[i].y(), xj = xj_.x(), yj = xj_.y();
    const PlaneNormal n = centre_normal_2d(B.position[i], xj_, dist);
    const double nx = n.x, ny = n.y;
    const double reach = ri + 0.5 * gap;
    const double px = xi + nx * reach, py = yi + ny * reach;
    const double a1x = px - xi, a1y = py - yi, a2x = px - xj, a2y = py - yj;
    const double wi = B.angular_velocity[i].z(), wj = B.angular_velocity[j].z();
    const double vjx = vj.x() + (0.0 - wj * a2y), vjy = vj.y() + wj * a2x;
    const double vix = B.velocity[i].x() + (0.0 - wi * a1y), viy = B.velocity[i].y() + wi * a1x;
    PairKinematics p;
    p.normal = Vec(nx, ny, 0.0);
    p.point = Vec(px, py, 0.0);
    p.arm1 = Vec(a1x, a1y, 0.0);
    p.arm2 = Vec(a2x, a2y, 0.0);
    p.rel_velocity = Vec(vjx - vix, vjy - viy, 0.0);
    p.rel_angular_velocity = Vec(0.0, 0.0, wj - wi);
    return p;
}

// pack_ball_rows()'s loop over the rows in range, for 2D or 3D.
template <int Dim, bool Periodic>
bool pack_rows_in_range(const Bodies& B, const ContactSet& s, const OptionalInputs& optional, double max_overlap,
                        std::size_t n_active, DenseBatch& d) {
    return pack_rows(B, s, optional, max_overlap, n_active, d,
                     [&](std::size_t a, std::int32_t i, std::int32_t j, double ri, double dist, double gap) {
                         const Vec xj = seen_from<Periodic>(B, i, j), vj = velocity_seen_from<Periodic>(B, i, j);
                         const PairKinematics p = Dim == 2 ? ball_pair_kinematics_2d(B, i, j, xj, vj, ri, dist, gap)
                                                           : ball_pair_kinematics(B, i, j, xj, vj, ri, dist, gap);
                         put(d.normal, a, p.normal);
                         if (!s.packed) put(d.point, a, p.point);
                         put(d.arm1, a, p.arm1);
                         put(d.arm2, a, p.arm2);
                         put(d.rel_velocity, a, p.rel_velocity);
                         return p.rel_angular_velocity;
                     });
}
} // namespace

// The range test (range_test_rows), then the geometry of the rows in range
// packed into d. True when an active contact overlaps beyond its model's
// max_overlap.
bool ForcePipeline::pack_ball_rows(const ModelInstance& inst, std::uint32_t si, std::size_t begin, std::size_t end,
                           DenseBatch& d) {
    const std::size_t n_active = range_test_rows(inst, si, begin, end, d.row, d.distance);
    d.rows = d.row;
    d.distances = d.distance;
    const ContactSet& s = *in_.sets[si];
    const std::size_t stride = std::size_t(inst.stride);
    // only the optional inputs the model reads (abi.h, PLAB_IO_*)
    d.poison_unread(inst);
    const OptionalInputs optional(inst);
    const auto& B = in_.bodies;
    const double mo = inst.max_overlap;
    const bool exceeded =
        B.cell.any() ? (in_.dim == 2 ? pack_rows_in_range<2, true>(B, s, optional, mo, n_active, d)
                                     : pack_rows_in_range<3, true>(B, s, optional, mo, n_active, d))
                     : (in_.dim == 2 ? pack_rows_in_range<2, false>(B, s, optional, mo, n_active, d)
                                     : pack_rows_in_range<3, false>(B, s, optional, mo, n_active, d));
    gather_history(d.history.data(), s.history.data(), d.row, n_active, stride);
    d.count = std::uint32_t(n_active);
    // the outputs a model adds to start from zero (dt limit: no limit); the
    // optional ones only when it writes them
    std::fill_n(d.force, 3 * n_active, 0.0);
    for (double* v : {d.strain, d.slip, d.dashpot, d.k_t}) std::fill_n(v, n_active, 0.0);
    if (inst.uses(PLAB_IO_MOMENTS))
        for (double* v : {d.moment1, d.moment2}) std::fill_n(v, 3 * n_active, 0.0);
    if (inst.uses(PLAB_IO_STIFFNESS_ROTATIONAL)) std::fill_n(d.k_r, n_active, 0.0);
    if (inst.uses(PLAB_IO_BREAK_ENERGY)) std::fill_n(d.break_energy, n_active, 0.0);
    if (inst.uses(PLAB_IO_DT_LIMIT)) std::fill_n(d.dt_limit, n_active, kInf);
    return exceeded;
}

// A packed set's normal, point and gap with the packers' arithmetic (the
// range test's distance and gap, centre_normal(), ball_contact_point()),
// not the whole pair kinematics: a reader needs neither the velocities nor
// the spin.



int call_model(const ModelInstance& inst, DenseBatch& d, int dim, double dt, const ReadFields& fields,
                     BatchCall call) {
    if (d.count == 0) return 0;
    // (every packed row is active; the packers leave the normals in d)
    turn_tangential_history(*inst.desc, d.history.data(), std::size_t(inst.stride), d.normal, nullptr, d.count);
    plab_contact_batch batch{sizeof(plab_contact_batch)};
    batch.dim = uint32_t(dim);
    batch.count = d.count;
    batch.end2_is_wall = call.to_wall;
    batch.history_stride = uint32_t(inst.stride);
    batch.dt = dt;
    bind_rows(batch, d, 0, d.history.data());
    batch.distance = d.distances;  // (where the packer left them)
    batch.body_fields = fields.cols;
    batch.body_fields_at_default = fields.at_default;
    // the sums start from zero where they are kept: not in the force stage
    // of a rates-stage model (abi.h, rates_stage), which may write them still
    const std::size_t n_fields = inst.fields_accumulated.size();
    const bool kept = call.stage == PLAB_STAGE_RATES || !inst.desc->rates_stage;
    if (n_fields) d.accumulated.bind(n_fields, kept ? d.count : 0);
    batch.accumulate1 = n_fields ? d.accumulated.end1 : nullptr;
    batch.accumulate2 = n_fields ? d.accumulated.end2 : nullptr;
    batch.stage = call.stage;
    return inst.desc->compute(inst.state, inst.props.data(), &batch);
}

namespace {
struct UnpackedSums { double strain = 0, slip = 0, dashpot = 0, broken = 0; };
// unpack_rows()'s loop over the packed rows, for 2D or 3D: a 2D slot takes
// fx, fy and the z moment alone (add_to_slot, reduction/chunked_sums.hpp), so only that
// component of r x F is worked out.
template <int Dim>
UnpackedSums unpack_loop(ContactSet& s, const DenseBatch& d, double* fm, std::size_t width, std::int32_t lo,
                         bool pure_moments, bool breaks) {
    UnpackedSums e;
    for (std::size_t a = 0; a < d.count; ++a) {
        const std::size_t k = d.row[a];
        if (!s.packed) {  // a packed set recomputes them on demand (contact_point())
            copy3(s.point.data(), k, d.point, a);
            copy3(s.normal.data(), k, d.normal, a);
        }
        e.strain += d.strain[a];
        e.slip += d.slip[a];
        e.dashpot += d.dashpot[a];
        if (breaks) e.broken += d.break_energy[a];
        const Vec f2(&d.force[3 * a]);
        double* s1 = fm + width * std::size_t(d.end1[a] - lo);
        double* s2 = fm + width * std::size_t(d.end2[a] - lo);
        if (Dim == 2) {  // Eigen's cross product in z: a.x b.y - a.y b.x
            const double *r1 = &d.arm1[3 * a], *r2 = &d.arm2[3 * a];
            double m1 = r1[0] * -f2[1] - r1[1] * -f2[0];
            double m2 = r2[0] * f2[1] - r2[1] * f2[0];
            if (pure_moments) { m1 += d.moment1[3 * a + 2]; m2 += d.moment2[3 * a + 2]; }
            add_to_slot_2d(s1, -f2[0], -f2[1], m1);  // (x - f and x + (-f): the same bits)
            add_to_slot_2d(s2, f2[0], f2[1], m2);
            continue;
        }
        Vec m1 = Vec(&d.arm1[3 * a]).cross(-f2);
        Vec m2 = Vec(&d.arm2[3 * a]).cross(f2);
        if (pure_moments) { m1 += Vec(&d.moment1[3 * a]); m2 += Vec(&d.moment2[3 * a]); }
        add_to_slot_3d(s1, -f2, m1);
        add_to_slot_3d(s2, f2, m2);
    }
    return e;
}
} // namespace

namespace {

// Rows [begin, end) of an output column filled with one value, unless the
// last fill already left it there.
void hold_value(double* col, std::size_t width, double u, std::size_t begin, std::size_t end, HeldOutputs& held,
                int which) {
    if (held.uniform[which] && bits(held.value[which]) == bits(u)) return;
    held.uniform[which] = true;
    held.value[which] = u;
    std::fill(col + width * begin, col + width * end, u);
}

// One output column (`width` doubles per row) back from the packed rows of
// batch [begin, end). Most models give many outputs one value for every
// contact (no pure moments, a constant stiffness, no step limit): then the
// whole batch is filled with it once, and later steps that give the same
// value write nothing. Values are compared bit for bit.
void write_back(double* col, std::size_t width, const double* dense, const DenseBatch& d, std::size_t begin,
                std::size_t end, HeldOutputs& held, int which) {
    const std::size_t n = width * d.count;
    if (n == 0) return;  // no row to report: what the column holds is not read
    const double u = dense[0];
    bool same = true;
    for (std::size_t i = 1; i < n; ++i) same &= bits(dense[i]) == bits(u);
    if (same) return hold_value(col, width, u, begin, end, held, which);
    held.uniform[which] = false;
    for (std::size_t a = 0; a < d.count; ++a)
        for (std::size_t c = 0; c < width; ++c) col[width * d.row[a] + c] = dense[width * a + c];
}

} // namespace

// Back from the packed rows of batch [begin, end): history, and what the
// readers of the contact columns use (force, moments, stiffnesses, step
// limit: outputs, stress, stable step, bond breaks, checkpoints; normal and
// point they recompute, ContactTable::point; the force only on a step
// whose forces are read, World::contact_forces_wanted); then each row's
// force and moments added to the chunk's partial sums, and the batch's
// energy sums, as scatter_rows() does for full columns.
void ForcePipeline::unpack_rows(std::uint32_t si, const ModelInstance& inst, const DenseBatch& d, std::size_t begin,
                        const Chunk& ch) {
    ContactSet& s = *in_.sets[si];
    const std::size_t stride = std::size_t(inst.stride);
    double* fm = reduction_.chunks.slots(ch);  // body i at width * (i - lo)
    const std::size_t width = slot_doubles(in_.dim, false);
    const std::int32_t lo = ch.lo;
    const bool pure_moments = inst.uses(PLAB_IO_MOMENTS), breaks = inst.uses(PLAB_IO_BREAK_ENERGY);
    write_forces(s, d, contact_forces_kept_);
    const UnpackedSums sums = in_.dim == 2 ? unpack_loop<2>(s, d, fm, width, lo, pure_moments, breaks)
                                       : unpack_loop<3>(s, d, fm, width, lo, pure_moments, breaks);
    const double strain = sums.strain, slip = sums.slip, dashpot = sums.dashpot, broken = sums.broken;
    scatter_history(s.history.data(), d.history.data(), d.row, d.count, stride);
    double* e = s.batch_energy.data() + kBatchEnergies * (begin / kContactBatch);
    e[0] = strain; e[1] = slip; e[2] = dashpot; e[3] = broken; e[4] = 0;
    if (d.count == 0) return;  // no row to report: what the columns hold is not read
    HeldOutputs& held = packed[si].held[begin / kContactBatch];
    const std::size_t end = std::min(s.size(), begin + kContactBatch);
    // an output the model does not write is not kept by a packed set
    // (ContactSet::keeps), or holds its neutral value (abi.h, PLAB_IO_*)
    if (pure_moments) {
        write_back(s.moment1.data(), 3, d.moment1, d, begin, end, held, 0);
        write_back(s.moment2.data(), 3, d.moment2, d, begin, end, held, 1);
    } else if (!s.moment1.empty()) {
        hold_value(s.moment1.data(), 3, 0.0, begin, end, held, 0);
        hold_value(s.moment2.data(), 3, 0.0, begin, end, held, 1);
    }
    write_back(s.k_t.data(), 1, d.k_t, d, begin, end, held, 2);
    if (inst.uses(PLAB_IO_STIFFNESS_ROTATIONAL)) write_back(s.k_r.data(), 1, d.k_r, d, begin, end, held, 3);
    else if (!s.k_r.empty()) hold_value(s.k_r.data(), 1, 0.0, begin, end, held, 3);
    if (inst.uses(PLAB_IO_DT_LIMIT)) write_back(s.dt_limit.data(), 1, d.dt_limit, d, begin, end, held, 4);
    else if (!s.dt_limit.empty()) hold_value(s.dt_limit.data(), 1, kInf, begin, end, held, 4);
}

} // namespace plab
