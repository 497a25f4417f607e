// Contact detection: the candidate pairs of each model instance, within its
// activity range plus a skin, found by a cell list (ball–ball) and a scan of
// the facets (ball–wall), and the Verlet test that says when to find them
// again: after a change of the scene, or once a body may have moved half a
// skin since the last build.
#pragma once

#include <plab_host/bodies.hpp>
#include <plab_host/walls.hpp>

#include "contacts/assignment.hpp"
#include "contacts/history_carry.hpp"
#include "contacts/model_instance.hpp"

#include <cstdint>
#include <vector>

namespace plab {

// Throws an InputError naming domain.min/max when a periodic axis of the
// cell is narrower than 2 x cut (the largest candidate cut-off, centre to centre).
void check_periodic_cell(const PeriodicCell& cell, int dim, double cut);

class NeighbourLists {
public:
    double skin = -1;  // m; < 0: a quarter of the mean radius
    std::uint64_t rebuilds = 0;

    double effective_skin(const Bodies& bodies) const;
    // Whether the lists must be found again.
    bool stale(const Bodies& bodies) const;
    void invalidate() { invalidated_ = true; }
    // The largest squared displacement since the build (-1: unknown), as
    // the drift found it, and the walls' motion of a step.
    void bodies_moved(double max_drift2) { max_drift2_ = max_drift2; }
    void walls_moved(double distance) { wall_motion_ += distance; }
    // The candidates of instance m, ball–ball in the order of one walk over
    // the bodies (for any thread count), ball–wall body by body.
    void find_pairs(const Bodies& bodies, const Walls& walls, const AssignmentTable& table,
                    const Instances& instances, std::size_t parallel_min, std::uint64_t step, bool lean);
    PairList& ball_pairs(std::size_t m) { return ball_pairs_[m]; }
    PairList& wall_pairs(std::size_t m) { return wall_pairs_[m]; }
    // The lists are built at these positions.
    void built(const Bodies& bodies);
    const std::vector<Vec>& position_at_build() const { return position_at_build_; }

    // What a checkpoint keeps, so that a restart rebuilds when the run would have.
    struct Saved {
        bool invalidated = true;
        std::vector<Vec> position_at_build;
        double wall_motion = 0;
    };
    bool invalidated() const { return invalidated_; }
    double wall_motion() const { return wall_motion_; }
    // A sheared cell's offset at the build (the periodic cell's checkpoint
    // section keeps it, after the detection section).
    double offset_at_build() const { return offset_at_build_; }
    void restore_offset_at_build(double offset) { offset_at_build_ = offset; }
    void restore(Saved s);

private:
    bool invalidated_ = true;
    std::vector<Vec> position_at_build_;
    double wall_motion_ = 0;
    double offset_at_build_ = 0;
    double max_drift2_ = -1;
    double slid_since_build(const PeriodicCell& cell) const;
    std::vector<PairList> ball_pairs_, wall_pairs_;  // per instance; cleared, not freed, between builds
    std::vector<std::vector<PairList>> block_pairs_;  // [block of bodies][instance]
    void find_ball_pairs(const Bodies& bodies, const AssignmentTable& table, const Instances& instances,
                         std::size_t parallel_min, std::uint64_t step);
    void find_ball_pairs_periodic(const Bodies& bodies, const AssignmentTable& table, const Instances& instances,
                                  std::size_t parallel_min);
    void find_wall_pairs(const Bodies& bodies, const Walls& walls, const AssignmentTable& table,
                         const Instances& instances);
};

} // namespace plab
