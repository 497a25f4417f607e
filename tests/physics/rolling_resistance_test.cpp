// rrlinear (physics/dem/rrlinear, <plab/dem/rolling_resistance.hpp>): the
// rolling term is an addition to `linear`, and what it takes from a rolling
// ball it books as dissipated energy. Its analytical decelerations and the
// incline's onset angle are validation/rolling_resistance.
#include "../core/settling_scene.hpp"
#include "../support/case_scene.hpp"

#include <catch2/catch.hpp>

#include <cmath>

namespace {

using plab::json;
using plab::Simulation;
using namespace plab::testing_support;

plab::Energies energies_after(Simulation& sim, std::uint64_t steps) {
    sim.cycle(steps);
    return sim.world().energies;
}

} // namespace

TEST_CASE("rrlinear with rr_fric 0 gives the settling pile of linear bit for bit", "[rrlinear]") {
    for (int dim : {2, 3}) {
        INFO("dim " << dim);
        auto run = [dim](const char* model) {
            json scene = settling_scene(dim, dim == 2 ? 150 : 300);
            scene["plugins"] = {model};
            scene["contact_models"][0]["model"] = model;
            Simulation sim(scene);
            sim.set_quiet(true);
            sim.cycle(1500);
            return std::make_pair(plab::state_hash(sim.world()), sim.world().energies.slip);
        };
        const auto linear = run("linear"), rolling = run("rrlinear");
        CHECK(linear.second > 0);  // the pile's contacts slide
        CHECK(linear == rolling);
    }
}

TEST_CASE("a ball stopped by rolling resistance: its kinetic energy is dissipated and the balance closes", "[rrlinear]") {
    for (const char* file : {"scene_roll_2d.json", "scene_roll_3d.json"}) {
        INFO(file);
        Simulation sim(case_scene("rolling_resistance", {}, file));
        sim.set_quiet(true);
        const plab::Energies start = energies_after(sim, 1);
        const double t_stop = sim.scene()["variables"]["t_stop"].get<double>();
        const plab::Energies end = energies_after(sim, std::uint64_t(1.2 * t_stop / sim.world().last_dt));
        CHECK(end.kinetic < 1e-9 * start.kinetic);  // stopped
        // rolling at the limit moment: the plastic rolling rotation dissipates it
        CHECK(end.slip - start.slip == Approx(start.kinetic).epsilon(0.01));
        CHECK(std::fabs(end.balance() - start.balance()) < 1e-6 * start.kinetic);
    }
}
