// `bodies[i]` of type "clump" (or "rigid"): one rigid body made of pebbles,
// its mass and inertia from its true shape (plab_host/mass_properties.hpp),
// and `clump_fill`: clumps of one template dropped at random into a box.
#pragma once

#include "json_reader.hpp"

#include <plab_host/world.hpp>

#include <string>

namespace plab {

// Adds the clump of `n` (a bodies[] entry); a mesh shape's relative file is
// found in `scene_dir`.
void generate_clump(const Node& n, World& w, const std::string& scene_dir);
// Adds `count` clumps of the template `n.clump` at random centres and
// orientations in `n.box`, no two pebbles of different clumps overlapping.
void generate_clump_fill(const Node& n, World& w, const std::string& scene_dir);
// A clump's "fix" (or a `set`'s "fix"/"free" of clumps): translations per
// component, the rotation whole or not at all; in 2D only x, y and rz count.
std::uint8_t read_clump_fixity(const Node& fix, int dim);

} // namespace plab
