// Scene materials (scripting/materials.hpp): SPH constants stated once per
// group reach the contact model and the passes; contradictions, typos and a
// group with two materials are errors naming the JSON paths.
#include <simulation.hpp>

#include <plab_host/plugins.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>

using plab::json;
using Catch::Matchers::Contains;

namespace {

// One fluid ball resting dp above one boundary ball; the material states
// rho0, c0, gamma, h and the kernel once.
json two_ball_scene() {
    return json::parse(R"({
      "dimension": 2,
      "gravity": [0, -9.81],
      "plugins": ["sph"],
      "bodies": [
        {"type": "ball", "group": "fluid", "position": [0, 0.01], "radius": 0.005, "mass": 0.1, "fix": ["all"]},
        {"type": "ball", "group": "boundary", "position": [0, 0], "radius": 0.0025, "mass": 0.025, "fix": ["all"]}
      ],
      "materials": {"water": {"groups": ["fluid", "boundary"], "rest_density": 1000, "speed_of_sound": 15,
                              "gamma": 7, "smoothing_length": 0.012, "kernel": "wendland_c2"}},
      "contact_models": [{"groups": ["fluid", "boundary"], "model": "sph", "properties": {"viscosity": "artificial"}}],
      "passes": [
        {"name": "sph_eos", "material": "water", "properties": {"boundary_group": "boundary"}},
        {"name": "sph_wall_pressure", "material": "water", "properties": {"boundary_group": "boundary"}}
      ]
    })");
}

double model_property(const plab::World& w, const char* key) {
    return w.model(0).property(key);
}

} // namespace

TEST_CASE("a material's constants reach the sph model and the passes that name it", "[scene][sph]") {
    plab::Simulation sim(two_ball_scene());
    sim.set_quiet(true);
    plab::World& w = sim.world();
    CHECK(model_property(w, "rest_density") == 1000);
    CHECK(model_property(w, "speed_of_sound") == 15);
    CHECK(model_property(w, "smoothing_length") == 0.012);
    CHECK(model_property(w, "kernel") == 0);
    CHECK(w.model(0).range() == Approx(2 * 0.012));  // Wendland support 2h from the material's h
    w.prepare();
    // Islam eq. 10 with one fluid neighbour at rest at rho0 (p = 0), 1 cm above:
    // p_w = rho_f g·(x_w - x_f) = 1000 · 9.81 · 0.01, the scene gravity filled into gravity_y;
    // eq. 11 (inverse Tait with the material's c0 and gamma): rho_w = rho0 (p_w/B + 1)^(1/gamma)
    const auto& p = w.fields.column(w.fields.index("sph_pressure"));
    const auto& rho = w.fields.column(w.fields.index("sph_density"));
    const double p_w = 1000 * 9.81 * 0.01, B = 1000 * 15.0 * 15.0 / 7;
    CHECK(p[1] == Approx(p_w).epsilon(1e-12));
    CHECK(rho[1] == Approx(1000 * std::pow(p_w / B + 1, 1.0 / 7)).epsilon(1e-12));
}

TEST_CASE("an explicit value that contradicts the material names both JSON paths", "[scene][sph]") {
    json scene = two_ball_scene();
    scene["contact_models"][0]["properties"]["speed_of_sound"] = 20;
    CHECK_THROWS_WITH(plab::Simulation(scene),
                      Contains("scene.contact_models[0].properties.speed_of_sound") &&
                          Contains("scene.materials.water.speed_of_sound") && Contains("contradicts"));
    scene = two_ball_scene();
    scene["passes"][0]["properties"]["speed_of_sound"] = 15;  // the same value again is allowed
    CHECK_NOTHROW(plab::Simulation(scene));
    scene["passes"][1]["properties"]["gravity_y"] = -9.7;
    CHECK_THROWS_WITH(plab::Simulation(scene), Contains("scene.passes[1].properties.gravity_y") && Contains("scene.gravity"));
}

