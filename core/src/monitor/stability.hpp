// The instability detector: the generic checks behind the limits and the
// diagnostic of <plab_host/stability.hpp>. The core knows states, energies,
// contact gaps and radii; a pass that knows more (SPH density) reports
// through the pass view's diagnostic buffer (abi.h, plab_pass_view::diagnostic).
#pragma once

#include <plab_host/bodies.hpp>
#include <plab_host/energies.hpp>
#include <plab_host/stability.hpp>
#include <plab_host/types.hpp>
#include <plab_host/walls.hpp>

#include "contacts/assignment.hpp"

#include <string>

namespace plab {

// The energy balance and domain the detector compares with, measured at the
// last change of the scene: a `set velocity` adds kinetic energy that no
// force did work for, and is not an instability.
struct StabilityBaseline {
    double balance = 0, body = 0, boundary = 0, dissipated = 0, stored = 0, potential = 0, max_work = 0;
    Vec lo = Vec::Constant(-kInf), hi = Vec::Constant(kInf);
};

// The generic checks, each a Diagnostic with an empty quantity when it
// passes. The overlap check reads the contact tables (Monitor::check_overlaps).
class InstabilityDetector {
public:
    StabilityLimits limits;
    StabilityBaseline baseline;
    void measure_baseline(const Energies& energies, const Bodies& bodies, const Walls& walls, const Vec& gravity);
    // The first ball outside the domain or not finite (the drift flags that one is).
    Diagnostic domain_check(const Bodies& bodies, const AssignmentTable& groups) const;
    // Energy from nowhere (it keeps the largest work done since the baseline).
    Diagnostic energy_check(const Energies& energies, const Bodies& bodies, const AssignmentTable& groups);
};

} // namespace plab
