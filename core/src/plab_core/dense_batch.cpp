// Range test, packing and unpacking of ball–ball rows for the dense batch
// (dense_batch.hpp). The arithmetic is that of ball_geometry_rows() and
// scatter_rows(), so results are the same bit for bit.
#include "dense_batch.hpp"

#include <algorithm>
#include <cmath>

namespace plab {

namespace {
inline void put(double* col, std::size_t a, const Vec& v) {
    col[3 * a] = v.x(); col[3 * a + 1] = v.y(); col[3 * a + 2] = v.z();
}
inline void copy3(double* to, std::size_t k, const double* from, std::size_t a) {
    to[3 * k] = from[3 * a]; to[3 * k + 1] = from[3 * a + 1]; to[3 * k + 2] = from[3 * a + 2];
}
} // namespace

// Rows [begin, end): the range test of every candidate (gap, distance and
// the active flag stay in the set's columns, for every reader), the history
// of rows out of range back to its declared defaults (a separated contact is
// forgotten, as the adapter's batch loop did), and the geometry of the rows
// in range packed into d. True when an active contact overlaps beyond its
// model's max_overlap.
bool World::pack_ball_rows(const ModelInstance& inst, ContactSet& s, std::size_t begin, std::size_t end,
                           DenseBatch& d) {
    const bool by_distance = inst.desc->range_kind == PLAB_RANGE_DISTANCE;
    const int persist = inst.desc->persist_slot;
    const std::size_t stride = std::size_t(inst.stride);
    const auto& B = bodies;
    std::uint32_t idle[kContactBatch];
    std::size_t n_active = 0, n_idle = 0;
    for (std::size_t k = begin; k < end; ++k) {  // no branch per row: in-range flags follow no pattern
        const std::int32_t i = s.end1[k], j = s.end2[k];
        const double dist = (B.position[j] - B.position[i]).norm();
        const double gap = dist - s.radius1[k] - s.radius2[k];
        const bool bonded = persist >= 0 && s.history[k * stride + persist] > 0;
        const bool active = bonded || (by_distance ? dist <= inst.range : gap <= inst.range);
        s.gap[k] = gap;
        s.distance[k] = dist;
        s.active[k] = active;
        d.row[n_active] = std::uint32_t(k);
        idle[n_idle] = std::uint32_t(k);
        n_active += active;
        n_idle += !active;
    }
    for (std::size_t r = 0; r < n_idle; ++r)
        for (std::size_t h = 0; h < stride; ++h) s.history[idle[r] * stride + h] = inst.desc->history[h].default_value;
    bool exceeded = false;
    for (std::size_t a = 0; a < n_active; ++a) {
        const std::size_t k = d.row[a];
        const std::int32_t i = s.end1[k], j = s.end2[k];
        const Vec& xi = B.position[i];
        const double ri = s.radius1[k], rj = s.radius2[k];
        const Vec dx = B.position[j] - xi;
        const double dist = s.distance[k], gap = s.gap[k];
        const Vec normal = dist > 0 ? Vec(dx / dist) : Vec::UnitX();
        const Vec point = xi + normal * (ri + 0.5 * gap);  // middle of the overlap
        const Vec vj = B.velocity[j] + B.angular_velocity[j].cross(point - B.position[j]);
        const Vec vi = B.velocity[i] + B.angular_velocity[i].cross(point - xi);
        d.end1[a] = i;
        d.end2[a] = j;
        d.gap[a] = gap;
        d.distance[a] = dist;
        put(d.normal, a, normal);
        put(d.point, a, point);
        put(d.rel_velocity, a, vj - vi);
        put(d.rel_angular_velocity, a, B.angular_velocity[j] - B.angular_velocity[i]);
        d.radius1[a] = ri;
        d.radius2[a] = rj;
        d.mass1[a] = s.mass1[k];
        d.mass2[a] = s.mass2[k];
        d.eff_mass[a] = s.eff_mass[k];
        d.eff_radius[a] = s.eff_radius[k];
        std::copy_n(s.history.data() + k * stride, stride, d.history.data() + a * stride);
        exceeded |= -gap > inst.max_overlap * std::min(ri, rj);
    }
    d.count = std::uint32_t(n_active);
    // the outputs a model adds to start from zero (dt limit: no limit)
    for (double* v : {d.force, d.moment1, d.moment2}) std::fill_n(v, 3 * n_active, 0.0);
    for (double* v : {d.strain, d.slip, d.dashpot, d.k_t, d.k_r, d.break_energy}) std::fill_n(v, n_active, 0.0);
    std::fill_n(d.dt_limit, n_active, kInf);
    return exceeded;
}

int call_model_dense(const ModelInstance& inst, DenseBatch& d, int dim, double dt, const double* const* read_cols) {
    if (d.count == 0) return 0;
    plab_contact_batch batch{};
    batch.dim = uint32_t(dim);
    batch.count = d.count;
    batch.end2_is_wall = 0;
    batch.history_stride = uint32_t(inst.stride);
    batch.dt = dt;
    batch.end1 = d.end1;
    batch.end2 = d.end2;
    batch.active = d.active;
    batch.normal = d.normal;
    batch.gap = d.gap;
    batch.distance = d.distance;
    batch.rel_velocity = d.rel_velocity;
    batch.rel_angular_velocity = d.rel_angular_velocity;
    batch.radius1 = d.radius1;
    batch.radius2 = d.radius2;
    batch.mass1 = d.mass1;
    batch.mass2 = d.mass2;
    batch.eff_mass = d.eff_mass;
    batch.eff_radius = d.eff_radius;
    batch.body_fields = read_cols;
    batch.history = d.history.data();
    batch.force = d.force;
    batch.moment1 = d.moment1;
    batch.moment2 = d.moment2;
    batch.strain_energy = d.strain;
    batch.slip_energy = d.slip;
    batch.dashpot_energy = d.dashpot;
    batch.stiffness_translational = d.k_t;
    batch.stiffness_rotational = d.k_r;
    batch.dt_limit = d.dt_limit;
    batch.accumulate1 = nullptr;  // models that accumulate fields take the full-column path
    batch.accumulate2 = nullptr;
    batch.break_energy = d.break_energy;
    batch.stage = PLAB_STAGE_FORCES;
    return inst.desc->compute(inst.state, inst.props.data(), &batch);
}

// Back from the packed rows of batch [begin, end): history, and what the
// readers of the contact columns use (force, moments, point, normal,
// stiffnesses, step limit: outputs, stress, stable step, bond breaks,
// checkpoints); then each row's force and moments added to the chunk's partial
// sums, and the batch's energy sums, as scatter_rows() does for full columns.
void World::unpack_rows(std::uint32_t si, const ModelInstance& inst, const DenseBatch& d, std::size_t begin,
                        const Chunk& ch) {
    ContactSet& s = *sets_[si];
    const auto& B = bodies;
    const std::size_t stride = std::size_t(inst.stride);
    double* fm = partial_fm_.data() + ch.offset;  // body i at kSlotDoubles * (i - lo)
    const std::int32_t lo = ch.lo;
    double strain = 0, slip = 0, dashpot = 0, broken = 0;
    for (std::size_t a = 0; a < d.count; ++a) {
        const std::size_t k = d.row[a];
        std::copy_n(d.history.data() + a * stride, stride, s.history.data() + k * stride);
        copy3(s.force.data(), k, d.force, a);
        copy3(s.moment1.data(), k, d.moment1, a);
        copy3(s.moment2.data(), k, d.moment2, a);
        copy3(s.point.data(), k, d.point, a);
        copy3(s.normal.data(), k, d.normal, a);
        s.k_t[k] = d.k_t[a];
        s.k_r[k] = d.k_r[a];
        s.dt_limit[k] = d.dt_limit[a];
        strain += d.strain[a];
        slip += d.slip[a];
        dashpot += d.dashpot[a];
        broken += d.break_energy[a];
        const Vec f2(&d.force[3 * a]), point(&d.point[3 * a]);
        const Vec m1 = (point - B.position[d.end1[a]]).cross(-f2) + Vec(&d.moment1[3 * a]);
        const Vec m2 = (point - B.position[d.end2[a]]).cross(f2) + Vec(&d.moment2[3 * a]);
        double* f1m1 = fm + kSlotDoubles * std::size_t(d.end1[a] - lo);
        double* f2m2 = fm + kSlotDoubles * std::size_t(d.end2[a] - lo);
        for (int c = 0; c < 3; ++c) { f1m1[c] -= f2[c]; f1m1[3 + c] += m1[c]; }
        for (int c = 0; c < 3; ++c) { f2m2[c] += f2[c]; f2m2[3 + c] += m2[c]; }
    }
    double* e = s.batch_energy.data() + kBatchEnergies * (begin / kContactBatch);
    e[0] = strain; e[1] = slip; e[2] = dashpot; e[3] = broken; e[4] = 0;
}

} // namespace plab
