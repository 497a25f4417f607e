// What the host sets about the instability detector, and what it reports.
// A run that goes unstable must stop with a message naming the quantity, the
// body or contact, the step and a likely cause — never write garbage
// (docs/stability.md).
#pragma once

#include <plab_host/types.hpp>

#include <cstdint>
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

} // namespace plab
