// Cumulative energies (J), PFC's energy bookkeeping. With no damping and no
// friction kinetic + strain - body - boundary stays constant.
#pragma once

namespace plab {

struct Energies {
    double kinetic = 0;       // state: translational + rotational
    double strain = 0;        // state: stored in contact springs
    double body = 0;          // work done by gravity
    double boundary = 0;      // work done by walls, applied loads and fixed velocities
    double slip = 0;          // dissipated by friction
    double dashpot = 0;       // dissipated by contact dashpots
    double local_damping = 0; // dissipated by local and viscous body damping
    double bond_break = 0;    // elastic energy released by breaking bonds
    double balance() const { return kinetic + strain - body - boundary + slip + dashpot + local_damping + bond_break; }
};

} // namespace plab
