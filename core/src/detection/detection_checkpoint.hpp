// The detection subsystem's checkpoint section, "detection": the Verlet
// lists' reference (positions at the last build, wall motion since), whether
// the forces are prepared, the per-body stiffness sums of the last force pass
// (the monitor's, read by the next step's stable timestep) and the contact
// list the passes see. io/checkpoint.cpp frames it; world/cycle_checkpoint.cpp
// lists it.
#pragma once

#include <plab_host/checkpoint.hpp>

#include "detection/neighbour_lists.hpp"
#include "detection/range_test.hpp"
#include "monitor/stiffness_sums.hpp"

namespace plab {

struct DetectionState {
    NeighbourLists& neighbours;
    PassContacts& pass_contacts;
    bool& prepared;
};

void save_detection(const DetectionState& d, const StiffnessSums& summed, CheckpointWriter& out);
void load_detection(const DetectionState& d, StiffnessSums& stiffness, std::size_t body_count, CheckpointReader& in);

} // namespace plab
