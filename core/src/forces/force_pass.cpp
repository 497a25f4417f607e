// Force–displacement: the host computes each candidate contact's geometry
// once (normal, gap, contact point, relative velocity), calls each model once
// per batch of contacts, then sums forces onto bodies in a fixed order.
#include "world/world.hpp"

#include "forces/packed_batch.hpp"
#include "common/error.hpp"
#include "forces/row_lists.hpp"
#include "forces/tangential_history.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

namespace plab {

void World::geometry(ModelInstance& inst, ContactSet& s) {
    const std::size_t n = s.size();
    const std::size_t n_batches = (n + kContactBatch - 1) / kContactBatch;
    bool exceeded = false;
#pragma omp parallel for schedule(static) reduction(| : exceeded) if (n >= parallel_min)
    for (std::size_t b = 0; b < n_batches; ++b)
        exceeded |= contact_geometry(bodies, walls, inst, s, b * kContactBatch, std::min(n, (b + 1) * kContactBatch));
    s.overlap_exceeded = exceeded;
}

namespace {
// The outputs a model adds to start from zero (dt limit: no limit).
void clear_outputs(ContactSet& s, std::size_t o, std::size_t m) {
    for (auto* v : {&s.force, &s.moment1, &s.moment2}) std::fill_n(v->begin() + 3 * o, 3 * m, 0.0);
    for (auto* v : {&s.strain, &s.slip, &s.dashpot, &s.k_t, &s.k_r, &s.break_energy}) std::fill_n(v->begin() + o, m, 0.0);
    std::fill_n(s.dt_limit.begin() + o, m, kInf);
    for (auto& a : s.acc1) std::fill_n(a.begin() + o, m, 0.0);
    for (auto& a : s.acc2) std::fill_n(a.begin() + o, m, 0.0);
}
} // namespace

// Calls the model once on rows [o, o + m) of a set, the tangential history
// of its active rows first turned into their contact planes; returns its
// status. `clear`: zero the outputs of every row first (the rates stage
// writes some that the force stage must not see); otherwise the geometry
// zeroed those of the active rows, which are the only ones a model writes.
int World::call_model(ModelInstance& inst, ContactSet& s, std::size_t o, std::size_t m, std::uint32_t stage,
                      const ReadFields& fields, bool clear) {
    if (clear) clear_outputs(s, o, m);  // here rather than up front: the rows stay in cache for the model
    const std::size_t stride = std::size_t(inst.stride);
    turn_tangential_history(*inst.desc, s.history.data() + o * stride, stride, s.normal.data() + 3 * o,
                            s.active.data() + o, m);
    // pointers into the accumulation columns, on the stack: no allocation in the cycle
    constexpr std::size_t kMaxAccumulated = 16;
    double* a1[kMaxAccumulated];
    double* a2[kMaxAccumulated];
    if (s.acc1.size() > kMaxAccumulated) return 3;
    for (std::size_t f = 0; f < s.acc1.size(); ++f) {
        a1[f] = s.acc1[f].data() + o;
        a2[f] = s.acc2[f].data() + o;
    }
    plab_contact_batch batch{sizeof(plab_contact_batch)};
    batch.dim = uint32_t(dim);
    batch.count = uint32_t(m);
    batch.end2_is_wall = s.with_wall;
    batch.history_stride = uint32_t(inst.stride);
    batch.dt = last_dt;
    bind_rows(batch, s, o, s.history.data() + o * inst.stride);
    batch.body_fields = fields.cols;
    batch.body_fields_at_default = fields.at_default;
    batch.accumulate1 = a1;
    batch.accumulate2 = a2;
    batch.stage = stage;
    return inst.desc->compute(inst.state, inst.props.data(), &batch);
}

void World::compute(ModelInstance& inst, ContactSet& s, std::uint32_t stage) {
    const std::size_t n = s.size();
    if (n == 0) return;
    const ReadFields fields = read_fields(inst);
    const std::size_t n_batches = (n + kContactBatch - 1) / kContactBatch;
    s.forces_zero = false;  // (any stage may write the outputs)
    int failed = 0;
#pragma omp parallel for schedule(static) reduction(| : failed) if (n >= parallel_min)
    for (std::size_t b = 0; b < n_batches; ++b) {
        const std::size_t o = b * kContactBatch, m = std::min(kContactBatch, n - o);
        if (call_model(inst, s, o, m, stage, fields, true) != 0) failed = 1;
    }
    if (failed) model_failed(inst);
    if (inst.desc->persist_slot >= 0) record_breaks(inst, s);
}

void World::model_failed(const ModelInstance& inst) const {
    throw RunError("contact model '" + inst.model + "' reported a failure in compute() at step " +
                   std::to_string(step_count));
}

// The force pass of one set in a single sweep over its chunks (world.hpp),
// batch by batch: geometry (ball–ball sets; a wall set has it done before,
// because resolve_wall_features needs a ball's rows together), the model,
// and the rows' forces added to the chunk's partial sums while the batch is
// in cache. Batches and chunks are fixed row ranges, so every sum is
// thread-count free.
void World::force_sweep(std::uint32_t si, bool with_geometry) {
    ContactSet& s = *sets_[si];
    ModelInstance& inst = *instances_[si / 2];
    const std::size_t n = s.size();
    s.batch_energy.assign(kBatchEnergies * ((n + kContactBatch - 1) / kContactBatch), 0.0);
    if (n == 0) return;
    const ReadFields fields = read_fields(inst);
    // ball–ball rows go to the model packed (forces/packed_batch.hpp), unless it
    // accumulates body fields in this stage (those sums walk the full
    // columns, reduce()); a rates-stage model's force-stage sums are not kept
    const bool dense = with_geometry && (inst.fields_accumulated.empty() || inst.desc->rates_stage);
    const bool at_centres = (inst.desc->flags & PLAB_MODEL_FORCE_AT_CENTRES) != 0;
    const std::uint32_t c0 = sums_.first_chunk(si), c1 = sums_.end_chunk(si);
    if (dense && at_centres && inst.uses(PLAB_IO_DT_LIMIT))
        packed_[si].limits.assign((n + kContactBatch - 1) / kContactBatch, BatchLimit{kInf, 0});
    // a still table (StillInstances) whose rows mark_ball_rows_in_range()
    // tested: nothing to pack, only its chunks' partial sums to clear
    const bool still = dense && at_centres && in_range_marked_ && si < in_range_.size() && in_range_[si].listed &&
                       still_.centre_table_still(si, s, instances_);
    if (still) hold_still(s);
    else s.forces_zero = false;
    int failed = 0;
    bool exceeded = false;
#pragma omp parallel for schedule(static) reduction(| : failed, exceeded) if (n >= parallel_min)
    for (std::uint32_t c = c0; c < c1; ++c) {
        Chunk& ch = sums_.chunk(c);
        sums_.clear(ch, dim);
        ch.forces_only = dense && at_centres;
        if (still) continue;
        for (std::size_t o = ch.begin; o < ch.end; o += kContactBatch) {
            const std::size_t m = std::min(kContactBatch, ch.end - o);
            if (dense && at_centres) {  // SPH: no spin, moments, stiffness or energies
                DenseBatch& d = DenseBatch::for_this_thread(std::size_t(inst.stride));
                exceeded |= pack_centre_rows(inst, si, o, o + m, d);
                if (call_model_dense(inst, d, dim, last_dt, fields) != 0) failed = 1;
                unpack_centre_rows(si, inst, d, o, ch);
                continue;
            }
            if (dense) {
                DenseBatch& d = DenseBatch::for_this_thread(std::size_t(inst.stride));
                exceeded |= pack_ball_rows(inst, si, o, o + m, d);
                if (call_model_dense(inst, d, dim, last_dt, fields) != 0) failed = 1;
                unpack_rows(si, inst, d, o, ch);
                continue;
            }
            if (with_geometry) exceeded |= contact_geometry(bodies, walls, inst, s, o, o + m);
            if (call_model(inst, s, o, m, PLAB_STAGE_FORCES, fields, false) != 0) failed = 1;
            scatter_rows(si, o, o + m, ch);
        }
    }
    if (with_geometry) s.overlap_exceeded = exceeded;
    if (failed) model_failed(inst);
    if (inst.desc->persist_slot >= 0) record_breaks(inst, s);
}

// A model marks a bond it just broke with -mode in its persist slot; the
// host records the break and leaves the contact unbonded.
void World::record_breaks(ModelInstance& inst, ContactSet& s) {
    const int slot = inst.desc->persist_slot;
    for (std::size_t k = 0; k < s.size(); ++k) {
        double& state = s.history[k * inst.stride + slot];
        if (state >= 0) continue;
        BondBreak b;
        b.step = step_count;
        b.time = time;
        std::tie(b.id1, b.id2) = row_keys(s, k);
        b.point = contact_point(s, k);
        b.mode = int(-state);
        b.model = inst.model;
        bond_breaks.push_back(b);
        state = 0;
    }
}

// Adds contact row k's contributions to the fields its model accumulates,
// for body i at end 1 or end 2.
void World::accumulate(const ModelInstance& owner, const ContactSet& s, std::uint32_t k, bool is_end2, std::size_t i) {
    for (std::size_t a = 0; a < owner.fields_accumulated.size(); ++a)
        fields.column(owner.fields_accumulated[a])[i] += is_end2 ? s.acc2[a][k] : s.acc1[a][k];
}

// What each active row of [begin, end) adds to its two bodies (force and
// moment), summed in row order into the partial sums of its chunk. The
// batch's energy sums are taken here too (sum_energies() adds the batches
// in order, so the totals do not depend on the thread count).
void World::scatter_rows(std::uint32_t si, std::size_t begin, std::size_t end, const Chunk& ch) {
    ContactSet& s = *sets_[si];
    const auto& B = bodies;
    double* fm = sums_.slots(ch);  // body i at width * (i - lo), or listed
    const std::size_t width = slot_doubles(dim, false);
    const std::int32_t lo = ch.lo;
    const std::uint32_t* listed = ch.listed ? sums_.listed_slot(si) : nullptr;
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
        add_to_slot(dim, f1m1, -f2, m1);  // (x - f and x + (-f) are the same bits)
        if (s.with_wall) {
            // power of the ball on the wall: -(force on the wall) . v_wall(point)
            wall_power -= f2.dot(walls.velocity_at(walls.facets[s.end2[k]].wall, point));
            continue;
        }
        const Vec m2 = (point - B.position[s.end2[k]]).cross(f2) + Vec(&s.moment2[3 * k]);
        add_to_slot(dim, fm + width * std::size_t(s.end2[k] - lo), f2, m2);
    }
    double* e = s.batch_energy.data() + kBatchEnergies * (begin / kContactBatch);
    e[0] = strain; e[1] = slip; e[2] = dashpot; e[3] = broken; e[4] = wall_power;
}

