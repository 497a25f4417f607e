#include "forces/packed_tables.hpp"

namespace plab {

void PackedTables::forget(const std::vector<ContactSet*>& tables) {
    tables_.resize(tables.size());
    for (std::size_t si = 0; si < tables.size(); ++si) {
        tables_[si].held.assign((tables[si]->size() + kContactBatch - 1) / kContactBatch, HeldOutputs{});
        tables_[si].live.assign(tables[si]->size(), 1);
    }
}

void PackedTables::clear_limits(std::size_t tables) {
    tables_.resize(tables);
    for (PackedTable& t : tables_) t.limits.clear();
}

} // namespace plab
