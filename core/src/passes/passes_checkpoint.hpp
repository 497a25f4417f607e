// The passes' checkpoint section, "passes": each pass's name and properties,
// and the private state of a pass that registers state hooks
// (plab_pass_state_hooks), in the bytes its plug-in writes.
// io/checkpoint.cpp frames it; world/cycle_checkpoint.cpp lists it.
#pragma once

#include <plab_host/checkpoint.hpp>
#include <plab_host/plugins.hpp>

#include "passes/passes.hpp"

#include <vector>

namespace plab {

void save_passes(const std::vector<PassInstance>& passes, const PluginHost& host, CheckpointWriter& out);
void load_passes(std::vector<PassInstance>& passes, const PluginHost& host, CheckpointReader& in);

} // namespace plab
