// Balls that enter and leave a run (issue 36): inlets that insert balls at a
// rate, as LIGGGHTS's fix insert/stream and PFC's ball generation during a
// cycle do, and outlets that delete the balls that reach a region (a
// hopper's discharge, LIGGGHTS's delete region). The scene's lists:
//   "inlets":  [{"name", "box": {"min", "max"}, "radius" (value, [min, max]
//               or a size distribution), "density", "group", "velocity",
//               "rate": {"count_per_second" | "mass_per_second"}, "total",
//               "every", "seed", "max_attempts"}]
//   "outlets": [{"name", "box": {"min", "max"}, "every"}]
// Every `every` steps, before the step, an inlet adds the balls its rate
// has made due since the run began (up to `total`), each at a random place
// in its box that overlaps no ball (of the world or just added); an outlet
// removes the free balls whose centre is in its box. Both count what they
// moved (history quantities inlet.<count|mass> and outlet.<count|mass>,
// with "inlet" / "outlet": its name) and keep it, and the inlet's random
// generator, in a checkpoint: a restarted run inserts the same balls.
#pragma once

#include "ball_fill.hpp"
#include "json_reader.hpp"
#include "size_distribution.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace plab {

class CheckpointReader;
class CheckpointWriter;

struct Inlet {
    std::string name;
    Box box;
    Material material;
    std::optional<SizeDistribution> sizes;
    Vec velocity = Vec::Zero();
    double rate = 0;       // balls/s, or kg/s where by_mass
    bool by_mass = false;
    long total = 0;        // balls, at most
    long every = 1;        // steps
    long max_attempts = 0; // positions tried per ball
    // what it has done (checkpointed)
    long inserted = 0;
    double mass = 0;       // kg inserted
    Rng rng{1};
};

struct Outlet {
    std::string name;
    Box box;
    long every = 1;
    long removed = 0;  // checkpointed
    double mass = 0;
};

class BodyFlows {
public:
    void read_inlets(const Node& n, World& w, const std::string& scene_dir);
    void read_outlets(const Node& n, World& w);
    bool empty() const { return inlets_.empty() && outlets_.empty(); }
    bool has_inlets() const { return !inlets_.empty(); }
    // The removals and insertions due before the world's next step.
    void before_step(World& w);
    // A history column "inlet.<count|mass>" or "outlet.<count|mass>" (with
    // "inlet" / "outlet"), or none for another quantity.
    std::function<double(const World&)> quantity(const Node& column) const;
    void save(CheckpointWriter& out) const;
    void load(CheckpointReader& in);

private:
    std::vector<Inlet> inlets_;
    std::vector<Outlet> outlets_;
};

} // namespace plab
