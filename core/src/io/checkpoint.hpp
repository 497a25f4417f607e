// The kernel's side of a checkpoint (plab_host/checkpoint.hpp has the file
// format, its reader and writer).
#pragma once

#include <plab_host/checkpoint.hpp>

#include "world/cycle.hpp"

namespace plab {

// The Cycle's complete state (a friend of Cycle).
struct WorldCheckpoint {
    static void save(const Cycle& w, CheckpointWriter& out);
    // `w` must be built from the same scene (groups, model instances, passes,
    // fields registered); its state is replaced by the file's.
    static void load(Cycle& w, CheckpointReader& in);

private:
    // one pair per group of sections, in file order
    static void save_scalars(const Cycle& w, CheckpointWriter& out);  // world, assignment
    static void save_fields(const Cycle& w, CheckpointWriter& out);
    static void save_contacts(const Cycle& w, CheckpointWriter& out);
    static void save_detection(const Cycle& w, CheckpointWriter& out);
    static void save_passes(const Cycle& w, CheckpointWriter& out);
    static void save_log(const Cycle& w, CheckpointWriter& out);  // bond_breaks, rng
    static void load_scalars(Cycle& w, CheckpointReader& in);
    static void load_fields(Cycle& w, CheckpointReader& in);
    static void load_contacts(Cycle& w, CheckpointReader& in);
    static void load_detection(Cycle& w, CheckpointReader& in);
    static void load_passes(Cycle& w, CheckpointReader& in);
    static void load_log(Cycle& w, CheckpointReader& in);
};

} // namespace plab
