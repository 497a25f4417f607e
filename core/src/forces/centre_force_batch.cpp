// Packing and unpacking of ball–ball rows for a model whose pair force acts
// between the particle centres (PLAB_MODEL_FORCE_AT_CENTRES, abi.h: SPH).
// The dense batch of forces/packed_batch.hpp without what such a model never uses:
// no spin terms in the relative velocity, no moments r x F, no stiffness or
// energy columns cleared or read back. The rows reach the model through the
// same DenseBatch, bind_rows() and call_model(); the force sums go to
// the chunks' partials in row order, as unpack_rows() does, so results do
// not depend on the thread count.
#include "forces/packed_batch.hpp"

#include <algorithm>
#include <cmath>

namespace plab {

namespace {
// pack_centre_rows()'s loop over the rows in range, for 2D or 3D (a 2D
// world's positions and velocities have z = 0: the normal and the relative
// velocity in the plane, with centre_normal()'s arithmetic).
template <int Dim, bool Periodic>
bool pack_centre_loop(const Bodies& B, const ContactSet& s, const OptionalInputs& optional, double max_overlap,
                      std::size_t n_active, DenseBatch& d) {
    // (no contact point: readers recompute it, ContactTable::point; no spin)
    return pack_rows(B, s, optional, max_overlap, n_active, d,
                     [&](std::size_t a, std::int32_t i, std::int32_t j, double, double dist, double) {
                         const Vec xj = seen_from<Periodic>(B, i, j);  // (a copy the compiler drops without a cell)
                         const Vec vj = velocity_seen_from<Periodic>(B, i, j);
                         if (Dim == 2) {
                             const PlaneNormal n = centre_normal_2d(B.position[i], xj, dist);
                             d.normal[3 * a] = n.x;
                             d.normal[3 * a + 1] = n.y;
                             d.normal[3 * a + 2] = 0.0;
                             d.rel_velocity[3 * a] = vj.x() - B.velocity[i].x();
                             d.rel_velocity[3 * a + 1] = vj.y() - B.velocity[i].y();
                             d.rel_velocity[3 * a + 2] = 0.0;
                         } else {
                             put(d.normal, a, centre_normal(B.position[i], xj, dist));
                             put(d.rel_velocity, a, vj - B.velocity[i]);
                         }
                         return Vec(Vec::Zero());
                     });
}
} // namespace

// Rows [begin, end) of ball–ball set si: the rows in range that
// mark_ball_rows_in_range() listed this cycle (or range_test_rows()), packed
// into d with the centres' relative velocity. True when an active contact
// overlaps beyond the model's max_overlap.
bool ForcePipeline::pack_centre_rows(const ModelInstance& inst, std::uint32_t si, std::size_t begin, std::size_t end,
                             DenseBatch& d) {
    ContactSet& s = *in_.sets[si];
    const auto& B = in_.bodies;
    const std::size_t stride = std::size_t(inst.stride);
    std::size_t n_active;
    const RowsInRange* marked = in_range_marked_ && si < in_range_.size() && in_range_[si].listed ? &in_range_[si] : nullptr;
    if (marked && begin % kContactBatch == 0) {  // mark_ball_rows_in_range() listed this batch's rows in range
        n_active = marked->count[begin / kContactBatch];
        d.rows = marked->row.data() + begin;
        d.distances = marked->distance.data() + begin;
    } else {
        n_active = range_test_rows(inst, si, begin, end, d.row, d.distance);  // (gap: below)
        d.rows = d.row;
        d.distances = d.distance;
    }
    // only the optional inputs the model reads (abi.h, PLAB_IO_*): `sph`
    // reads the masses, not the effective mass and radius (two divisions)
    d.poison_unread(inst);
    const OptionalInputs optional(inst);
    const double mo = inst.max_overlap;
    const bool exceeded = B.cell.any() ? (in_.dim == 2 ? pack_centre_loop<2, true>(B, s, optional, mo, n_active, d)
                                                       : pack_centre_loop<3, true>(B, s, optional, mo, n_active, d))
                                       : (in_.dim == 2 ? pack_centre_loop<2, false>(B, s, optional, mo, n_active, d)
                                                       : pack_centre_loop<3, false>(B, s, optional, mo, n_active, d));
    gather_history(d.history.data(), s.history.data(), d.rows, n_active, stride);
    d.count = std::uint32_t(n_active);
    // only the outputs the host reads start from zero (dt limit: no limit)
    std::fill_n(d.force, 3 * n_active, 0.0);
    if (inst.uses(PLAB_IO_DT_LIMIT)) std::fill_n(d.dt_limit, n_active, kInf);
    return exceeded;
}

// Back from the packed rows of batch [begin, end): history and force to
// the set's columns (their readers: outputs, stress; the force only on a
// step whose forces are read, World::contact_forces_wanted), the
// batch's least step limit to PackedTable::limits (the stable step), and
// each row's force added, in row order, to the chunk's partial sums: -F on
// end 1, +F on end 2, no moment.
void ForcePipeline::unpack_centre_rows(std::uint32_t si, const ModelInstance& inst, const DenseBatch& d,
                               std::size_t begin, const Chunk& ch) {
    ContactSet& s = *in_.sets[si];
    const std::size_t stride = std::size_t(inst.stride);
    double* fm = reduction_.chunks.slots(ch);  // body i at width * (i - lo): forces only (Chunk::forces_only)
    const std::size_t width = slot_doubles(in_.dim, true);
    const bool with_z = in_.dim == 3;  // (2D slots: fx, fy)
    const std::int32_t lo = ch.lo;
    write_forces(s, d, contact_forces_kept_);  // (point and normal: recomputed on demand, the set is packed)
    // The rows of one end 1 come in a run (a neighbour list): its sum is
    // kept in registers over the run, not loaded and stored back per row,
    // which made every row wait for the previous one's store. The sums are
    // the same in the same order, so the bits are too.
    std::int32_t held_body = -1;
    double* held = fm;
    double sx = 0, sy = 0, sz = 0;  // (locals, not an array: GCC kept an array on the stack)
    const auto put_back = [&] {
        held[0] = sx;
        held[1] = sy;
        if (with_z) held[2] = sz;
    };
    for (std::size_t a = 0; a < d.count; ++a) {
        const double fx = d.force[3 * a], fy = d.force[3 * a + 1], fz = d.force[3 * a + 2];
        if (d.end1[a] != held_body) {
            if (held_body >= 0) put_back();
            held_body = d.end1[a];
            held = fm + width * std::size_t(held_body - lo);
            sx = held[0];
            sy = held[1];
            if (with_z) sz = held[2];
        }
        sx -= fx; sy -= fy; sz -= fz;
        if (d.end2[a] == held_body) {  // (a body paired with itself: not in a neighbour list, but kept in order)
            sx += fx; sy += fy; sz += fz;
            continue;
        }
        double* f2 = fm + width * std::size_t(d.end2[a] - lo);
        f2[0] += fx;
        f2[1] += fy;
        if (with_z) f2[2] += fz;
    }
    if (held_body >= 0) put_back();
    if (inst.uses(PLAB_IO_DT_LIMIT)) {  // the batch's least step limit, its first row (PackedTable::limits)
        BatchLimit& least = packed[si].limits[begin / kContactBatch];
        for (std::size_t a = 0; a < d.count; ++a)
            if (d.dt_limit[a] < least.dt) least = {d.dt_limit[a], d.rows[a]};
    }
    scatter_history(s.history.data(), d.history.data(), d.rows, d.count, stride);
    // (the batch's energy sums stay zero: force_sweep cleared them)
}

} // namespace plab
