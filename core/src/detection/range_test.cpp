// The range test before the passes of phase RATES_DONE, when a rates-stage
// model's own stage is skipped (summation density: docs/sph.md) and its
// forces come from the packed sweep after those passes. One sweep over the
// candidates sets the active flags (and gaps) every reader sees, lists the
// passes' contacts (what build_pass_contacts() would list, in the same
// order) with their centre distance (the passes' contact_distance, abi.h
// ABI 6: summation density needs no square root of its own) and, for the
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

void World::mark_ball_rows_in_range() {
    const bool list = !passes_.empty();
    std::size_t listed = 0;  // rows of the pass-contact columns listed so far
    in_range_.resize(sets_.size());
    for (std::uint32_t si = 0; si < sets_.size(); ++si) {
        ContactSet& s = *sets_[si];
        in_range_[si].listed = false;
        if (s.with_wall) {  // geometry() set their flags
            if (list) {
                std::size_t m = 0;
                for (std::size_t k = 0; k < s.size(); ++k) m += s.active[k] != 0;
                if (pc_end1_.size() < listed + m) resize_pass_contacts(listed + m);  // (only the new tail is cleared)
                for (std::size_t k = 0; k < s.size(); ++k)
                    if (s.active[k]) {
                        pc_end1_[listed] = s.end1[k];
                        pc_end2_[listed] = s.end2[k];
                        pc_wall_[listed] = 1;
                        pc_distance_[listed] = s.distance[k];
                        ++listed;
                    }
            }
            continue;
        }
        mark_set_in_range(si, list ? &listed : nullptr);
    }
    if (list) resize_pass_contacts(listed);  // down to the rows listed (a shrink: nothing cleared)
    in_range_marked_ = true;
}

void World::resize_pass_contacts(std::size_t n) {
    pc_end1_.resize(n);
    pc_end2_.resize(n);
    pc_wall_.resize(n);
    pc_distance_.resize(n);
}

// Set si's candidates, batch by batch (threads take whole batches), with
// the packers' range test (range_test_rows: flags, gaps, history of rows
// that left the range): the rows in range of batch b listed from
// b * kContactBatch on, then the
// passes' contacts appended in batch order, so the list is the same for
// any thread count. `listed`: the pass-contact rows so far (null: no
// passes, no list).
void World::mark_set_in_range(std::uint32_t si, std::size_t* listed) {
    const bool list = listed != nullptr;
    const ModelInstance& inst = *set_owner_[si];
    RowsInRange& r = in_range_[si];
    const bool centre = on_centre_path(inst);
    const std::size_t n = sets_[si]->size(), n_batches = (n + kContactBatch - 1) / kContactBatch;
    r.count.resize(n_batches);
    r.row.resize(n);
    const bool distances = centre || list;  // (the packer's and the passes')
    r.distance.resize(distances ? n : 0);
#pragma omp parallel for schedule(static) if (n >= parallel_min)
    for (std::size_t b = 0; b < n_batches; ++b) {
        const std::size_t k0 = b * kContactBatch, k1 = std::min(n, k0 + kContactBatch);
        r.count[b] = std::uint32_t(range_test_rows(inst, si, k0, k1, r.row.data() + k0,
                                                   distances ? r.distance.data() + k0 : nullptr));
    }
    r.listed = centre;
    if (list) append_pass_contacts(si, *listed);
}

// The passes' contacts of ball–ball set si from its rows in range, each
// batch's at its place in the list (threads take whole batches).
void World::append_pass_contacts(std::uint32_t si, std::size_t& listed) {
    const ContactSet& s = *sets_[si];
    const RowsInRange& r = in_range_[si];
    const std::size_t n_batches = r.count.size(), base = listed;
    batch_at_.resize(n_batches);  // where each batch's rows start in the list
    std::size_t total = 0;
    for (std::size_t b = 0; b < n_batches; ++b) { batch_at_[b] = base + total; total += r.count[b]; }
    if (pc_end1_.size() < base + total) resize_pass_contacts(base + total);
    listed = base + total;
#pragma omp parallel for schedule(static) if (s.size() >= parallel_min)
    for (std::size_t b = 0; b < n_batches; ++b) {
        const std::uint32_t* row = r.row.data() + b * kContactBatch;
        const std::size_t at = batch_at_[b];
        for (std::size_t a = 0; a < r.count[b]; ++a) {
            pc_end1_[at + a] = s.end1[row[a]];
            pc_end2_[at + a] = s.end2[row[a]];
        }
        std::copy_n(r.distance.data() + b * kContactBatch, r.count[b], pc_distance_.data() + at);
        std::fill_n(pc_wall_.data() + at, r.count[b], std::uint8_t(0));
    }
}

} // namespace plab
