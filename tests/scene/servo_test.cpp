// Servo-controlled walls (scripting/servo.hpp, issue 36): a lid pressed on
// a packing of discs reaches its target stress and stops there; the stress
// it reports is the balls' force on it over its area; the packing's stress
// from its contacts is the lid's; a servo let go by a command stays off
// across a restart; bad servos are refused by path.
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

using namespace plab;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

// 150 discs (r 2-3 mm) in a 10 cm wide box, no gravity, a lid at 12 cm
// pressed down by a servo; local damping settles the packing.
json pressed_packing(double stress) {
    json scene = json::parse(R"({
      "dimension": 2,
      "bodies": [{"type": "random_fill", "group": "grains", "box": {"min": [0, 0], "max": [0.1, 0.1]},
                  "radius": [0.002, 0.003], "count": 150, "density": 2500, "local_damping": 0.7, "seed": 3}],
      "walls": [{"type": "box", "name": "box", "min": [0, 0], "max": [0.1, 0.2], "open": ["top"]},
                {"type": "segment", "name": "lid", "from": [0, 0.12], "to": [0.1, 0.12]}],
      "servos": [{"wall": "lid", "direction": [0, -1], "area": 0.1, "gain": 0.5, "max_speed": 0.5}],
      "plugins": ["linear"],
      "contact_models": [{"groups": ["*", "*"], "model": "linear", "properties": {"kn": 1e6, "ks": 1e6, "fric": 0.3}}],
      "timestep": {"safety_factor": 0.5}})");
    scene["servos"][0]["stress"] = stress;
    return scene;
}

} // namespace

TEST_CASE("a servo lid presses a packing to its target stress and comes to rest there", "[scene][servo]") {
    for (double target : {1e4, 1e5}) {
        INFO("target " << target << " Pa");
        Simulation sim(pressed_packing(target));
        sim.set_quiet(true);
        sim.cycle(40000);  // the lid closes in and the packing settles by about 0.5 s, 13 000 steps
        const World& w = sim.world();
        const int lid = w.walls.find("lid");
        const double stress = w.walls.walls[std::size_t(lid)].force.y() / 0.1;  // the balls push the lid up
        CHECK(stress == Approx(target).epsilon(0.01));
        CHECK(std::fabs(w.walls.walls[std::size_t(lid)].velocity.y()) < 1e-4);
        // at rest, the box (its floor, and its sides by friction) holds what the lid pushes: no gravity
        const int box = w.walls.find("box");
        CHECK(w.walls.walls[std::size_t(box)].force.y() == Approx(-w.walls.walls[std::size_t(lid)].force.y()).epsilon(0.01));
    }
}

TEST_CASE("at rest under a servo lid, the packing's stress from its contacts is the lid's stress within 1 %",
          "[scene][servo][measurements]") {
    json scene = pressed_packing(1e5);
    // frictionless walls, as a biaxial test's platens: the walls' stress is then normal only
    scene["contact_models"].push_back({{"groups", {"grains", "walls"}}, {"model", "linear"},
                                       {"properties", {{"kn", 1e6}, {"ks", 1e6}, {"fric", 0.0}}}});
    // the whole packing: the measurement box reaches past the walls (a wall
    // contact's point lies half the overlap inside the wall) and above the
    // lid, so its volume is rescaled to the packing's (0.1 m x the lid's
    // height) below
    scene["histories"] = {{"every", 1000},
                          {"record", {{{"name", "syy"}, {"quantity", "measure.contact_stress"},
                                       {"with", {{"min", {-0.01, -0.01}}, {"max", {0.11, 0.2}}, {"component", "yy"}}}},
                                      {{"name", "sxx"}, {"quantity", "measure.contact_stress"},
                                       {"with", {{"min", {-0.01, -0.01}}, {"max", {0.11, 0.2}}, {"component", "xx"}}}}}}};
    Simulation sim(scene);
    sim.set_quiet(true);
    sim.cycle(40000);
    const World& w = sim.world();
    const int lid = w.walls.find("lid");
    double height = 0;
    for (const Facet& f : w.walls.facets)
        if (f.wall == lid) height = f.a.y();
    const double lid_stress = w.walls.walls[std::size_t(lid)].force.y() / 0.1;
    const double syy = sim.history("syy").back() * (0.12 * 0.21) / (0.1 * height);  // (tension positive: the packing is compressed)
    CHECK(lid_stress == Approx(1e5).epsilon(0.01));
    CHECK(-syy == Approx(lid_stress).epsilon(0.01));
    CHECK(sim.history("sxx").back() < 0);  // (the sides hold the packing in too)
}

TEST_CASE("a servo on an unknown wall, a zero direction or a second servo on a wall is refused by path", "[scene][servo]") {
    json s = pressed_packing(1e4);
    s["servos"][0]["wall"] = "lidd";
    CHECK_THROWS_WITH(Simulation(s), Contains("scene.servos[0].wall") && Contains("lidd") && Contains("lid"));
    s = pressed_packing(1e4);
    s["servos"][0]["direction"] = {0, 0};
    CHECK_THROWS_WITH(Simulation(s), Contains("scene.servos[0].direction"));
    s = pressed_packing(1e4);
    s["servos"].push_back(s["servos"][0]);
    CHECK_THROWS_WITH(Simulation(s), Contains("scene.servos[1].wall") && Contains("has a servo already"));
    s = pressed_packing(1e4);
    s["servos"][0].erase("max_speed");
    CHECK_THROWS_WITH(Simulation(s), Contains("scene.servos[0].max_speed"));
}

TEST_CASE("a servo let go by a command stays off after a restart: the run resumes to the same bits", "[scene][servo][restart]") {
    json scene = pressed_packing(1e5);
    scene["timestep"] = {{"fixed", 2e-5}};
    // pressed, then the lid let go and pushed down at a constant speed (a
    // platen); the checkpoint falls after the let-go, so a restart that
    // forgot it would drive the lid by the servo again
    scene["commands"] = {{{"cycle", 3000}},
                         {{"servo", {{"wall", "lid"}, {"off", true}}}},
                         {{"set", {{"wall", "lid"}, {"velocity", {0, -0.02}}}}},
                         {{"cycle", 2000}}};
    const fs::path dir = fs::temp_directory_path() / "plab_servo_restart";
    fs::remove_all(dir);
    Simulation whole(scene);
    whole.set_quiet(true);
    whole.set_output_dir(dir.string());
    whole.set_checkpoint_every(4000 * 2e-5);  // one checkpoint, near step 4000
    whole.run();
    const World& w = whole.world();
    CHECK(w.walls.walls[std::size_t(w.walls.find("lid"))].velocity.y() == -0.02);  // the servo stayed off
    auto resumed = Simulation::restart(whole.checkpoint_path());
    resumed->set_quiet(true);
    CHECK(resumed->world().step_count > 3000);
    resumed->run();
    CHECK(resumed->world().step_count == 5000);
    CHECK(state_hash(resumed->world()) == state_hash(w));
}
