// Model instances whose every pair is of balls that cannot move (every DOF
// fixed: SPH boundary particles). Their centre forces move nothing, so a
// force pass holds their ball–ball rows at zero instead of computing them.
// Fixity may change between rebuilds (a `set` command, a case's clamp), so
// this is found at every force pass, a byte per ball, when a model has
// centre forces.
#pragma once

#include <plab_host/bodies.hpp>

#include "contacts/assignment.hpp"
#include "contacts/model_instance.hpp"

#include <cstdint>
#include <vector>

namespace plab {

class StillInstances {
public:
    void find(const Bodies& bodies, const AssignmentTable& table, const Instances& instances);
    // Whether table si (instance m's balls at 2m, walls at 2m + 1) is the
    // ball–ball table of a still centre-force instance. The model is not
    // asked for its forces, as Yade makes no interaction between two bodies
    // that are not dynamic; the rows stay in the list and in range for the
    // passes (density summation), with zero force and no step limit, and
    // add nothing to their balls.
    bool centre_table_still(std::uint32_t si, const ContactSet& table, const Instances& instances) const;

private:
    std::vector<std::uint8_t> instance_, group_;
};

// A still table's rows: zero force, no step limit (once, until it changes).
void hold_still(ContactSet& table);

} // namespace plab