TEST_CASE("material errors: unused key, out of range, unknown material or group, two materials", "[scene][sph]") {
    json scene = two_ball_scene();
    scene["materials"]["water"]["rest_densty"] = 1000;
    CHECK_THROWS_WITH(plab::Simulation(scene), Contains("scene.materials.water.rest_densty") && Contains("no contact model or pass"));
    scene = two_ball_scene();
    scene["materials"]["water"]["gamma"] = -1;  // checked against the pass's declared range
    CHECK_THROWS_WITH(plab::Simulation(scene), Contains("scene.materials.water.gamma") && Contains("valid range"));
    scene = two_ball_scene();
    scene["passes"][0]["material"] = "oil";
    CHECK_THROWS_WITH(plab::Simulation(scene), Contains("scene.passes[0].material") && Contains("water"));
    scene = two_ball_scene();
    scene["materials"]["water"]["groups"] = {"fluid", "sand"};
    CHECK_THROWS_WITH(plab::Simulation(scene), Contains("scene.materials.water.groups[1]") && Contains("unknown group"));
    scene = two_ball_scene();
    scene["materials"]["oil"] = {{"groups", {"fluid"}}, {"rest_density", 900}};
    CHECK_THROWS_WITH(plab::Simulation(scene), Contains(".groups[0]") && Contains("one material"));
}

// Issue 37: c0 from the flow. The rules, computed here from their formulas:
// a dam break of height H, 2 sqrt(g H) (Ritter); a wall speed v with a depth
// D, max(v, sqrt(g D)); "auto" is 10 x it, in the model and in both passes.
TEST_CASE("speed_of_sound auto is 10 x the expected maximum speed of the material's rule", "[scene][sph]") {
    struct Case { json expected; double speed; };
    const Case cases[] = {{json::parse(R"({"dam_break_height": 0.2})"), 2 * std::sqrt(9.81 * 0.2)},
                          {json::parse(R"({"speed": 0.1})"), 0.1},
                          {json::parse(R"({"speed": 0.05, "depth": 0.06})"), std::sqrt(9.81 * 0.06)},
                          {json::parse(R"({"speed": 3, "depth": 0.06})"), 3.0},
                          {json(1.5), 1.5}};
    for (const Case& c : cases) {
        INFO(c.expected.dump());
        json scene = two_ball_scene();
        scene["materials"]["water"]["expected_max_speed"] = c.expected;
        scene["materials"]["water"]["speed_of_sound"] = "auto";
        plab::Simulation sim(scene);
        sim.set_quiet(true);
        CHECK(model_property(sim.world(), "speed_of_sound") == Approx(10 * c.speed).epsilon(1e-12));
        // the passes got the same c0: the wall ball's density is the inverse Tait of that c0
        sim.world().prepare();
        const double p_w = 1000 * 9.81 * 0.01, B = 1000 * 100 * c.speed * c.speed / 7;
        CHECK(sim.world().fields.column(sim.world().fields.index("sph_density"))[1] ==
              Approx(1000 * std::pow(p_w / B + 1, 1.0 / 7)).epsilon(1e-12));
        const json report = sim.summary()["speed_of_sound"];
        REQUIRE(report.size() == 1);
        CHECK(report[0]["speed_of_sound"].get<double>() == Approx(10 * c.speed).epsilon(1e-12));
        CHECK(report[0]["rule"].get<std::string>() == "auto: 10 x expected_max_speed");
        CHECK(report[0]["expected_max_speed"].get<double>() == Approx(c.speed).epsilon(1e-12));
    }
}

TEST_CASE("a speed of sound below 10 x the expected maximum speed is refused with its range", "[scene][sph]") {
    json scene = two_ball_scene();
    scene["materials"]["water"]["expected_max_speed"] = {{"dam_break_height", 0.2}};  // 10 x 2.80 = 28.0 m/s
    CHECK_THROWS_WITH(plab::Simulation(scene), Contains("scene.materials.water.speed_of_sound") && Contains("value 15") &&
                                                   Contains("[28.0143, inf)"));
    scene["materials"]["water"]["speed_of_sound"] = 30;  // above the rule: used as given, reported as checked
    plab::Simulation sim(scene);
    CHECK(model_property(sim.world(), "speed_of_sound") == 30);
    CHECK(sim.summary()["speed_of_sound"][0]["rule"].get<std::string>() == "given, checked >= 10 x expected_max_speed");
}