void World::scatter_to_chunks(std::uint32_t si) {
    const std::size_t n = sets_[si]->size();
    sets_[si]->batch_energy.assign(kBatchEnergies * ((n + kContactBatch - 1) / kContactBatch), 0.0);
#pragma omp parallel for schedule(static) if (n >= parallel_min)
    for (std::uint32_t c = sums_.first_chunk(si); c < sums_.end_chunk(si); ++c) {
        Chunk& ch = sums_.chunk(c);
        sums_.clear(ch, dim);
        ch.forces_only = false;
        for (std::size_t o = ch.begin; o < ch.end; o += kContactBatch)
            scatter_rows(si, o, std::min(ch.end, o + kContactBatch), ch);
    }
}

// PFC local damping and mass-proportional viscous damping of body i's force
// and moment (their work added to local_work).
void World::damp_body(std::size_t i, Vec& f, Vec& m, double& local_work) const {
    const double alpha = bodies.local_damping[i];
    if (alpha > 0) {  // PFC local damping: -alpha |F| sign(v), per component
        for (int c = 0; c < 3; ++c) {
            const double v = bodies.velocity[i][c], w = bodies.angular_velocity[i][c];
            const double fd = -alpha * std::fabs(f[c]) * ((v > 0) - (v < 0));
            const double md = -alpha * std::fabs(m[c]) * ((w > 0) - (w < 0));
            f[c] += fd;
            m[c] += md;
            local_work -= (fd * v + md * w) * last_dt;
        }
    }
    const double c = bodies.viscous_damping[i];
    if (c > 0) {  // mass-proportional: every mode decays at the same rate c/2 (quasi-static solves)
        const Vec fd = -c * bodies.mass[i] * bodies.velocity[i];
        const Vec md = -c * bodies.inertia[i] * bodies.angular_velocity[i];
        f += fd;
        m += md;
        local_work -= (fd.dot(bodies.velocity[i]) + md.dot(bodies.angular_velocity[i])) * last_dt;
    }
}

