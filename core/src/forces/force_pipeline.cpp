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
        for (std::uint32_t si = 0; si < in_.sets.size(); ++si) force_sweep(si);
        in_range_marked_ = false;
    } else if (swept_) {
        for (std::uint32_t si = 0; si < in_.sets.size(); ++si) force_sweep(si);
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

// A ball–ball set keeps no geometry columns (ContactSet::packed) when its
// rows are packed with their geometry (packer_of) and no rates stage needs
// every row's geometry before the forces (run(): swept_).
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

// Calls the model once on the active rows of [o, o + m) of a set whose
// geometry is in its columns, packed (forces/table_batch.cpp); returns its
// status. `clear`: zero the outputs of every row first (the rates stage
// writes some that the force stage must not see); otherwise the geometry
// zeroed those of the active rows, which are the only ones a model writes.
int ForcePipeline::call_on_table(ModelInstance& inst, ContactSet& s, std::size_t o, std::size_t m, std::uint32_t stage,
                                 const ReadFields& fields, bool clear) {
    if (clear) clear_outputs(s, o, m);  // here rather than up front: the rows stay in cache for the model
    DenseBatch& d = DenseBatch::for_this_thread(std::size_t(inst.stride));
    pack_table_rows(inst, s, o, o + m, d);
    const BatchCall call{stage, s.with_wall};
    const int status = call_model(inst, d, in_.dim, in_.last_dt, fields, call);
    unpack_table_rows(inst, s, d, stage == PLAB_STAGE_RATES || !inst.desc->rates_stage);
    return status;
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
        if (call_on_table(inst, s, o, m, stage, fields, true) != 0) failed = 1;
    }
    if (failed) model_failed(inst);
    if (inst.desc->persist_slot >= 0) record_breaks(inst, s);
}

void ForcePipeline::model_failed(const ModelInstance& inst) const {
    throw RunError("contact model '" + inst.model + "' reported a failure in compute() at step " +
                   std::to_string(in_.step_count));
}

// The force pass of one set in a single sweep over its chunks
// (reduction/chunked_sums.hpp), batch by batch (force_batch), each batch's
// forces added to its chunk's partial sums while it is in cache. Batches
// and chunks are fixed row ranges, so every sum is thread-count free.
void ForcePipeline::force_sweep(std::uint32_t si) {
    ContactSet& s = *in_.sets[si];
    ModelInstance& inst = *in_.instances[si / 2];
    const std::size_t n = s.size();
    s.batch_energy.assign(kBatchEnergies * ((n + kContactBatch - 1) / kContactBatch), 0.0);
    if (n == 0) return;
    const ReadFields fields = read_fields(inst);
    const Packer packer = packer_of(inst, s);
    const std::uint32_t c0 = reduction_.chunks.first_chunk(si), c1 = reduction_.chunks.end_chunk(si);
    if (packer == Packer::centre_pair && inst.uses(PLAB_IO_DT_LIMIT))
        packed[si].limits.assign((n + kContactBatch - 1) / kContactBatch, BatchLimit{kInf, 0});
    // a still table (StillInstances) whose rows mark_ball_rows_in_range()
    // tested: nothing to pack, only its chunks' partial sums to clear
    const bool still = packer == Packer::centre_pair && in_range_marked_ && si < in_range_.size() &&
                       in_range_[si].listed && still_.centre_table_still(si, s, in_.instances);
    if (still) hold_still(s);
    else s.forces_zero = false;
    int failed = 0;
    bool exceeded = false;
#pragma omp parallel for schedule(static) reduction(| : failed, exceeded) if (n >= in_.parallel_min)
    for (std::uint32_t c = c0; c < c1; ++c) {
        Chunk& ch = reduction_.chunks.chunk(c);
        reduction_.chunks.clear(ch, in_.dim);
        ch.forces_only = packer == Packer::centre_pair;
        if (still) continue;
        for (std::size_t o = ch.begin; o < ch.end; o += kContactBatch)
            failed |= force_batch(packer, inst, si, o, std::min(kContactBatch, ch.end - o), fields, ch, exceeded) != 0;
    }
    if (!s.with_wall) s.overlap_exceeded = exceeded;  // (a wall table's: geometry())
    if (failed) model_failed(inst);
    if (inst.desc->persist_slot >= 0) record_breaks(inst, s);
}

// How a table's rows reach its model. Ball–ball rows are packed with their
// geometry, by the model's kind: the pair's full kinematics, or only what a
// force between centres needs (PLAB_MODEL_FORCE_AT_CENTRES: no spin,
// moments, stiffness or energies). Ball–wall rows, and those of a model
// that sums body fields in the force stage (the sums go to the columns,
// Reduction::reduce), are packed from the geometry in the columns; a
// rates-stage model's force-stage sums are not kept, so it packs as any.
ForcePipeline::Packer ForcePipeline::packer_of(const ModelInstance& inst, const ContactSet& s) const {
    if (s.with_wall || !(inst.fields_accumulated.empty() || inst.desc->rates_stage)) return Packer::table;
    return (inst.desc->flags & PLAB_MODEL_FORCE_AT_CENTRES) ? Packer::centre_pair : Packer::ball_pair;
}

// One batch of rows [o, o + m) of set si through the pipeline: its geometry
// and packing, the model, and the forces into the chunk's partial sums.
// Returns the model's status; `exceeded` set when a row overlaps beyond
// max_overlap.
int ForcePipeline::force_batch(Packer packer, ModelInstance& inst, std::uint32_t si, std::size_t o, std::size_t m,
                               const ReadFields& fields, const Chunk& ch, bool& exceeded) {
    ContactSet& s = *in_.sets[si];
    DenseBatch& d = DenseBatch::for_this_thread(std::size_t(inst.stride));
    switch (packer) {
    case Packer::ball_pair: exceeded |= pack_ball_rows(inst, si, o, o + m, d); break;
    case Packer::centre_pair: exceeded |= pack_centre_rows(inst, si, o, o + m, d); break;
    case Packer::table:
        if (!s.with_wall) exceeded |= contact_geometry(in_.bodies, in_.walls, inst, s, o, o + m);
        pack_table_rows(inst, s, o, o + m, d);
        break;
    }
    const int status = call_model(inst, d, in_.dim, in_.last_dt, fields, {PLAB_STAGE_FORCES, s.with_wall});
    switch (packer) {
    case Packer::ball_pair: unpack_rows(si, inst, d, o, ch); break;
    case Packer::centre_pair: unpack_centre_rows(si, inst, d, o, ch); break;
    case Packer::table:
        unpack_table_rows(inst, s, d, !inst.desc->rates_stage);
        reduction_.scatter_rows(si, o, o + m, ch);
        break;
    }
    return status;
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
