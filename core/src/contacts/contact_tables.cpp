#include "contacts/contact_tables.hpp"

namespace plab {

void ContactTables::list(const Instances& instances, std::size_t bodies) {
    sets.clear();
    owner.clear();
    for (auto& inst : instances) {
        sets.push_back(&inst->balls);
        owner.push_back(inst.get());
        sets.push_back(&inst->walls);
        owner.push_back(inst.get());
    }
    // The rows of a packed centre-force table (SPH) are left out: their
    // stiffness is zero (nothing to add to the stiffness sums), and a packed
    // table accumulates no field that a per-body sum would read.
    std::vector<std::uint8_t> listed(sets.size());
    for (std::uint32_t si = 0; si < sets.size(); ++si)
        listed[si] = !(sets[si]->packed && (owner[si]->desc->flags & PLAB_MODEL_FORCE_AT_CENTRES));
    body_contacts.build(sets, listed, bodies);
}

void fill_pair_constants(const Bodies& bodies, ContactSet& set) {
    if (set.packed) return;
    for (std::size_t r = 0; r < set.size(); ++r) {
        const std::int32_t i = set.end1[r], j = set.end2[r];
        const double ri = bodies.radius[i], mi = bodies.mass[i];
        const double rj = set.with_wall ? 0.0 : bodies.radius[j], mj = set.with_wall ? kInf : bodies.mass[j];
        set.radius1[r] = ri;
        set.radius2[r] = rj;
        set.mass1[r] = mi;
        set.mass2[r] = mj;
        set.eff_mass[r] = set.with_wall ? mi : mi * mj / (mi + mj);  // a wall has infinite mass
        set.eff_radius[r] = set.with_wall ? ri : ri * rj / (ri + rj);
    }
}

} // namespace plab
