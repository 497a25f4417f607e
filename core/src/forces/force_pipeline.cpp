// The force pipeline (force_pipeline.hpp): the host computes each candidate
// contact's geometry once (normal, gap, contact point, relative velocity),
// calls each model once per batch of contacts, and scatters the rows' forces
// into the reduction's partial sums.
#include "forces/force_pipeline.hpp"

#include <plab_host/errors.hpp>

#include "contacts/contact_keys.hpp"
#include "forces/geometry.hpp"
#include "forces/packed_batch.hpp"
#include "forces/row_lists.hpp"
#include "forces/tangential_history.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

namespace plab {

// Without a rates stage, each table is done in one sweep over batches
// (geometry, model, scatter to slots); a rates stage needs all the geometry
// before any force. A rates stage whose sums nothing reads is skipped
// (rates_stage_needed).
void ForcePipeline::run(const std::function<void(std::uint32_t)>& run_passes) {
    find_fields_at_default();
    packed.clear_limits(in_.sets.size());  // force_sweep() keeps those of centre-force sets, the columns the others'
    still_.find(in_.bodies, in_.groups, in_.instances);
    bool rates_models = false;
    swept_ = true;
    for (auto& inst : in_.instances) {
        rates_models |= inst->desc->rates_stage != 0;
        swept_ &= !(inst->desc->rates_stage && rates_stage_needed(*inst));
    }
    for (std::uint32_t si = 0; si < in_.sets.size(); ++si) {
        ModelInstance& inst = *in_.instances[si / 2];
        ContactSet& s = *in_.sets[si];
        if (!s.with_wall && swept_) continue;  // geometry in the sweep
        geometry(inst, s);
        if (s.with_wall) resolve_wall_features(in_.bodies, in_.walls, s);
    }
    if (swept_ && rates_models) {
        // the passes that turn rates into states (e.g. summation density,
        // the EOS) still run before the forces, on this cycle's contacts
        mark_ball_rows_in_range();  // (it lists the passes' contacts too)
        run_passes(PLAB_PHASE_RATES_DONE);
        for (std::uint32_t si = 0; si < in_.sets.size(); ++si) force_sweep(si, !in_.sets[si]->with_wall);
        in_range_marked_ = false;
    } else if (swept_) {
        for (std::uint32_t si = 0; si < in_.sets.size(); ++si) force_sweep(si, !in_.sets[si]->with_wall);
        if (!in_.passes.empty()) in_.pass_contacts.list_active(in_.sets);  // the sweeps set the active flags
    } else {
        if (!in_.passes.empty()) in_.pass_contacts.list_active(in_.sets);
        rates_stage(run_passes);
        for (std::uint32_t m = 0; m < in_.instances.size(); ++m) {
            ModelInstance& inst = *in_.instances[m];
            if (still_.centre_table_still(2 * m, inst.balls, in_.instances)) hold_still(inst.balls);  // (as force_sweep)
            else compute(inst, inst.balls, PLAB_STAGE_FORCES);
            compute(inst, inst.walls, PLAB_STAGE_FORCES);
        }
    }
}

void ForcePipeline::forget_rows() {
    packed.forget(in_.sets);
    packed.clear_limits(in_.sets.size());
}

// A set is packed when force_sweep() takes the dense path for it: no rates
// stage runs over full columns (force_pass(): swept_), and its model
// accumulates nothing or only sums of a rates stage, which is skipped.
bool ForcePipeline::packs_balls(const ModelInstance& inst) const {
    for (const auto& other : in_.instances)
        if (other->desc->rates_stage && rates_stage_needed(*other)) return false;
    return inst.fields_accumulated.empty() || inst.desc->rates_stage;
}


void ForcePipeline::geometry(ModelInstance& inst, ContactSet& s) {
    const std::size_t n = s.size();
    const std::size_t n_batches = (n + kContactBatch - 1) / kContactBatch;
    bool exceeded = false;
#pragma omp parallel for schedule(static) reduction(| : exceeded) if (n >= in_.parallel_min)
    for (std::size_t b = 0; b < n_batches; ++b)
        exceeded |= contact_geometry(in_.bodies, in_.walls, inst, s, b * kContactBatch, std::min(n, (b + 1) * kContactBatch));
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
int ForcePipeline::call_model(ModelInstance& inst, ContactSet& s, std::size_t o, std::size_t m, std::uint32_t stage,
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
    batch.dim = uint32_t(in_.dim);
    batch.count = uint32_t(m);
    batch.end2_is_wall = s.with_wall;
    batch.history_stride = uint32_t(inst.stride);
    batch.dt = in_.last_dt;
    bind_rows(batch, s, o, s.history.data() + o * inst.stride);
    batch.body_fields = fields.cols;
    batch.body_fields_at_default = fields.at_default;
    batch.accumulate1 = a1;
    batch.accumulate2 = a2;
    batch.stage = stage;
    return inst.desc->compute(inst.state, inst.props.data(), &batch);
}

void ForcePipeline::compute(ModelInstance& inst, ContactSet& s, std::uint32_t stage) {
    const std::size_t n = s.size();
    if (n == 0) return;
    const ReadFields fields = read_fields(inst);
    const std::size_t n_batches = (n + kContactBatch - 1) / kContactBatch;
    s.forces_zero = false;  // (any stage may write the outputs)
    int failed = 0;
#pragma omp parallel for schedule(static) reduction(| : failed) if (n >= in_.parallel_min)
    for (std::size_t b = 0; b < n_batches; ++b) {
        const std::size_t o = b * kContactBatch, m = std::min(kContactBatch, n - o);
        if (call_model(inst, s, o, m, stage, fields, true) != 0) failed = 1;
    }
    if (failed) model_failed(inst);
    if (inst.desc->persist_slot >= 0) record_breaks(inst, s);
}

void ForcePipeline::model_failed(const ModelInstance& inst) const {
    throw RunError("contact model '" + inst.model + "' reported a failure in compute() at step " +
                   std::to_string(in_.step_count));
}

// The force pass of one set in a single sweep over its chunks (reduction/chunked_sums.hpp),
// batch by batch: geometry (ball–ball sets; a wall set has it done before,
// because resolve_wall_features needs a ball's rows together), the model,
// and the rows' forces added to the chunk's partial sums while the batch is
// in cache. Batches and chunks are fixed row ranges, so every sum is
// thread-count free.
void ForcePipeline::force_sweep(std::uint32_t si, bool with_geometry) {
    ContactSet& s = *in_.sets[si];
    ModelInstance& inst = *in_.instances[si / 2];
    const std::size_t n = s.size();
    s.batch_energy.assign(kBatchEnergies * ((n + kContactBatch - 1) / kContactBatch), 0.0);
    if (n == 0) return;
    const ReadFields fields = read_fields(inst);
    // ball–ball rows go to the model packed (forces/packed_batch.hpp), unless it
    // accumulates body fields in this stage (those sums walk the full
    // columns, reduce()); a rates-stage model's force-stage sums are not kept
    const bool dense = with_geometry && (inst.fields_accumulated.empty() || inst.desc->rates_stage);
    const bool at_centres = (inst.desc->flags & PLAB_MODEL_FORCE_AT_CENTRES) != 0;
    const std::uint32_t c0 = reduction_.chunks.first_chunk(si), c1 = reduction_.chunks.end_chunk(si);
    if (dense && at_centres && inst.uses(PLAB_IO_DT_LIMIT))
        packed[si].limits.assign((n + kContactBatch - 1) / kContactBatch, BatchLimit{kInf, 0});
    // a still table (StillInstances) whose rows mark_ball_rows_in_range()
    // tested: nothing to pack, only its chunks' partial sums to clear
    const bool still = dense && at_centres && in_range_marked_ && si < in_range_.size() && in_range_[si].listed &&
                       still_.centre_table_still(si, s, in_.instances);
    if (still) hold_still(s);
    else s.forces_zero = false;
    int failed = 0;
    bool exceeded = false;
#pragma omp parallel for schedule(static) reduction(| : failed, exceeded) if (n >= in_.parallel_min)
    for (std::uint32_t c = c0; c < c1; ++c) {
        Chunk& ch = reduction_.chunks.chunk(c);
        reduction_.chunks.clear(ch, in_.dim);
        ch.forces_only = dense && at_centres;
        if (still) continue;
        for (std::size_t o = ch.begin; o < ch.end; o += kContactBatch) {
            const std::size_t m = std::min(kContactBatch, ch.end - o);
            if (dense && at_centres) {  // SPH: no spin, moments, stiffness or energies
                DenseBatch& d = DenseBatch::for_this_thread(std::size_t(inst.stride));
                exceeded |= pack_centre_rows(inst, si, o, o + m, d);
                if (call_model_dense(inst, d, in_.dim, in_.last_dt, fields) != 0) failed = 1;
                unpack_centre_rows(si, inst, d, o, ch);
                continue;
            }
            if (dense) {
                DenseBatch& d = DenseBatch::for_this_thread(std::size_t(inst.stride));
                exceeded |= pack_ball_rows(inst, si, o, o + m, d);
                if (call_model_dense(inst, d, in_.dim, in_.last_dt, fields) != 0) failed = 1;
                unpack_rows(si, inst, d, o, ch);
                continue;
            }
            if (with_geometry) exceeded |= contact_geometry(in_.bodies, in_.walls, inst, s, o, o + m);
            if (call_model(inst, s, o, m, PLAB_STAGE_FORCES, fields, false) != 0) failed = 1;
            reduction_.scatter_rows(si, o, o + m, ch);
        }
    }
    if (with_geometry) s.overlap_exceeded = exceeded;
    if (failed) model_failed(inst);
    if (inst.desc->persist_slot >= 0) record_breaks(inst, s);
}

// A model marks a bond it just broke with -mode in its persist slot; the
// host records the break and leaves the contact unbonded.
void ForcePipeline::record_breaks(ModelInstance& inst, ContactSet& s) {
    const int slot = inst.desc->persist_slot;
    for (std::size_t k = 0; k < s.size(); ++k) {
        double& state = s.history[k * inst.stride + slot];
        if (state >= 0) continue;
        BondBreak b;
        b.step = in_.step_count;
        b.time = in_.time;
        std::tie(b.id1, b.id2) = row_key(in_.bodies, in_.walls, s, k);
        b.point = row_point(in_.bodies, s, k);
        b.mode = int(-state);
        b.model = inst.model;
        in_.bond_breaks.push_back(b);
        state = 0;
    }
}








// Models with a rates stage accumulate field rates (SPH continuity) over
// this cycle's geometry; the sums land in their fields, then the passes of
// phase RATES_DONE turn them into states before any force is computed.
void ForcePipeline::rates_stage(const std::function<void(std::uint32_t)>& run_passes) {
    bool any = false;
    for (auto& inst : in_.instances) {
        if (!inst->desc->rates_stage) continue;
        any = true;
        for (int f : inst->fields_accumulated) std::fill(in_.fields.column(f).begin(), in_.fields.column(f).end(), 0.0);
        compute(*inst, inst->balls, PLAB_STAGE_RATES);
        compute(*inst, inst->walls, PLAB_STAGE_RATES);
    }
    if (!any) return;
    const std::size_t n = in_.bodies.size();
#pragma omp parallel for schedule(static) if (n >= in_.parallel_min)
    for (std::size_t i = 0; i < n; ++i)
        for (const BodyContact& en : in_.body_contacts.of(i)) {
            const ModelInstance& owner = *in_.set_owner[en.set];
            if (!owner.desc->rates_stage) continue;
            const ContactSet& s = *in_.sets[en.set];
            const std::uint32_t k = en.row();
            if (!s.active[k]) continue;
            reduction_.accumulate(owner, s, k, en.end2(), i);
        }
    run_passes(PLAB_PHASE_RATES_DONE);
}

// A rates stage is needed when something reads what it sums: a pass (e.g.
// sph_density_integration reads sph_drho_dt) or a model that declares one
// of its accumulated fields. Otherwise the stage is skipped and those fields
// keep their last values (zero): with summation density, SPH's continuity
// sum feeds nothing, and skipping it halves the model's calls.
bool ForcePipeline::field_computed(int f) const {
    bool skipped = true, filled_by_rates = false;  // the rates stage runs for all or none (step())
    for (const auto& inst : in_.instances) {
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
// (a command that sets a field, a checkpoint) counts at once.
void ForcePipeline::find_fields_at_default() {
    std::vector<std::uint8_t>& at_default = field_at_default_;  // first the candidates (no allocation in the cycle)
    at_default.assign(in_.fields.size(), 0);
    for (const auto& inst : in_.instances)
        for (int f : inst->fields_read) at_default[f] = 1;
    for (const auto& inst : in_.instances)
        for (int f : inst->fields_accumulated) at_default[f] = 0;
    for (const PassInstance& p : in_.passes)
        for (int f : p.fields) at_default[f] = 0;
    for (std::size_t f = 0; f < in_.fields.size(); ++f) {
        if (!at_default[f]) continue;
        const double d = in_.fields.default_value(int(f));
        at_default[f] = std::all_of(in_.fields.column(f).begin(), in_.fields.column(f).end(), [d](double v) { return v == d; });
    }
}

ReadFields ForcePipeline::read_fields(const ModelInstance& inst) const {
    ReadFields r;
    for (std::size_t f = 0; f < inst.fields_read.size(); ++f) {
        const int idx = inst.fields_read[f];
        r.cols[f] = in_.fields.column(idx).data();
        // (the field's default is its first registrant's: it must be this model's too)
        const bool at_default = std::size_t(idx) < field_at_default_.size() && field_at_default_[idx] &&
                                in_.fields.default_value(idx) == inst.desc->fields_read[f].default_value;
        if (at_default) r.at_default |= std::uint64_t(1) << f;
    }
    return r;
}

bool ForcePipeline::rates_stage_needed(const ModelInstance& inst) const {
    for (int f : inst.fields_accumulated) {
        for (const PassInstance& p : in_.passes)
            if (std::find(p.fields.begin(), p.fields.end(), f) != p.fields.end()) return true;
        for (const auto& other : in_.instances)
            if (std::find(other->fields_read.begin(), other->fields_read.end(), f) != other->fields_read.end())
                return true;
    }
    return false;
}




} // namespace plab
