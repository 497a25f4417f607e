// Per-body lists of the contact rows touching each body, in (table, row)
// order. The sums taken body by body (field accumulations, stiffness) walk
// them, so they do not depend on the thread count.
#pragma once

#include "contacts/contact_set.hpp"

#include <cstdint>
#include <vector>

namespace plab {

// Row `row` of contact table `set` (the world's set order); the body is the
// row's end 2 when end2() (the top bit of the stored row).
struct BodyContact {
    std::uint32_t set = 0;
    std::uint32_t stored_row = 0;
    static constexpr std::uint32_t kEnd2Bit = 1u << 31;
    std::uint32_t row() const { return stored_row & ~kEnd2Bit; }
    bool end2() const { return (stored_row & kEnd2Bit) != 0; }
};

class BodyContacts {
public:
    struct Range {
        const BodyContact *first, *last;
        const BodyContact* begin() const { return first; }
        const BodyContact* end() const { return last; }
    };
    // The lists for `bodies` bodies over the tables whose `listed[si]` is set.
    void build(const std::vector<ContactSet*>& sets, const std::vector<std::uint8_t>& listed, std::size_t bodies);
    bool built_for(std::size_t bodies) const { return start_.size() == bodies + 1; }
    Range of(std::size_t body) const { return {entries_.data() + start_[body], entries_.data() + start_[body + 1]}; }
    void release();  // freed (a lean rebuild); build() makes them anew

private:
    std::vector<std::uint32_t> start_;  // body i's entries: [start_[i], start_[i + 1])
    std::vector<BodyContact> entries_;
};

} // namespace plab
