#include "detection/range_test.hpp"

#include <algorithm>

namespace plab {

void PassContacts::resize(std::size_t n) {
    end1_.resize(n);
    end2_.resize(n);
    wall_.resize(n);
    distance_.resize(n);
}

// (the distances stay as they are: distance(false) hides them)
void PassContacts::list_active(const std::vector<ContactSet*>& tables) {
    end1_.clear(); end2_.clear(); wall_.clear();
    for (const ContactSet* s : tables)
        for (std::size_t k = 0; k < s->size(); ++k)
            if (s->active[k]) {
                end1_.push_back(s->end1[k]);
                end2_.push_back(s->end2[k]);
                wall_.push_back(s->with_wall);
            }
}

void PassContacts::append_active_wall_rows(const ContactSet& s) {
    std::size_t m = 0;
    for (std::size_t k = 0; k < s.size(); ++k) m += s.active[k] != 0;
    if (end1_.size() < listed_ + m) resize(listed_ + m);  // (only the new tail is cleared)
    for (std::size_t k = 0; k < s.size(); ++k)
        if (s.active[k]) {
            end1_[listed_] = s.end1[k];
            end2_[listed_] = s.end2[k];
            wall_[listed_] = 1;
            distance_[listed_] = s.distance[k];
            ++listed_;
        }
}

// Each batch's rows at their place in the list (threads take whole batches).
void PassContacts::append_in_range(const ContactSet& s, const RowsInRange& r, std::size_t parallel_min) {
    const std::size_t n_batches = r.count.size(), base = listed_;
    batch_at_.resize(n_batches);  // where each batch's rows start in the list
    std::size_t total = 0;
    for (std::size_t b = 0; b < n_batches; ++b) { batch_at_[b] = base + total; total += r.count[b]; }
    if (end1_.size() < base + total) resize(base + total);
    listed_ = base + total;
#pragma omp parallel for schedule(static) if (s.size() >= parallel_min)
    for (std::size_t b = 0; b < n_batches; ++b) {
        const std::uint32_t* row = r.row.data() + b * kContactBatch;
        const std::size_t at = batch_at_[b];
        for (std::size_t a = 0; a < r.count[b]; ++a) {
            end1_[at + a] = s.end1[row[a]];
            end2_[at + a] = s.end2[row[a]];
        }
        std::copy_n(r.distance.data() + b * kContactBatch, r.count[b], distance_.data() + at);
        std::fill_n(wall_.data() + at, r.count[b], std::uint8_t(0));
    }
}

} // namespace plab
