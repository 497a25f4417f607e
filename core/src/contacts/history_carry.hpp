// A contact table's rows replaced by a new candidate list, the history of
// every pair that stays carried over by key (contact_keys.hpp): the merge of
// two lists sorted by the same keys.
#pragma once

#include "contacts/contact_keys.hpp"
#include "contacts/model_instance.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace plab {

using PairList = std::vector<std::array<std::int32_t, 2>>;

// The buffers a table's next list is built in (the old list's, after the
// swap). One set per table, never shared: a shared set would pass the big
// list's buffers on to every small or empty table in turn, and each would
// keep a big one.
struct TableBuffers {
    std::vector<std::int32_t> e1, e2;
    std::vector<double> history;
    std::vector<double> normal;          // ball–wall rows: the side each survivor is on
    std::vector<std::uint8_t> interior;  // (facet_distance, forces/force_pass.cpp)
};

struct CarryContext {
    const Bodies& bodies;
    const Walls& walls;
    std::size_t parallel_min;
    bool lean;              // a lean rebuild (World::lean_rebuild_rows): nothing kept twice
    std::size_t lean_rows;  // a list longer than this frees its buffers all the same
    // the old rows and the pairs go before the columns come
    bool frees_buffers(std::size_t rows) const { return lean || rows > lean_rows; }
};

// `pairs` sorted in place by their keys (end 1, then end 2), each pair once.
void sort_by_keys(const CarryContext& c, const ContactSet& set, PairList& pairs);
// The table's ends and history become `pairs`' (ordered so that end 1 has
// the lower id, sorted, each once), a survivor keeping its history and a new
// pair taking the model's defaults. A ball–wall survivor's side (normal and
// interior flag) waits in `t` for take_sides(), after the columns are laid
// out; returns whether there are sides to take.
bool carry_history(const CarryContext& c, const ModelInstance& inst, ContactSet& set, PairList& pairs,
                   TableBuffers& t);
void take_sides(const CarryContext& c, ContactSet& set, TableBuffers& t);
// A bonded pair stays a candidate however far its ends have moved apart.
void keep_bonded_pairs(const ModelInstance& inst, const ContactSet& set, PairList& pairs);

} // namespace plab
