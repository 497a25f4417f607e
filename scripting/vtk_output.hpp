// The VTK snapshot series: VTK XML PolyData (.vtp) files of the balls, the
// contacts, the walls and the rigid bodies' surfaces, with a .pvd collection for ParaView. Binary
// appended data, zlib-compressed by default (or raw), ASCII on request.
#pragma once

#include "json_reader.hpp"

#include <plab_host/world.hpp>

#include <string>

namespace plab {

struct VtkOptions {
    double interval = 0;  // simulated seconds between frames; 0: no series
    enum class Encoding { ascii, binary, zlib } encoding = Encoding::zlib;
    bool float32 = false;  // real arrays as Float32 (half the size; ~7 digits)
    // what each frame writes besides the balls
    bool contacts = true;        // touching contacts that carry no bond
    bool bonds = true;           // bonded contacts
    bool pair_contacts = false;  // interactions over a distance (SPH pairs, soft repulsion)
    bool walls = true;
    bool bodies = true;    // rigid bodies' surfaces (a scene with clumps)
    bool pebbles = true;   // the clumps' pebbles among the balls
    bool any_contacts() const { return contacts || bonds || pair_contacts; }
};

// scene.output.vtk: {"interval", "encoding", "precision", "contacts",
// "bonds", "pair_contacts", "walls", "bodies", "pebbles"}.
VtkOptions read_vtk_options(const Node& n);

std::string balls_vtp(const World& w, const VtkOptions& opt);
std::string contacts_vtp(const World& w, const VtkOptions& opt);
std::string walls_vtp(const World& w, const VtkOptions& opt);
std::string bodies_vtp(const World& w, const VtkOptions& opt);

} // namespace plab
