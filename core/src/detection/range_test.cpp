// The range test before the passes of phase RATES_DONE, when a rates-stage
// model's own stage is skipped (summation density: docs/sph.md) and its
// forces come from the packed sweep after those passes. One sweep over the
// candidates sets the active flags (and gaps) every reader sees, lists the
// passes' contacts (what PassContacts::list_active() would list, in the same
// order) with their centre distance (the passes' contact_distance, abi.h:
// summation density needs no square root of its own) and, for the
// centre-force path, the rows in range of each batch with their centre
// distance, so that pack_centre_rows() visits only those.
#include "forces/packed_batch.hpp"

#include <algorithm>

namespace plab {

namespace {
// The centre-force path of force_sweep() takes this set's rows packed.
bool on_centre_path(const ModelInstance& inst) {
    return (inst.desc->flags & PLAB_MODEL_FORCE_AT_CENTRES) &&
           (inst.fields_accumulated.empty() || inst.desc->rates_stage);
}
} // namespace

void ForcePipeline::mark_ball_rows_in_range() {
    const bool list = !in_.passes.empty();
    if (list) in_.pass_contacts.start();
    in_range_.resize(in_.sets.size());
    for (std::uint32_t si = 0; si < in_.sets.size(); ++si) {
        ContactSet& s = *in_.sets[si];
        in_range_[si].listed = false;
        if (s.with_wall) {  // the geometry set their flags
            if (list) in_.pass_contacts.append_active_wall_rows(s);
            continue;
        }
        mark_set_in_range(si, list);
    }
    if (list) in_.pass_contacts.finish();
    in_range_marked_ = true;
}

// Set si's candidates, batch by batch (threads take whole batches), with
// the packers' range test (range_test_rows: flags, gaps, history of rows
// that left the range): the rows in range of batch b listed from
// b * kContactBatch on, then the
// passes' contacts appended in batch order, so the list is the same for
// any thread count (`list`: there are passes).
void ForcePipeline::mark_set_in_range(std::uint32_t si, bool list) {
    const ModelInstance& inst = *in_.set_owner[si];
    RowsInRange& r = in_range_[si];
    const bool centre = on_centre_path(inst);
    const std::size_t n = in_.sets[si]->size(), n_batches = (n + kContactBatch - 1) / kContactBatch;
    r.count.resize(n_batches);
    r.row.resize(n);
    const bool distances = centre || list;  // (the packer's and the passes')
    r.distance.resize(distances ? n : 0);
#pragma omp parallel for schedule(static) if (n >= in_.parallel_min)
    for (std::size_t b = 0; b < n_batches; ++b) {
        const std::size_t k0 = b * kContactBatch, k1 = std::min(n, k0 + kContactBatch);
        r.count[b] = std::uint32_t(range_test_rows(inst, si, k0, k1, r.row.data() + k0,
                                                   distances ? r.distance.data() + k0 : nullptr));
    }
    r.listed = centre;
    if (list) in_.pass_contacts.append_in_range(*in_.sets[si], r, in_.parallel_min);
}

} // namespace plab
