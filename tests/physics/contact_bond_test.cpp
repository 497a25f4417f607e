// linear_cbond (physics/dem/linear_cbond): PFC's linear contact bond. A
// bonded pair pulled apart or sheared at a prescribed speed against its
// springs and strengths, and an unbonded contact that is `linear`.
#include "../core/settling_scene.hpp"
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

using namespace plab;

namespace {

constexpr double kR = 0.001, kn = 1e6, ks = 5e5;

// Two touching discs (R = 1 mm), both fixed, bonded; ball 1 is driven at
// `velocity`. Friction 0.5, so that a sheared bonded contact is held far
// beyond the Coulomb limit of an unbonded one.
std::unique_ptr<Simulation> cbonded_pair(const json& velocity, double tenf, double shearf) {
    json scene = {{"dimension", 2},
                  {"plugins", {"linear_cbond"}},
                  {"bodies", {{{"type", "ball"}, {"position", {0, 0}}, {"radius", kR}, {"density", 2500}, {"fix", {"all"}}},
                              {{"type", "ball"}, {"position", {2 * kR, 0}}, {"radius", kR}, {"density", 2500},
                               {"fix", {"all"}}, {"velocity", velocity}}}},
                  {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear_cbond"},
                                       {"properties", {{"kn", kn}, {"ks", ks}, {"fric", 0.5}, {"cb_tenf", tenf},
                                                       {"cb_shearf", shearf}}}}}},
                  {"timestep", {{"fixed", 1e-5}}}};
    auto sim = std::make_unique<Simulation>(scene);
    sim->set_quiet(true);
    REQUIRE(sim->world().bond(0, 0, 1e-9) == 1);
    return sim;
}

} // namespace

TEST_CASE("a contact bond pulled apart carries kn times its opening and breaks in tension at cb_tenf", "[cbond]") {
    const double v = 0.001, tenf = 0.5;  // breaks at an opening of 0.5 um, in 5000 steps of 1e-4 um
    auto sim = cbonded_pair({v, 0.0}, tenf, 1e300);
    World& w = sim->world();
    while (w.bond_breaks.empty() && w.step_count < 100000) {
        w.step();
        if (!w.bond_breaks.empty()) break;
        const double opening = w.bodies.position[1].x() - 2 * kR;
        CHECK(w.bodies.force[1].x() == Approx(-kn * opening).epsilon(1e-9));  // pulled back: tension
    }
    REQUIRE(w.bond_breaks.size() == 1);
    CHECK(w.bond_breaks[0].mode == PLAB_BREAK_TENSION);
    CHECK(w.bond_breaks[0].time == Approx(tenf / (kn * v)).margin(1.5 * w.fixed_dt));
    sim->cycle(10);
    CHECK(w.bodies.force[1].norm() == 0.0);  // apart and unbonded: the linear law has no tension
    // the spring's energy at the breaking force, tenf to one step's opening more
    const double f_max = tenf + kn * v * w.fixed_dt;
    CHECK(w.energies.bond_break >= 0.5 * tenf * tenf / kn);
    CHECK(w.energies.bond_break <= 0.5 * f_max * f_max / kn);
}

TEST_CASE("a sheared contact bond is not limited by friction and breaks in shear at cb_shearf", "[cbond]") {
    const double v = 0.01, shearf = 0.2;  // the pair touches at zero overlap: fric Fn = 0
    auto sim = cbonded_pair({0.0, v}, 1e300, shearf);
    World& w = sim->world();
    double largest_shear = 0;
    while (w.bond_breaks.empty() && w.step_count < 20000) {
        w.step();
        if (w.bond_breaks.empty()) largest_shear = std::max(largest_shear, std::fabs(w.bodies.force[1].y()));
    }
    REQUIRE(w.bond_breaks.size() == 1);
    CHECK(w.bond_breaks[0].mode == PLAB_BREAK_SHEAR);
    CHECK(w.bond_breaks[0].time == Approx(shearf / (ks * v)).margin(1.5 * w.fixed_dt));
    CHECK(largest_shear > 0.9 * shearf);  // held while bonded, at no normal force
    sim->cycle(10);
    CHECK(std::fabs(w.bodies.force[1].y()) <= 1e-12);  // unbonded: capped at fric Fn = 0
}

TEST_CASE("linear_cbond without bonds gives the settling pile of linear bit for bit", "[cbond]") {
    for (int dim : {2, 3}) {
        INFO("dim " << dim);
        auto run = [dim](const char* model) {
            json scene = settling_scene(dim, dim == 2 ? 150 : 300);
            scene["plugins"] = {model};
            scene["contact_models"][0]["model"] = model;
            Simulation sim(scene);
            sim.set_quiet(true);
            sim.cycle(1500);
            return plab::state_hash(sim.world());
        };
        CHECK(run("linear") == run("linear_cbond"));
    }
}