// ABI 2.1: a scene material gives a model or pass the properties its
// package's material declares (abi.h plab_material_desc), and no others.
namespace {

std::string test_plugin(const std::string& name) { return std::string(PLAB_TEST_PLUGIN_DIR) + "/" + name + ".so"; }

std::string refusal(const json& scene) {
    try {
        plab::Simulation sim(scene);
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

} // namespace

// Two touching balls of groups a and b with the materials soft and hard;
// material_spring (tests/plugins/material_probe.cpp) takes k from the
// material probe_solid, and has a property c of its own.
TEST_CASE("a scene material gives the properties the model's package material declares, mixed by their rule", "[scene][materials]") {
    json scene = json::parse(R"({
      "dimension": 2,
      "bodies": [
        {"type": "ball", "group": "a", "position": [0, 0], "radius": 0.01, "density": 1000},
        {"type": "ball", "group": "b", "position": [0.0199, 0], "radius": 0.01, "density": 1000}
      ],
      "materials": {"soft": {"groups": ["a"], "k": 1e4}, "hard": {"groups": ["b"], "k": 4e4}},
      "contact_models": [{"groups": ["a", "b"], "model": "material_spring"}]
    })");
    scene["plugins"] = {test_plugin("material_probe")};
    {
        plab::Simulation sim(scene);
        CHECK(sim.world().model(0).property("k") == Approx(2 * 1e4 * 4e4 / 5e4).epsilon(1e-15));  // harmonic
        CHECK(sim.world().model(0).property("c") == 0);
    }
    // c is the model's own: a scene material that states it gives it nothing, and is told so
    scene["materials"]["soft"]["c"] = 5;
    CHECK_THAT(refusal(scene), Contains("scene.materials.soft.c: no contact model or pass using the material \"soft\" "
                                        "takes a property 'c' from it; they take k: the properties their package's "
                                        "material declares"));
    scene["materials"]["soft"].erase("c");
    // a pass takes from the scene material it names what its package material declares (fric)
    scene["materials"]["hard"]["fric"] = 0.25;
    scene["passes"] = {{{"name", "material_pass"}, {"material", "hard"}}};
    plab::Simulation sim(scene);
    sim.world().prepare();
    CHECK(sim.world().fields.column(sim.world().fields.index("material_pass_fric"))[0] == 0.25);
}

TEST_CASE("a model or pass that names no package material takes nothing from a scene material", "[scene][materials]") {
    // coordination_number names no material: a scene that gives it one is told so
    json scene = two_ball_scene();
    scene["plugins"].push_back("coordination_number");
    scene["passes"].push_back({{"name", "coordination_number"}, {"material", "water"}});
    CHECK_THAT(refusal(scene), Contains("scene.passes[2].material: pass coordination_number takes no properties from a "
                                        "material (it names no package material"));
    // mu is the sph model's own (not the fluid's material): before ABI 2.1 a
    // scene material's mu reached it by its name, now it is a key no user takes
    scene = two_ball_scene();
    scene["materials"]["water"]["mu"] = 1e-3;
    CHECK_THAT(refusal(scene), Contains("scene.materials.water.mu: no contact model or pass using the material \"water\" "
                                        "takes a property 'mu' from it; they take smoothing_length, kernel, "
                                        "rest_density, speed_of_sound, gamma"));
}

TEST_CASE("the SPH package's material is one declaration, registered alike by the sph and coupling libraries", "[scene][materials][host]") {
    plab::PluginHost host;
    for (const char* lib : {"coupling_fluid_particle", "sph", "coupling_fluid_structure", "coupling_soft_repulsive"})
        CHECK_NOTHROW(host.load(host.resolve(lib)));
    const plab_material_desc* m = host.material("sph_fluid");
    REQUIRE(m != nullptr);
    CHECK(m->property_count == 6);
    for (const char* model : {"sph", "fluid_particle", "coupling_soft_repulsive"})
        CHECK(std::string(host.model(model)->material) == "sph_fluid");
    for (const char* pass : {"sph_eos", "sph_wall_pressure", "sph_density_summation", "sph_xsph", "fluid_particle_drag",
                             "structure_sph_state"})
        CHECK(std::string(host.pass(pass)->material) == "sph_fluid");
    CHECK(host.pass("sph_density_integration")->material == nullptr);  // (boundary_group only)
}
