// A contact row's key: the ball id of end 1 and the ball or facet id of
// end 2. Derived from the ends, not stored (16 B per row): balls and facets
// are only ever appended, so an index names the same body at every rebuild.
#pragma once

#include <plab_host/bodies.hpp>
#include <plab_host/contacts.hpp>
#include <plab_host/walls.hpp>

#include "contacts/contact_set.hpp"

#include <utility>

namespace plab {

inline ContactKey pair_key(const Bodies& bodies, const Walls& walls, bool with_wall, std::int32_t end1,
                           std::int32_t end2) {
    return {bodies.id[std::size_t(end1)], with_wall ? walls.facets[std::size_t(end2)].id : bodies.id[std::size_t(end2)]};
}

inline ContactKey row_key(const Bodies& bodies, const Walls& walls, const ContactSet& s, std::size_t k) {
    return pair_key(bodies, walls, s.with_wall, s.end1[k], s.end2[k]);
}

} // namespace plab
