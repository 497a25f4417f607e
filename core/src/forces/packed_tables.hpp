// What the packed force paths keep per contact table from one force pass
// to the next: which outputs a batch holds uniformly, which rows may hold
// history, and the step limits per batch.
#pragma once

#include "contacts/contact_set.hpp"

#include <cstdint>
#include <vector>

namespace plab {

// For the outputs moment1, moment2, k_t, k_r, dt_limit of one batch: the
// value every row of the batch holds in the table's column, when they all
// hold the same (zero moments, a constant stiffness). The packed path then
// skips writing an unchanged output back (unpack_rows).
struct HeldOutputs { double value[5]; std::uint8_t uniform[5]; };

// The least step limit (abi.h, dt_limit) of a batch of a centre-force
// sweep and the first row that has it, which is all stable_timestep() takes
// from them. A per-pair limit (SPH's CFL) is seldom uniform, and writing it
// row by row into a column as long as the candidate list cost a cache miss
// per pair.
struct BatchLimit { double dt; std::uint32_t row; };

struct PackedTable {
    std::vector<HeldOutputs> held;  // per batch
    // per row: the row may hold history other than the defaults (it was
    // active at the last force pass, or came with its history from the last
    // list): only such rows need their history reset when out of range
    std::vector<std::uint8_t> live;
    // per batch; empty: the table's dt_limit column holds its limits
    // (cleared at every force pass and rebuild, so never older than the rows)
    std::vector<BatchLimit> limits;
};

class PackedTables {
public:
    PackedTable& operator[](std::uint32_t table) { return tables_[table]; }
    bool has_limits(std::uint32_t table) const { return table < tables_.size() && !tables_[table].limits.empty(); }
    const std::vector<BatchLimit>& limits(std::uint32_t table) const { return tables_[table].limits; }
    // After a rebuild or a load: nothing is known to be uniform, and any row
    // may hold history.
    void forget(const std::vector<ContactSet*>& tables);
    void clear_limits(std::size_t tables);

private:
    std::vector<PackedTable> tables_;
};

} // namespace plab
