// The contacts subsystem's checkpoint sections: "assignment" (the groups
// and PFC's assignment table) and "contacts" (each model instance's ball and
// wall tables: ends, keys, history by slot name, columns, field sums).
// io/checkpoint.cpp frames them; world/cycle_checkpoint.cpp lists them.
#pragma once

#include <plab_host/bodies.hpp>
#include <plab_host/checkpoint.hpp>
#include <plab_host/plugins.hpp>
#include <plab_host/walls.hpp>

#include "contacts/assignment.hpp"
#include "contacts/model_instance.hpp"

#include <functional>

namespace plab {

void save_assignment(const AssignmentTable& a, CheckpointWriter& out);
// The groups must be the scene's; the table may name instances [0, instance_count).
void load_assignment(AssignmentTable& a, std::size_t instance_count, CheckpointReader& in);

void save_contacts(const Instances& instances, const Bodies& bodies, const Walls& walls, CheckpointWriter& out);
// `packs_balls`: whether an instance's ball–ball rows go to it packed (the
// force pipeline's choice, which decides the columns its table keeps).
void load_contacts(Instances& instances, const Bodies& bodies, const Walls& walls, const PluginHost& host,
                   const std::function<bool(const ModelInstance&)>& packs_balls, CheckpointReader& in);

} // namespace plab
