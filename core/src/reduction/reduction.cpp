// The reduction (reduction.hpp): contact rows scattered into the chunks'
// partial sums, the bodies' sums block by block, damping, the walls' loads.
#include "reduction/reduction.hpp"

#include "forces/geometry.hpp"
#include "forces/row_lists.hpp"

#include <algorithm>
#include <cmath>

namespace plab {

void Reduction::build() {
    chunks.build(in_.sets, in_.parallel_min);
    any_accumulation_ = false;
    for (auto& inst : in_.instances) any_accumulation_ |= !inst->desc->rates_stage && !inst->fields_accumulated.empty();
}

// Adds contact row k's contributions to the fields its model accumulates,
// for body i at end 1 or end 2.
void Reduction::accumulate(const ModelInstance& owner, const ContactSet& s, std::uint32_t k, bool is_end2, std::size_t i) {
    for (std::size_t a = 0; a < owner.fields_accumulated.size(); ++a)
        in_.fields.column(owner.fields_accumulated[a])[i] += is_end2 ? s.acc2[a][k] : s.acc1[a][k];
}

// What each active row of [begin, end) adds to its two bodies (force and
// moment), summed in row order into the partial sums of its chunk. The
// batch's energy sums are taken here too (sum_energies() adds the batches
// in order, so the totals do not depend on the thread count).
void Reduction::scatter_rows(std::uint32_t si, std::size_t begin, std::size_t end, const Chunk& ch) {
    ContactSet& s = *in_.sets[si];
    const auto& B = in_.bodies;
    double* fm = chunks.slots(ch);  // body i at width * (i - lo), or listed
    const std::size_t width = slot_doubles(in_.dim, false);
    const std::int32_t lo = ch.lo;
    const std::uint32_t* listed = ch.listed ? chunks.listed_slot(si) : nullptr;
    double strain = 0, slip = 0, dashpot = 0, broken = 0, wall_power = 0;
    // the active rows, listed without a branch per row
    std::uint32_t rows[kContactBatch];
    const std::size_t n_active = list_flagged_rows(s.active.data() + begin, end - begin, std::uint32_t(begin), rows);
    for (std::size_t a = 0; a < n_active; ++a) {
        const std::size_t k = rows[a];
        double* f1m1 = fm + width * (listed ? std::size_t(listed[k]) : std::size_t(s.end1[k] - lo));
        strain += s.strain[k];
        slip += s.slip[k];
        dashpot += s.dashpot[k];
        broken += s.break_energy[k];
        const Vec f2(&s.force[3 * k]), point(&s.point[3 * k]);
        const Vec m1 = (point - B.position[s.end1[k]]).cross(-f2) + Vec(&s.moment1[3 * k]);
        add_to_slot(in_.dim, f1m1, -f2, m1);  // (x - f and x + (-f) are the same bits)
        if (s.with_wall) {
            // power of the ball on the wall: -(force on the wall) . v_wall(point)
            wall_power -= f2.dot(in_.walls.velocity_at(in_.walls.facets[s.end2[k]].wall, point));
            continue;
        }
        const Vec m2 = (point - row_end2_centre(B, s, k)).cross(f2) + Vec(&s.moment2[3 * k]);
        add_to_slot(in_.dim, fm + width * std::size_t(s.end2[k] - lo), f2, m2);
    }
    double* e = s.batch_energy.data() + kBatchEnergies * (begin / kContactBatch);
    e[0] = strain; e[1] = slip; e[2] = dashpot; e[3] = broken; e[4] = wall_power;
}

void Reduction::scatter_to_chunks(std::uint32_t si) {
    const std::size_t n = in_.sets[si]->size();
    in_.sets[si]->batch_energy.assign(kBatchEnergies * ((n + kContactBatch - 1) / kContactBatch), 0.0);
#pragma omp parallel for schedule(static) if (n >= in_.parallel_min)
    for (std::uint32_t c = chunks.first_chunk(si); c < chunks.end_chunk(si); ++c) {
        Chunk& ch = chunks.chunk(c);
        chunks.clear(ch, in_.dim);
        ch.forces_only = false;
        for (std::size_t o = ch.begin; o < ch.end; o += kContactBatch)
            scatter_rows(si, o, std::min(ch.end, o + kContactBatch), ch);
    }
}

// PFC local damping and mass-proportional viscous damping of body i's force
// and moment (their work added to local_work).
void Reduction::damp_body(std::size_t i, Vec& f, Vec& m, double& local_work) const {
    const double alpha = in_.bodies.local_damping[i];
    if (alpha > 0) {  // PFC local damping: -alpha |F| sign(v), per component
        for (int c = 0; c < 3; ++c) {
            const double v = in_.bodies.velocity[i][c], w = in_.bodies.angular_velocity[i][c];
            const double fd = -alpha * std::fabs(f[c]) * ((v > 0) - (v < 0));
            const double md = -alpha * std::fabs(m[c]) * ((w > 0) - (w < 0));
            f[c] += fd;
            m[c] += md;
            local_work -= (fd * v + md * w) * in_.last_dt;
        }
    }
    const double c = in_.bodies.viscous_damping[i];
    if (c > 0) {  // mass-proportional: every mode decays at the same rate c/2 (quasi-static solves)
        const Vec fd = -c * in_.bodies.mass[i] * in_.bodies.velocity[i];
        const Vec md = -c * in_.bodies.inertia[i] * in_.bodies.angular_velocity[i];
        f += fd;
        m += md;
        local_work -= (fd.dot(in_.bodies.velocity[i]) + md.dot(in_.bodies.angular_velocity[i])) * in_.last_dt;
    }
}

// Bodies [i0, i1) after their contact sums: field accumulations, damping
// (its work added to local_work), the 2D projection. False when a body's
// state may be non-finite.
bool Reduction::finish_bodies(std::size_t i0, std::size_t i1, double& local_work) {
    if (any_accumulation_)  // fields of rates-stage models are summed after that stage
        for (std::size_t i = i0; i < i1; ++i)
            for (const BodyContact& en : in_.body_contacts.of(i)) {
                const ContactSet& s = *in_.sets[en.set];
                const std::uint32_t k = en.row();
                const ModelInstance& owner = *in_.set_owner[en.set];
                if (s.active[k] && !owner.desc->rates_stage) accumulate(owner, s, k, en.end2(), i);
            }
    const double *local_damping = in_.bodies.local_damping.data(), *viscous_damping = in_.bodies.viscous_damping.data();
    for (std::size_t i = i0; i < i1; ++i)
        if (local_damping[i] > 0 || viscous_damping[i] > 0) damp_body(i, in_.bodies.force[i], in_.bodies.moment[i], local_work);
    return bodies_finite(i0, i1);
}

// Bodies [i0, i1)'s sums, in a loop of their own (the damping's call made
// the compiler keep the flag and the columns' addresses in memory): a 2D
// world's force and moment projected on its plane, then false when a sum of
// a body's values is Inf or NaN (so is the sum then; an overflow of finite
// values too is caught, check_finite() tells which body).
bool Reduction::bodies_finite(std::size_t i0, std::size_t i1) {
    Vec* force = in_.bodies.force.data();
    Vec* moment = in_.bodies.moment.data();
    const Vec *position = in_.bodies.position.data(), *velocity = in_.bodies.velocity.data();
    // an OR, not a running sum, so that no body waits for the previous one
    bool non_finite = false;
    if (in_.dim == 2) {  // (z, vz of a 2D world are zero: Bodies::add, the kicks)
        for (std::size_t i = i0; i < i1; ++i) {
            force[i].z() = 0; moment[i].x() = 0; moment[i].y() = 0;
            non_finite |= !(std::fabs(force[i].x() + force[i].y() + moment[i].z() + position[i].x() + position[i].y() +
                                      velocity[i].x() + velocity[i].y()) < kInf);
        }
        return !non_finite;
    }
    for (std::size_t i = i0; i < i1; ++i)
        non_finite |= !(std::fabs(force[i].sum() + moment[i].sum() + position[i].sum() + velocity[i].sum()) < kInf);
    return !non_finite;
}

// Sum contact forces and moments onto bodies, then finish each body, in
// blocks of bodies. True when a body's state may be non-finite.
bool Reduction::reduce(double closing_kick, bool rows_summed, Leapfrog& leapfrog) {
    const std::size_t n = in_.bodies.size();
    for (auto& inst : in_.instances)
        if (!inst->desc->rates_stage)
            for (int f : inst->fields_accumulated) std::fill(in_.fields.column(f).begin(), in_.fields.column(f).end(), 0.0);
    if (!rows_summed)  // the sweeps summed the rows already
        for (std::uint32_t si = 0; si < in_.sets.size(); ++si) scatter_to_chunks(si);
    bool non_finite = false;
    const std::size_t n_blocks = body_blocks(in_.bodies.size());
    block_local_work_.assign(n_blocks, 0.0);  // local damping work per block
    if (closing_kick > 0) leapfrog.prepare_blocks(in_.bodies);
#pragma omp parallel for schedule(static) reduction(| : non_finite) if (n >= in_.parallel_min)
    for (std::size_t b = 0; b < n_blocks; ++b) {
        const std::size_t i0 = b * kBodyBlock, i1 = std::min(n, i0 + kBodyBlock);
        chunks.add_to_bodies(in_.bodies, in_.gravity, i0, i1);
        double work = 0;
        non_finite |= !finish_bodies(i0, i1, work);
        block_local_work_[b] = work;
        // the step's closing half kick while the block is in cache (Cycle::advance())
        if (closing_kick > 0) leapfrog.kick_block(in_.bodies, b, closing_kick, true);
    }
    chunks.all_taken();  // (add_to_bodies() cleared every slot it took)
    double local_work = 0;
    for (double w : block_local_work_) local_work += w;
    in_.energies.local_damping += local_work;
    sum_wall_loads();
    return non_finite;
}

// Each wall's force and moment (about its centre) from its contacts.
void Reduction::sum_wall_loads() {
    for (Wall& w : in_.walls.walls) { w.force.setZero(); w.moment.setZero(); }
    for (auto& inst : in_.instances) {
        const ContactSet& s = inst->walls;
        for (std::size_t k = 0; k < s.size(); ++k) {
            if (!s.active[k]) continue;
            Wall& w = in_.walls.walls[in_.walls.facets[s.end2[k]].wall];
            const Vec fc(&s.force[3 * k]);
            w.force += fc;
            w.moment += (Vec(&s.point[3 * k]) - w.centre).cross(fc) + Vec(&s.moment2[3 * k]);
        }
    }
}

} // namespace plab
