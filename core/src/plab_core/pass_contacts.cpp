// The range test before the passes of phase RATES_DONE, when a rates-stage
// model's own stage is skipped (summation density: docs/sph.md) and its
// forces come from the packed sweep after those passes. One sweep over the
// candidates sets the active flags and gaps every reader sees, lists the
// passes' contacts (what build_pass_contacts() would list, in the same
// order) and, for the centre-force path, the rows in range of each batch with
// their centre distance, so that pack_centre_rows() visits only those.
#include "dense_batch.hpp"

#include <algorithm>

namespace plab {

namespace {
// The centre-force path of force_sweep() takes this set's rows packed.
bool on_centre_path(const ModelInstance& inst) {
    return (inst.desc->flags & PLAB_MODEL_FORCE_AT_CENTRES) &&
           (inst.fields_accumulated.empty() || inst.desc->rates_stage);
}
} // namespace

void World::mark_ball_rows_in_range() {
    const bool list = !passes_.empty();
    if (list) { pc_end1_.clear(); pc_end2_.clear(); pc_wall_.clear(); }
    in_range_.resize(sets_.size());
    for (std::uint32_t si = 0; si < sets_.size(); ++si) {
        ContactSet& s = *sets_[si];
        in_range_[si].listed = false;
        if (s.with_wall) {  // geometry() set their flags
            if (list)
                for (std::size_t k = 0; k < s.size(); ++k)
                    if (s.active[k]) { pc_end1_.push_back(s.end1[k]); pc_end2_.push_back(s.end2[k]); pc_wall_.push_back(1); }
            continue;
        }
        mark_set_in_range(si, list);
    }
    in_range_marked_ = true;
}

// Set si's candidates, batch by batch (threads take whole batches): the
// rows in range of batch b listed from b * kContactBatch on, then the
// passes' contacts appended in batch order, so the list is the same for
// any thread count.
void World::mark_set_in_range(std::uint32_t si, bool list) {
    ContactSet& s = *sets_[si];
    const ModelInstance& inst = *set_owner_[si];
    RowsInRange& r = in_range_[si];
    const bool centre = on_centre_path(inst);
    const std::size_t n = s.size(), n_batches = (n + kContactBatch - 1) / kContactBatch;
    r.count.resize(n_batches);
    r.row.resize(n);
    r.distance.resize(centre ? n : 0);
    const RangeTest in_range(inst);
    const auto& B = bodies;
#pragma omp parallel for schedule(static) if (n >= parallel_min)
    for (std::size_t b = 0; b < n_batches; ++b) {
        const std::size_t k0 = b * kContactBatch, k1 = std::min(n, k0 + kContactBatch);
        std::uint32_t* row = r.row.data() + k0;
        double* distance = centre ? r.distance.data() + k0 : nullptr;
        // the columns' addresses held here: the stores below could alias them otherwise
        const std::int32_t *end1 = s.end1.data(), *end2 = s.end2.data();
        const double *radius1 = s.radius1.data(), *radius2 = s.radius2.data();
        const Vec* x = B.position.data();
        double* gaps = s.gap.data();
        std::uint8_t* flags = s.active.data();
        std::size_t c = 0;
        for (std::size_t k = k0; k < k1; ++k) {  // no branch per row: in-range flags follow no pattern
            const double dist = (x[end2[k]] - x[end1[k]]).norm();
            const double gap = dist - radius1[k] - radius2[k];
            const bool active = in_range(s.history, k, dist, gap);
            gaps[k] = gap;
            flags[k] = active;
            row[c] = std::uint32_t(k);
            if (centre) distance[c] = dist;
            c += active;
        }
        r.count[b] = std::uint32_t(c);
        if (centre) forget_left_rows(inst, si, k0, k1);
    }
    r.listed = centre;
    if (list) append_pass_contacts(si);
}

// The passes' contacts of ball–ball set si from its rows in range.
void World::append_pass_contacts(std::uint32_t si) {
    const ContactSet& s = *sets_[si];
    const RowsInRange& r = in_range_[si];
    const std::size_t n_batches = r.count.size(), base = pc_end1_.size();
    std::size_t total = 0;
    for (std::uint32_t c : r.count) total += c;
    pc_end1_.resize(base + total);
    pc_end2_.resize(base + total);
    pc_wall_.resize(base + total, 0);
    std::size_t at = base;
    for (std::size_t b = 0; b < n_batches; ++b) {
        const std::uint32_t* row = r.row.data() + b * kContactBatch;
        for (std::size_t a = 0; a < r.count[b]; ++a) {
            pc_end1_[at + a] = s.end1[row[a]];
            pc_end2_[at + a] = s.end2[row[a]];
        }
        at += r.count[b];
    }
}

// The history of rows [k0, k1) that just left the range back to the model's
// declared defaults (a separated contact is forgotten, as range_test_rows()
// does), after the active flags of those rows were set.
void World::forget_left_rows(const ModelInstance& inst, std::uint32_t si, std::size_t k0, std::size_t k1) {
    ContactSet& s = *sets_[si];
    std::uint8_t* live = live_[si].data();
    const std::size_t stride = std::size_t(inst.stride);
    if (stride == 0) return;  // nothing to forget (SPH), and `live` is read for history only
    for (std::size_t k = k0; k < k1; ++k) {
        if (live[k] && !s.active[k])
            for (std::size_t h = 0; h < stride; ++h) s.history[k * stride + h] = inst.desc->history[h].default_value;
        live[k] = s.active[k];
    }
}

} // namespace plab
