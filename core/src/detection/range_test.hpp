// The range test of the ball–ball tables before the passes of phase
// RATES_DONE (detection/range_test.cpp), and the list of active contacts
// every pass sees (plab_pass_view: contact_end1, contact_end2,
// contact_end2_is_wall, contact_distance).
#pragma once

#include "contacts/contact_set.hpp"

#include <cstdint>
#include <vector>

namespace plab {

// What the range test found in one ball–ball table: the rows in range of
// batch b, listed from b * kContactBatch, and their count; on the
// centre-force path (`listed`, for the packer) their centre distances too.
struct RowsInRange {
    std::vector<std::uint32_t> row, count;
    std::vector<double> distance;
    bool listed = false;
};

// The active contacts of every table, in table and row order (the same list
// for any thread count), for the passes.
class PassContacts {
public:
    std::size_t size() const { return end1_.size(); }
    const std::int32_t* end1() const { return end1_.data(); }
    const std::int32_t* end2() const { return end2_.data(); }
    const std::uint8_t* end2_is_wall() const { return wall_.data(); }
    // the centre distances, when the range test listed the contacts at the
    // current positions (null otherwise)
    const double* distance(bool current) const {
        return current && distance_.size() == end1_.size() ? distance_.data() : nullptr;
    }
    // The active rows of the tables, after the geometry set their flags.
    void list_active(const std::vector<ContactSet*>& tables);
    // The range test's lists: start, the rows of a ball–ball table in range
    // (each batch's at its place), the active rows of a wall table, finish.
    void start() { listed_ = 0; }
    void append_in_range(const ContactSet& s, const RowsInRange& r, std::size_t parallel_min);
    void append_active_wall_rows(const ContactSet& s);
    void finish() { resize(listed_); }  // down to the rows listed (a shrink: nothing cleared)

    // for checkpoints
    std::vector<std::int32_t>& end1_column() { return end1_; }
    std::vector<std::int32_t>& end2_column() { return end2_; }
    std::vector<std::uint8_t>& wall_column() { return wall_; }
    const std::vector<std::int32_t>& end1_column() const { return end1_; }
    const std::vector<std::int32_t>& end2_column() const { return end2_; }
    const std::vector<std::uint8_t>& wall_column() const { return wall_; }

private:
    std::vector<std::int32_t> end1_, end2_;
    std::vector<std::uint8_t> wall_;
    std::vector<double> distance_;
    std::vector<std::size_t> batch_at_;  // each batch's first place in the list
    std::size_t listed_ = 0;
    // The columns at n rows. The range test refills them every cycle without
    // emptying them first (resizing an emptied vector would clear the whole
    // list, ~2 MB on the dam break, only to overwrite it): it grows them as
    // it lists and shrinks them at the end.
    void resize(std::size_t n);
};

} // namespace plab
