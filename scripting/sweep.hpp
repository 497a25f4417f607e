// `plab sweep`: a scene over a grid of --set overrides, cost against accuracy.
#pragma once

#include <string>
#include <vector>

namespace plab {

// plab sweep SCENE --vary PATH=v1,v2 [--vary ...] [--set PATH=V]... [--jobs N] [--out DIR]
int cmd_sweep(const std::vector<std::string>& args, const std::string& self_exe);

} // namespace plab