// Bodies [i0, i1) after their contact sums: field accumulations, damping
// (its work added to local_work), the 2D projection. False when a body's
// state may be non-finite.
bool World::finish_bodies(std::size_t i0, std::size_t i1, double& local_work) {
    if (any_accumulation_)  // fields of rates-stage models are summed after that stage
        for (std::size_t i = i0; i < i1; ++i)
            for (const BodyContact& en : body_contacts_.of(i)) {
                const ContactSet& s = *sets_[en.set];
                const std::uint32_t k = en.row();
                const ModelInstance& owner = *set_owner_[en.set];
                if (s.active[k] && !owner.desc->rates_stage) accumulate(owner, s, k, en.end2(), i);
            }
    const double *local_damping = bodies.local_damping.data(), *viscous_damping = bodies.viscous_damping.data();
    for (std::size_t i = i0; i < i1; ++i)
        if (local_damping[i] > 0 || viscous_damping[i] > 0) damp_body(i, bodies.force[i], bodies.moment[i], local_work);
    return bodies_finite(i0, i1);
}

// Bodies [i0, i1)'s sums, in a loop of their own (the damping's call made
// the compiler keep the flag and the columns' addresses in memory): a 2D
// world's force and moment projected on its plane, then false when a sum of
// a body's values is Inf or NaN (so is the sum then; an overflow of finite
// values too is caught, check_finite() tells which body).
bool World::bodies_finite(std::size_t i0, std::size_t i1) {
    Vec* force = bodies.force.data();
    Vec* moment = bodies.moment.data();
    const Vec *position = bodies.position.data(), *velocity = bodies.velocity.data();
    // an OR, not a running sum, so that no body waits for the previous one
    bool non_finite = false;
    if (dim == 2) {  // (z, vz of a 2D world are zero: Bodies::add, the kicks)
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
bool World::reduce(double closing_kick) {
    const std::size_t n = bodies.size();
    for (auto& inst : instances_)
        if (!inst->desc->rates_stage)
            for (int f : inst->fields_accumulated) std::fill(fields.column(f).begin(), fields.column(f).end(), 0.0);
    if (!swept_)  // force_sweep() summed the rows already
        for (std::uint32_t si = 0; si < sets_.size(); ++si) scatter_to_chunks(si);
    bool non_finite = false;
    const std::size_t n_blocks = body_blocks();
    block_local_work_.assign(n_blocks, 0.0);  // local damping work per block
    if (closing_kick > 0) leapfrog_.prepare_blocks(bodies);
#pragma omp parallel for schedule(static) reduction(| : non_finite) if (n >= parallel_min)
    for (std::size_t b = 0; b < n_blocks; ++b) {
        const std::size_t i0 = b * kBodyBlock, i1 = std::min(n, i0 + kBodyBlock);
        sums_.add_to_bodies(bodies, gravity, i0, i1);
        double work = 0;
        non_finite |= !finish_bodies(i0, i1, work);
        block_local_work_[b] = work;
        // the step's closing half kick while the block is in cache (advance())
        if (closing_kick > 0) leapfrog_.kick_block(bodies, b, closing_kick, true);
    }
    sums_.all_taken();  // (add_to_bodies() cleared every slot it took)
    double local_work = 0;
    for (double w : block_local_work_) local_work += w;
    energies.local_damping += local_work;
    stiffness_.invalidate();

    for (Wall& w : walls.walls) { w.force.setZero(); w.moment.setZero(); }
    for (auto& inst : instances_) {
        const ContactSet& s = inst->walls;
        for (std::size_t k = 0; k < s.size(); ++k) {
            if (!s.active[k]) continue;
            Wall& w = walls.walls[walls.facets[s.end2[k]].wall];
            const Vec fc(&s.force[3 * k]);
            w.force += fc;
            w.moment += (Vec(&s.point[3 * k]) - w.centre).cross(fc) + Vec(&s.moment2[3 * k]);
        }
    }
    return non_finite;
}

// Models with a rates stage accumulate field rates (SPH continuity) over
// this cycle's geometry; the sums land in their fields, then the passes of
// phase RATES_DONE turn them into states before any force is computed.
void World::rates_stage() {
    bool any = false;
    for (auto& inst : instances_) {
        if (!inst->desc->rates_stage) continue;
        any = true;
        for (int f : inst->fields_accumulated) std::fill(fields.column(f).begin(), fields.column(f).end(), 0.0);
        compute(*inst, inst->balls, PLAB_STAGE_RATES);
        compute(*inst, inst->walls, PLAB_STAGE_RATES);
    }
    if (!any) return;
    const std::size_t n = bodies.size();
#pragma omp parallel for schedule(static) if (n >= parallel_min)
    for (std::size_t i = 0; i < n; ++i)
        for (const BodyContact& en : body_contacts_.of(i)) {
            const ModelInstance& owner = *set_owner_[en.set];
            if (!owner.desc->rates_stage) continue;
            const ContactSet& s = *sets_[en.set];
            const std::uint32_t k = en.row();
            if (!s.active[k]) continue;
            accumulate(owner, s, k, en.end2(), i);
        }
    run_passes(PLAB_PHASE_RATES_DONE);
}

// A rates stage is needed when something reads what it sums: a pass (e.g.
// sph_density_integration reads sph_drho_dt) or a model that declares one
// of its accumulated fields. Otherwise the stage is skipped and those fields
// keep their last values (zero): with summation density, SPH's continuity
// sum feeds nothing, and skipping it halves the model's calls.
bool World::field_computed(int f) const {
    bool skipped = true, filled_by_rates = false;  // the rates stage runs for all or none (step())
    for (const auto& inst : instances_) {
        if (!inst->desc->rates_stage) continue;
        skipped &= !rates_stage_needed(*inst);
        const auto& acc = inst->fields_accumulated;
        filled_by_rates |= std::find(acc.begin(), acc.end(), f) != acc.end();
    }
    return !(skipped && filled_by_rates);
}

// Which fields hold their default at every body in this force pass: the
// ones a model reads that no pass declares and no model accumulates
// (nothing in the cycle writes them) and whose values are the default now.
// A scan each force pass, not a flag kept: a value set from outside
// (World::field(), a checkpoint) counts at once.
void World::find_fields_at_default() {
    std::vector<std::uint8_t>& at_default = field_at_default_;  // first the candidates (no allocation in the cycle)
    at_default.assign(fields.size(), 0);
    for (const auto& inst : instances_)
        for (int f : inst->fields_read) at_default[f] = 1;
    for (const auto& inst : instances_)
        for (int f : inst->fields_accumulated) at_default[f] = 0;
    for (const PassInstance& p : passes_)
        for (int f : p.fields) at_default[f] = 0;
    for (std::size_t f = 0; f < fields.size(); ++f) {
        if (!at_default[f]) continue;
        const double d = fields.default_value(int(f));
        at_default[f] = std::all_of(fields.column(f).begin(), fields.column(f).end(), [d](double v) { return v == d; });
    }
}

ReadFields World::read_fields(const ModelInstance& inst) const {
    ReadFields r;
    for (std::size_t f = 0; f < inst.fields_read.size(); ++f) {
        const int idx = inst.fields_read[f];
        r.cols[f] = fields.column(idx).data();
        // (the field's default is its first registrant's: it must be this model's too)
        const bool at_default = std::size_t(idx) < field_at_default_.size() && field_at_default_[idx] &&
                                fields.default_value(idx) == inst.desc->fields_read[f].default_value;
        if (at_default) r.at_default |= std::uint64_t(1) << f;
    }
    return r;
}

bool World::rates_stage_needed(const ModelInstance& inst) const {
    for (int f : inst.fields_accumulated) {
        for (const PassInstance& p : passes_)
            if (std::find(p.fields.begin(), p.fields.end(), f) != p.fields.end()) return true;
        for (const auto& other : instances_)
            if (std::find(other->fields_read.begin(), other->fields_read.end(), f) != other->fields_read.end())
                return true;
    }
    return false;
}

// PFC's per-ball estimate; the reason names the model and group that set
// it, so a diagnostic can say "2.1x the stable limit of model linear for
// group grains". Strings are built once, for the winner only.
StableStep World::stable_timestep() {
    sum_stiffness();
    if (!nominal_valid_) { nominal_cache_ = nominal_timestep(); nominal_valid_ = true; }
    StableStep best = nominal_cache_;
    std::size_t ball = bodies.size();
    bool rotation = false;
    // per-ball stiffness sums exist once forces were computed (prepare())
    const std::vector<double>&k_trans = stiffness_.translational(), &k_rot = stiffness_.rotational();
    const std::size_t summed = std::min(bodies.size(), k_trans.size());
    for (std::size_t i = 0; i < summed; ++i) {
        if (k_trans[i] > 0) {
            const double dt = std::sqrt(bodies.mass[i] / k_trans[i]);
            if (dt < best.critical) { best.critical = dt; ball = i; rotation = false; }
        }
        if (k_rot[i] > 0) {
            const double dt = std::sqrt(bodies.inertia[i] / k_rot[i]);
            if (dt < best.critical) { best.critical = dt; ball = i; rotation = true; }
        }
    }
    const ModelInstance* limit_model = nullptr;
    const ContactSet* limit_set = nullptr;
    std::size_t limit_row = 0;
    for (std::uint32_t si = 0; si < sets_.size(); ++si) {
        const ContactSet* s = sets_[si];
        auto consider = [&](double dt, std::size_t k) {
            if (!(dt < best.critical)) return;
            best.critical = dt;
            limit_model = set_owner_[si]; limit_set = s; limit_row = k;
            ball = bodies.size();
        };
        if (packed_.has_limits(si)) {  // (their rows are active)
            for (const BatchLimit& b : packed_.limits(si)) consider(b.dt, b.row);
            continue;
        }
        if (s->dt_limit.empty()) continue;  // a set that keeps no step limit has none (ContactSet::keeps)
        for (std::size_t k = 0; k < s->size(); ++k)
            if (s->active[k]) consider(s->dt_limit[k], k);
    }
    if (limit_model) {
        best.limited_by = "model " + limit_model->model + " for groups " + contact_groups(*limit_set, limit_row) +
                          ": its step limit";
    } else if (ball < bodies.size()) {
        best.limited_by = "model " + stiffest_model(ball) + " for group " + assignment_.group_name(bodies.group[ball]) + ": " +
                          (rotation ? "rotation" : "translation") + " of ball id " + std::to_string(bodies.id[ball]) +
                          (rotation ? " (sqrt(I/sum k_r))" : " (sqrt(m/sum k))");
    }
    return best;
}

// "grains-walls": the groups of a contact's two ends.
std::string World::contact_groups(const ContactSet& s, std::size_t k) const {
    const int g2 = s.with_wall ? walls.walls[walls.facets[s.end2[k]].wall].group : bodies.group[s.end2[k]];
    return assignment_.group_name(bodies.group[s.end1[k]]) + "-" + assignment_.group_name(g2);
}

// The model that gives ball i most of its stiffness.
std::string World::stiffest_model(std::size_t i) const {
    std::vector<double> k_of(instances_.size(), 0.0);
    if (body_contacts_.built_for(bodies.size()))
        for (const BodyContact& en : body_contacts_.of(i)) {
            const ContactSet& s = *sets_[en.set];
            const std::uint32_t k = en.row();
            if (!s.active[k]) continue;
            for (std::size_t m = 0; m < instances_.size(); ++m)
                if (set_owner_[en.set] == instances_[m].get()) k_of[m] += s.k_t_at(k);
        }
    const auto top = std::max_element(k_of.begin(), k_of.end());
    return top == k_of.end() || *top <= 0 ? std::string("(none)") : instances_[std::size_t(top - k_of.begin())]->model;
}

} // namespace plab

namespace plab {

std::vector<Eigen::Matrix3d> World::ball_stress() const {
    std::vector<Eigen::Matrix3d> sigma(bodies.size(), Eigen::Matrix3d::Zero());
    for (const auto& inst : instances_)
        for (const ContactSet* s : {&inst->balls, &inst->walls})
            for (std::size_t k = 0; k < s->size(); ++k) {
                if (!s->active[k]) continue;
                const Vec f2(&s->force[3 * k]), p = contact_point(*s, k);
                const int i = s->end1[k];
                sigma[i] += (p - bodies.position[i]) * (-f2).transpose();
                if (!s->with_wall) {
                    const int j = s->end2[k];
                    sigma[j] += (p - bodies.position[j]) * f2.transpose();
                }
            }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const double r = bodies.radius[i];
        const double volume = dim == 2 ? M_PI * r * r : 4.0 / 3.0 * M_PI * r * r * r;
        sigma[i] /= volume;
    }
    return sigma;
}

std::size_t World::bond(int a, int b, double gap_tolerance) {
    if (!prepared_) prepare();
    std::size_t made = 0;
    for (auto& inst : instances_) {
        const int slot = inst->desc->persist_slot;
        if (slot < 0) continue;
        ContactSet& s = inst->balls;
        for (std::size_t k = 0; k < s.size(); ++k) {
            const int g1 = bodies.group[s.end1[k]], g2 = bodies.group[s.end2[k]];
            if (!((g1 == a && g2 == b) || (g1 == b && g2 == a))) continue;
            if (contact_gap(s, k) > gap_tolerance) continue;
            s.history[k * inst->stride + slot] = 1;
            ++made;
        }
    }
    prepared_ = false;  // re-evaluate forces with the bonds in place
    return made;
}

std::size_t World::intact_bonds() const {
    std::size_t n = 0;
    for (const auto& inst : instances_) {
        const int slot = inst->desc->persist_slot;
        if (slot < 0) continue;
        for (const ContactSet* s : {&inst->balls, &inst->walls})
            for (std::size_t k = 0; k < s->size(); ++k) n += s->history[k * inst->stride + slot] > 0;
    }
    return n;
}

} // namespace plab
