// The last good state: a copy, taken every `snapshot_interval` steps, of
// what a step changes — the motion of the bodies, the walls, the fields, the
// energies, the clock — and of the contact rows whose history is not the
// model's default (the others, and all geometry, come back with the rebuild
// after a restore). A step that goes unstable puts it back (Cycle::step).
// Everything else about a body changes only with the scene, which drops the
// copy: it never spans a change.
#pragma once

#include <plab_host/bodies.hpp>
#include <plab_host/clumps.hpp>
#include <plab_host/energies.hpp>
#include <plab_host/fields.hpp>
#include <plab_host/walls.hpp>

#include "contacts/model_instance.hpp"

#include <cstdint>
#include <vector>

namespace plab {

// The clock of a world (kept and put back with the state).
struct Clock {
    double time = 0, last_dt = 0;
    std::uint64_t step_count = 0;
};

class LastGoodState {
public:
    bool valid() const { return valid_; }
    void drop() { valid_ = false; }
    void keep(const Bodies& bodies, const Clumps& clumps, const Walls& walls, const BodyFields& fields,
              const Energies& energies, const Clock& clock, std::size_t bond_breaks, const Instances& instances);
    // The state back; the contact tables hold the kept rows, to be rebuilt.
    void restore(Bodies& bodies, Clumps& clumps, Walls& walls, BodyFields& fields, Energies& energies, Clock& clock,
                 std::size_t& bond_breaks, Instances& instances) const;

private:
    struct TableRows {
        std::vector<std::int32_t> end1, end2;
        std::vector<double> history;
    };
    bool valid_ = false;
    std::vector<Vec> position_, velocity_, angular_velocity_;
    // the clumps' motion (their sums come back with the re-evaluation)
    std::vector<Vec> clump_position_, clump_velocity_, clump_angular_velocity_, clump_angular_momentum_;
    std::vector<Eigen::Quaterniond> clump_orientation_;
    Walls walls_;
    std::vector<std::vector<double>> fields_;
    Energies energies_;
    Clock clock_;
    std::size_t bond_breaks_ = 0;
    std::vector<TableRows> tables_;  // per instance: balls, walls
};

} // namespace plab
