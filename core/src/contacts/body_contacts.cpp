#include "contacts/body_contacts.hpp"

#include "common/buffers.hpp"

#include <numeric>

namespace plab {

void BodyContacts::build(const std::vector<ContactSet*>& sets, const std::vector<std::uint8_t>& listed,
                         std::size_t n) {
    start_.assign(n + 1, 0);
    for (std::uint32_t si = 0; si < sets.size(); ++si) {
        const ContactSet* s = sets[si];
        if (!listed[si]) continue;
        for (std::size_t k = 0; k < s->size(); ++k) {
            ++start_[s->end1[k] + 1];
            if (!s->with_wall) ++start_[s->end2[k] + 1];
        }
    }
    std::partial_sum(start_.begin(), start_.end(), start_.begin());
    fill(entries_, std::size_t(start_[n]), BodyContact{});
    std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);  // each body's next free entry
    for (std::uint32_t si = 0; si < sets.size(); ++si) {
        const ContactSet* s = sets[si];
        if (!listed[si]) continue;
        for (std::uint32_t k = 0; k < s->size(); ++k) {
            entries_[next[s->end1[k]]++] = {si, k};
            if (!s->with_wall) entries_[next[s->end2[k]]++] = {si, k | BodyContact::kEnd2Bit};
        }
    }
}

void BodyContacts::release() { plab::release(entries_); }

} // namespace plab
