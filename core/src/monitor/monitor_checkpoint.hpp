// The monitor's checkpoint section, "stability": the instability detector's
// baseline, the energy balance at the last change of the scene (without it a
// restart would see a jump, issue 7). Files of format 1 lack it: the baseline
// is then measured at the restored state. io/checkpoint.cpp frames it;
// world/cycle_checkpoint.cpp lists it.
#pragma once

#include <plab_host/checkpoint.hpp>

#include "monitor/stability.hpp"

namespace plab {

void save_stability(const StabilityBaseline& b, CheckpointWriter& out);
void load_stability(StabilityBaseline& b, CheckpointReader& in);

} // namespace plab
