// Buffers that the neighbour rebuild fills anew: how they grow and how they
// are freed. A big world's peak memory is its lists and columns, so a
// buffer holds about what it needs, never twice as much (std::vector's own
// growth doubles), and a freed one really goes.
#pragma once

#include <vector>

namespace plab {

// Frees v's block (`v = {}` would only clear it: that assigns an empty
// initializer list and keeps the capacity).
template <class V>
void release(V& v) {
    V().swap(v);
}

// v emptied, with room for n elements. A list that outgrows its block gets
// room for an eighth more: the candidate count of a flow creeps up and down
// from one rebuild to the next, and a reallocation at every new high would
// fault the pages of every column in again. A buffer with no block yet
// (new, or freed by a lean rebuild, which allocates anew every time) gets
// just n.
template <class T>
void clear_for(std::vector<T>& v, std::size_t n) {
    if (n <= v.capacity()) {
        v.clear();
        return;
    }
    const std::size_t room = v.capacity() == 0 ? n : n + n / 8;
    release(v);  // the old block goes first: no two copies at the peak
    v.reserve(room);
}

// v holds n copies of x, in a block sized as clear_for() does.
template <class T>
void fill(std::vector<T>& v, std::size_t n, T x) {
    clear_for(v, n);
    v.assign(n, x);
}

} // namespace plab
