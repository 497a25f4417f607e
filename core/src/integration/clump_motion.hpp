// The law of motion of clumps (plab_host/clumps.hpp): the same kick–drift–
// kick leapfrog as the balls' (leapfrog.hpp), with the rotation of a rigid
// body of any shape (rigid_rotation.hpp: the angular momentum kicked by the
// torque, the free rotation between the kicks). The pebbles are balls the
// leapfrog leaves alone (dof_clumped); this places them after each drift and
// gives them the clump's velocities after each kick.
#pragma once

#include <plab_host/clumps.hpp>

#include "integration/leapfrog.hpp"

#include <vector>

namespace plab {

// What a clump step adds to the world's energy sums.
struct ClumpEnergies {
    double kinetic = 0;        // at the synchronised velocities, J
    double boundary = 0;       // work of the fixed DOFs' reactions over the step, J
    double local_damping = 0;  // work taken by local damping over the step, J
};

class ClumpMotion {
public:
    // Before the balls' drift: the pebbles' velocities zeroed, so the drift
    // neither moves them nor counts the work of their weight.
    void hold_pebbles(const Clumps& clumps, Bodies& bodies) const;
    // Half a kick of each clump with the sums of the last force pass, the
    // drift and free rotation over dt, the pebbles placed; the result is
    // `balls` (the balls' drift) with the clumps' gravity work, their
    // pebbles' displacement since the last build and the domain check.
    DriftResult kick_and_drift(Clumps& clumps, Bodies& bodies, const DriftInputs& in, double dt, DriftResult balls,
                               std::size_t parallel_min);
    // After the force pass: the pebbles' forces and moments summed onto each
    // clump in pebble order (with the clump's weight), local damping, the
    // closing half kick (half_dt 0: none), the pebbles' velocities, and the
    // energy sums over a step of length dt.
    ClumpEnergies finish(Clumps& clumps, Bodies& bodies, const Vec& gravity, double half_dt, double dt,
                         std::size_t parallel_min);

private:
    // per clump, added in clump order after the threaded loops
    std::vector<DriftResult> drift_;
    std::vector<ClumpEnergies> energies_;
};

} // namespace plab
