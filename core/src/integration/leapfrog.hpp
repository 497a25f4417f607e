// The law of motion: the kick–drift–kick leapfrog (thesis eqs. 32–36) over
// blocks of bodies, with the energy sums it takes while the velocities and
// positions are at hand. It owns 1/m and 1/I of every body and the per-block
// sums; the bodies, gravity, the domain and the positions at the last
// neighbour build are its inputs.
#pragma once

#include <plab_host/bodies.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace plab {

// What the drift reads besides the bodies.
struct DriftInputs {
    Vec gravity = Vec::Zero();
    Vec lo = Vec::Constant(-kInf), hi = Vec::Constant(kInf);  // the detector's domain
    // positions at the last neighbour build (another size: none yet)
    const std::vector<Vec>* position_at_build = nullptr;
    // the drift velocity correction fields (abi.h, PLAB_PHASE_PRE_DRIFT), or null
    std::array<const double*, 3> correction{};
    bool corrected() const { return correction[0] != nullptr; }
};

// What the drift found, summed over the blocks in order.
struct DriftResult {
    double body_work = 0;  // work of gravity over the drift, J
    double max_drift2 = -1;  // largest squared displacement since the build (-1: no reference)
    bool left_domain = false;  // a position left the domain or is not finite
};

class Leapfrog {
public:
    // 1/m and 1/I of every body (after a change of mass or inertia, again)
    void cache_inverse_masses(const Bodies& bodies);
    // Half a kick, v += h F/m, w += h M/I, of every body; the closing kick
    // of a step (`closing`) also takes the blocks' energy sums.
    void kick(Bodies& bodies, double half_dt, bool closing, std::size_t parallel_min);
    // Half a kick of block b alone (the reduction takes the closing kick
    // block by block, right after the block's force sums).
    void kick_block(Bodies& bodies, std::size_t block, double half_dt, bool closing);
    // x += (v + correction) dt of every body.
    DriftResult drift(Bodies& bodies, const DriftInputs& in, double dt, std::size_t parallel_min);
    // Half a kick and the drift, block by block (no pass between them).
    DriftResult kick_and_drift(Bodies& bodies, const DriftInputs& in, double dt, std::size_t parallel_min);
    // The closing kick's energy sums without a kick (forces at a state).
    void body_energies(Bodies& bodies, double dt);  // (reads the bodies)
    // The blocks' kinetic energy at the synchronised velocities and the work
    // of applied loads and fixed-DOF reactions over the last step, in block order.
    double kinetic() const;
    double boundary_work() const;
    // Sizes the per-block sums for the bodies (call before kick_block()).
    void prepare_blocks(const Bodies& bodies);

private:
    std::vector<double> inv_mass_, inv_inertia_;
    std::vector<double> block_kinetic_, block_boundary_;
    std::vector<double> block_body_work_, block_max_drift2_;
    std::vector<std::uint8_t> block_out_;
    void drift_block(Bodies& bodies, std::size_t block, double dt, const DriftInputs& in);
    DriftResult finish_drift(const Bodies& bodies, const DriftInputs& in) const;
};

} // namespace plab
