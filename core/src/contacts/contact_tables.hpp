// Every contact table of a world in one list — instance m's ball–ball table
// at 2m, its ball–wall table at 2m + 1 — with the model instance that owns
// each, the buffers that carry their history across a rebuild, and each
// body's rows (for the sums taken body by body, in a fixed order).
#pragma once

#include <plab_host/bodies.hpp>

#include "contacts/body_contacts.hpp"
#include "contacts/history_carry.hpp"
#include "contacts/model_instance.hpp"

#include <vector>

namespace plab {

struct ContactTables {
    std::vector<ContactSet*> sets;
    std::vector<const ModelInstance*> owner;
    std::vector<TableBuffers> buffers;
    BodyContacts body_contacts;

    // The list of the instances' tables, and each body's rows.
    void list(const Instances& instances, std::size_t bodies);
};

// The radii and masses of a table's ends, and their effective mass and
// radius, for a model that reads the full columns (a packed table's go to
// its model packed, from the bodies).
void fill_pair_constants(const Bodies& bodies, ContactSet& set);

} // namespace plab
