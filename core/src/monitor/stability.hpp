// The instability detector's limits and its diagnostic. A run that goes
// unstable must stop with a message naming the quantity, the body or
// contact, the step and a likely cause — never write garbage. The checks
// are generic: the core knows states, energies, contact gaps and radii;
// a pass that knows more (SPH density) reports through the pass view's
// diagnostic buffer (abi.h, plab_pass_view::diagnostic).
#pragma once

#include "bodies/bodies.hpp"
#include "bodies/walls.hpp"
#include "common/types.hpp"
#include "contacts/assignment.hpp"
#include "monitor/energies.hpp"

#include <string>

namespace plab {

struct StabilityLimits {
    bool enabled = true;
    // Energy that appears from nowhere: the gain of the energy balance
    // (kinetic + strain - work done + dissipated) since the last change of
    // the scene, as a fraction of the energy turned over (initial kinetic and
    // strain energy, work done, dissipated energy, and 1 % of the potential
    // energy m |g| L the particles hold over their own extent L along
    // gravity: a floor for scenes at rest, where the other terms are ~0).
    // A stable leapfrog keeps it at O(dt²); an unstable one grows it
    // exponentially, so the threshold only sets how early the detector fires.
    double energy_gain = 0.5;  // 1, (0, inf); inf: off
    // Particles leaving the domain: the scene's domain, else the bounding
    // box of the walls grown by `domain_margin` times its largest extent.
    Vec domain_min = Vec::Constant(-kInf), domain_max = Vec::Constant(kInf);
    double domain_margin = 0.5;  // 1, [0, inf)
};

// What stopped a run.
struct Diagnostic {
    std::string quantity;  // e.g. "overlap", "energy gain", "non-finite state", "sph_density"
    std::string subject;   // e.g. "contact 3-4 of model linear (groups grains-grains)"
    std::uint64_t step = 0;
    double time = 0;
    std::string detail;    // value against limit
    std::string cause;     // likely cause and what to do
    std::string message() const {
        return "unstable: " + quantity + " at step " + std::to_string(step) + " (t = " + std::to_string(time) +
               " s): " + subject + ": " + detail + "; likely cause: " + cause;
    }
};

// The energy balance and domain the detector compares with, measured at the
// last change of the scene: a `set velocity` adds kinetic energy that no
// force did work for, and is not an instability.
struct StabilityBaseline {
    double balance = 0, body = 0, boundary = 0, dissipated = 0, stored = 0, potential = 0, max_work = 0;
    Vec lo = Vec::Constant(-kInf), hi = Vec::Constant(kInf);
};

// The generic checks, each a Diagnostic with an empty quantity when it
// passes. The overlap check reads the contact tables (World::check_overlaps).
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
