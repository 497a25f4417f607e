// A checkpoint of the cycle as a list of section hooks, one per part of the
// state, in file order: each subsystem's save and restore of what it owns
// (its *_checkpoint.hpp), and the world's own ("world": clock and energies;
// "bond_breaks"; "rng"). io/checkpoint.cpp runs them within the file's
// framing. A subsystem with new state adds its hook here, at the end, and a
// checkpoint format version (docs/restart.md).
#pragma once

#include <plab_host/checkpoint.hpp>

#include <functional>
#include <vector>

namespace plab {

class Cycle;

struct CheckpointSection {
    std::function<void(CheckpointWriter&)> save;
    std::function<void(CheckpointReader&)> load;
};

std::vector<CheckpointSection> checkpoint_sections(Cycle& cycle);

} // namespace plab
