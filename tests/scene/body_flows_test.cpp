// Inlets and outlets (scripting/body_flows.hpp): balls poured in at a rate
// without overlaps, removed at an outlet and counted, the same bits on a
// restart from a checkpoint taken mid-pour and on two threads.
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <omp.h>

#include <filesystem>

using namespace plab;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// A 2D bin 0.1 m wide fed from an inlet near its top at 4000 balls/s (300
// in all, radii 1-1.5 mm), draining through an outlet box below its open
// floor gap: a floor in two segments leaves a 12 mm orifice at the centre.
json pour() {
    return {{"dimension", 2},
            {"plugins", {"linear"}},
            {"gravity", {0, -9.81}},
            {"timestep", {{"fixed", 2e-5}}},
            {"walls", {{{"type", "segment"}, {"name", "left_floor"}, {"from", {0.0, 0.0}}, {"to", {0.044, 0.0}}},
                       {{"type", "segment"}, {"name", "right_floor"}, {"from", {0.056, 0.0}}, {"to", {0.1, 0.0}}},
                       {{"type", "segment"}, {"name", "left"}, {"from", {0.0, 0.0}}, {"to", {0.0, 0.3}}},
                       {{"type", "segment"}, {"name", "right"}, {"from", {0.1, 0.0}}, {"to", {0.1, 0.3}}}}},
            {"inlets", {{{"name", "feed"}, {"box", {{"min", {0.01, 0.2}}, {"max", {0.09, 0.25}}}}, {"radius", {0.001, 0.0015}},
                         {"density", 2500}, {"group", "grains"}, {"velocity", {0, -0.5}},
                         {"rate", {{"count_per_second", 4000}}}, {"total", 300}, {"every", 250}, {"seed", 7}}}},
            {"outlets", {{{"name", "drain"}, {"box", {{"min", {-1, -1}}, {"max", {2, -0.02}}}}, {"every", 100}}}},
            {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"},
                                 {"properties", {{"kn", 1e6}, {"ks", 5e5}, {"fric", 0.3}, {"dp_nratio", 0.3}}}}}},
            {"histories", {{"every", 500},
                           {"record", {{{"name", "in"}, {"quantity", "inlet.count"}, {"inlet", "feed"}},
                                       {{"name", "in_mass"}, {"quantity", "inlet.mass"}, {"inlet", "feed"}},
                                       {{"name", "out"}, {"quantity", "outlet.count"}, {"outlet", "drain"}},
                                       {{"name", "out_mass"}, {"quantity", "outlet.mass"}, {"outlet", "drain"}}}}}}};
}

double balls_mass(const World& w) {
    double m = 0;
    for (double x : w.bodies.mass) m += x;
    return m;
}

} // namespace

TEST_CASE("an inlet pours at its rate up to its total, an outlet removes and counts, and mass is accounted for",
          "[scene][flows]") {
    Simulation sim(pour());
    sim.set_quiet(true);
    World& w = sim.world();
    sim.cycle(2500);
    // its events come every 250 steps, before the step: the last before this
    // row's, at step 2250 (t = 0.045 s, to rounding), made floor(4000 t) due
    const double in = sim.history("in").back();
    CHECK(in >= 179);
    CHECK(in <= 180);
    CHECK(double(w.bodies.size()) == in - sim.history("out").back());
    sim.cycle(30000);  // 0.65 s: all 300 poured, most drained
    const double n_in = sim.history("in").back(), n_out = sim.history("out").back();
    CHECK(n_in == 300);
    CHECK(n_out > 100);
    CHECK(double(w.bodies.size()) == n_in - n_out);
    CHECK(balls_mass(w) == Approx(sim.history("in_mass").back() - sim.history("out_mass").back()).epsilon(1e-12));
}

TEST_CASE("a pour restarted from a checkpoint taken mid-pour, and one on two threads, give the same bits",
          "[scene][flows][restart]") {
    const fs::path dir = fs::temp_directory_path() / "plab_flows_restart";
    fs::create_directories(dir);
    const fs::path file = dir / "mid_pour.plab";
    Simulation whole(pour());
    whole.set_quiet(true);
    whole.cycle(6100);  // (mid-event cycle: 24 events done, more due)
    whole.save_checkpoint(file.string());
    whole.cycle(9000);
    auto restarted = Simulation::restart(file.string());
    restarted->set_quiet(true);
    restarted->cycle(9000);
    CHECK(restarted->world().bodies.size() == whole.world().bodies.size());
    CHECK(state_hash(restarted->world()) == state_hash(whole.world()));
    CHECK(restarted->history("in").back() == whole.history("in").back());
    CHECK(restarted->history("out").back() == whole.history("out").back());
    CHECK(whole.history("out").back() > 0);  // (balls left before the end: removal was exercised)

    const int threads = omp_get_max_threads();
    omp_set_num_threads(2);
    Simulation two(pour());
    two.set_quiet(true);
    two.world().parallel_min = 1;  // (every loop split, however short)
    two.cycle(15100);
    omp_set_num_threads(threads);
    CHECK(state_hash(two.world()) == state_hash(whole.world()));
}
