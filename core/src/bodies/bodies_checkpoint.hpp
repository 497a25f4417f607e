// The bodies subsystem's checkpoint sections: "bodies" (the SoA state),
// "walls" (walls and their facets) and "fields" (the per-body field
// registry's columns). io/checkpoint.cpp frames them; world/cycle_checkpoint.cpp
// lists them in file order.
#pragma once

#include <plab_host/bodies.hpp>
#include <plab_host/checkpoint.hpp>
#include <plab_host/fields.hpp>
#include <plab_host/walls.hpp>

namespace plab {

void save_bodies(const Bodies& b, CheckpointWriter& out);
void load_bodies(Bodies& b, int group_count, CheckpointReader& in);
void save_walls(const Walls& w, CheckpointWriter& out);
void load_walls(Walls& w, int group_count, CheckpointReader& in);
void save_fields(const BodyFields& f, CheckpointWriter& out);
// A field the file lacks (registered since it was written) starts at its default.
void load_fields(BodyFields& f, std::size_t body_count, CheckpointReader& in);

} // namespace plab
