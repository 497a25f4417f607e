// Bad scenes must fail with an InputError that names the JSON path, the
// offending value and the valid range or the allowed values. One test case
// per class of bad input, in process. tests/errors/catalogue.json checks the
// same classes (and more) end to end through the plab CLI; docs/errors.md is
// generated from it.
#include <simulation.hpp>

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

using plab::json;
using Catch::Matchers::Contains;
using Catch::Matchers::EndsWith;

namespace {

// A small valid 2D scene: a lattice of grains, one probe ball, a box of
// walls, one linear contact rule, histories and two commands. Each test
// breaks one thing in a copy of it.
json base_scene() {
    return json::parse(R"({
      "dimension": 2,
      "domain": {"min": [0, 0], "max": [1, 1]},
      "gravity": [0, -9.81],
      "plugins": ["linear"],
      "bodies": [
        {"type": "lattice", "group": "grains", "box": {"min": [0.1, 0.1], "max": [0.3, 0.3]},
         "radius": 0.01, "density": 2500},
        {"type": "ball", "group": "probe", "position": [0.5, 0.5], "radius": 0.02, "density": 2500}
      ],
      "walls": [{"type": "box", "name": "container", "min": [0, 0], "max": [1, 1], "open": ["top"]}],
      "contact_models": [
        {"groups": ["*", "*"], "model": "linear",
         "properties": {"kn": 1e6, "ks": 5e5, "fric": 0.5, "dp_nratio": 0.2}}
      ],
      "timestep": {"safety_factor": 0.5},
      "histories": {"every": 10, "record": [{"quantity": "time"}, {"name": "ke", "quantity": "energy.kinetic"}]},
      "commands": [{"cycle": 10}, {"solve": {"time": 0.001}}]
    })");
}

// The message of the InputError that loading `scene` throws, or a marker
// that makes every Contains() check fail when nothing is thrown.
std::string load_error(const json& scene) {
    try {
        plab::Simulation sim(scene, ".");
    } catch (const plab::InputError& e) {
        return e.what();
    }
    return "<no InputError thrown>";
}

std::string override_error(json scene, const std::string& assignment) {
    try {
        plab::apply_override(scene, assignment);
    } catch (const plab::InputError& e) {
        return e.what();
    }
    return "<no InputError thrown>";
}

std::string temp_file(const std::string& name, const std::string& text) {
    const auto path = std::filesystem::temp_directory_path() / ("plab_scene_errors_" + name);
    std::ofstream(path) << text;
    return path.string();
}

} // namespace

TEST_CASE("a valid scene constructs and runs without throwing", "[scene]") {
    SECTION("the base scene of these tests") {
        plab::Simulation sim(base_scene(), ".");
        sim.set_quiet(true);
        CHECK(sim.world().bodies.size() > 1);
        CHECK_NOTHROW(sim.run());
    }
    SECTION("the smallest scene: a dimension") {
        const json minimal = {{"dimension", 3}};
        CHECK_NOTHROW(plab::Simulation(minimal, "."));
    }
}

TEST_CASE("a scene summarised before its first step does not crash", "[scene]") {
    // stable_timestep() needs a prepared world; summary() prepares it
    json s = base_scene();
    s.erase("commands");
    plab::Simulation sim(s, ".");
    sim.set_quiet(true);
    sim.run();
    const json summary = sim.summary();
    CHECK(summary["steps"] == 0);
    CHECK(summary["timestep"]["critical"].get<double>() > 0);
}

TEST_CASE("malformed JSON names the file, the position and the offending token", "[scene]") {
    const std::string path = temp_file("malformed.json", "{\n  \"dimension\": 2,\n  \"bodies\": [,]\n}\n");
    CHECK_THROWS_AS(plab::read_scene_file(path), plab::InputError);
    CHECK_THROWS_WITH(plab::read_scene_file(path),
                      Contains(path) && Contains("malformed JSON") && Contains("line 3") && Contains("unexpected ','"));
    std::filesystem::remove(path);
}

TEST_CASE("a scene file that does not exist is named", "[scene]") {
    CHECK_THROWS_WITH(plab::read_scene_file("/nonexistent/scene.json"),
                      Contains("/nonexistent/scene.json") && Contains("cannot open"));
}

TEST_CASE("an unknown top-level key names its path and lists the allowed keys", "[scene]") {
    json s = base_scene();
    s["bodys"] = json::array();
    CHECK_THAT(load_error(s), Contains("scene.bodys") && Contains("unknown key 'bodys'") &&
                                  Contains("allowed here: description, dimension, domain") && Contains("commands"));
}

TEST_CASE("an unknown key inside a generator names its path and lists the generator's keys", "[scene]") {
    json s = base_scene();
    s["bodies"][0]["radious"] = 0.01;
    CHECK_THAT(load_error(s), Contains("scene.bodies[0].radious") && Contains("unknown key 'radious'") &&
                                  Contains("radius") && Contains("packing") && Contains("spacing"));
}

TEST_CASE("an unknown key inside a wall names its path and lists the keys of that wall type", "[scene]") {
    json s = base_scene();
    s["walls"][0]["opn"] = json::array({"top"});
    CHECK_THAT(load_error(s),
               Contains("scene.walls[0].opn") && Contains("for a box wall") && Contains("min, max, open"));
}

TEST_CASE("an unknown key inside a contact rule names its path and lists the rule's keys", "[scene]") {
    json s = base_scene();
    s["contact_models"][0]["modle"] = "linear";
    CHECK_THAT(load_error(s), Contains("scene.contact_models[0].modle") && Contains("groups, model, properties"));
}

TEST_CASE("an unknown plug-in names its path, the name and the plug-ins found", "[scene]") {
    json s = base_scene();
    s["plugins"] = json::array({"linaer"});
    CHECK_THAT(load_error(s), Contains("scene.plugins[0]") && Contains("'linaer' not found") &&
                                  Contains("plug-ins found:") && Contains("linear"));
}

// Found by tests/fuzz (crash-a0a7525...): a name longer than a file name may
// be made std::filesystem throw instead of reporting "not found".
TEST_CASE("a plug-in name too long for a file name is an unknown plug-in, not a filesystem error", "[scene][fuzz]") {
    json s = base_scene();
    s["plugins"] = json::array({"linear" + std::string(300, 'x')});
    CHECK_THAT(load_error(s), Contains("scene.plugins[0]") && Contains("not found") && Contains("plug-ins found:"));
    s["plugins"] = json::array({std::string(300, 'x') + "/plab_linear.so"});
    CHECK_THAT(load_error(s), Contains("scene.plugins[0]") && Contains("not found"));
}

TEST_CASE("an unknown contact model lists the models available", "[scene]") {
    json s = base_scene();
    s["contact_models"][0]["model"] = "hertz_mindlin";
    CHECK_THAT(load_error(s), Contains("scene.contact_models[0].model") && Contains("\"hertz_mindlin\"") &&
                                  Contains("linear") && Contains("\"null\""));
    SECTION("and says how to load one when no plug-in is listed") {
        s.erase("plugins");
        CHECK_THAT(load_error(s), Contains("none (list plug-ins under \"plugins\")"));
    }
}

TEST_CASE("an unknown property of a model lists the model's properties", "[scene]") {
    json s = base_scene();
    s["contact_models"][0]["properties"]["kk"] = 1e6;
    CHECK_THAT(load_error(s), Contains("scene.contact_models[0].properties.kk") && Contains("'kk'") &&
                                  Contains("kn, ks, fric, dp_nratio, dp_sratio, dp_mode, rgap"));
}

TEST_CASE("a property value outside its declared range names its path, value and range", "[scene]") {
    json s = base_scene();
    auto& props = s["contact_models"][0]["properties"];
    SECTION("a damping ratio of 1.5 (dimensionless: no unit after the range)") {
        props["dp_nratio"] = 1.5;
        CHECK_THAT(load_error(s), Contains("scene.contact_models[0].properties.dp_nratio") && Contains("value 1.5") &&
                                      EndsWith("valid range [0, 1)"));
    }
    SECTION("a negative friction coefficient") {
        props["fric"] = -0.1;
        CHECK_THAT(load_error(s), Contains("properties.fric") && Contains("-0.1") && Contains("[0, inf)"));
    }
    SECTION("a dashpot mode of 7 (a choice: its names)") {
        props["dp_mode"] = 7;
        CHECK_THAT(load_error(s), Contains("properties.dp_mode") && Contains("7 is not one of full, slip_shear, no_tension"));
    }
    SECTION("a property that is not a number") {
        props["kn"] = "stiff";
        CHECK_THAT(load_error(s), Contains("properties.kn") && Contains("\"stiff\"") && Contains("(0, inf) N/m"));
    }
}

TEST_CASE("a negative or zero stiffness names its path, value and range", "[scene]") {
    json s = base_scene();
    SECTION("kn = -5") {
        s["contact_models"][0]["properties"]["kn"] = -5;
        CHECK_THAT(load_error(s), Contains("scene.contact_models[0].properties.kn") && Contains("value -5") &&
                                      Contains("normal stiffness") && Contains("(0, inf) N/m"));
    }
    SECTION("kn = 0") {
        s["contact_models"][0]["properties"]["kn"] = 0;
        CHECK_THAT(load_error(s), Contains("properties.kn") && Contains("value 0 ") && Contains("(0, inf)"));
    }
    SECTION("ks = -1 (zero is allowed: no shear spring)") {
        s["contact_models"][0]["properties"]["ks"] = -1;
        CHECK_THAT(load_error(s), Contains("properties.ks") && Contains("value -1") && Contains("[0, inf)"));
    }
}

TEST_CASE("a negative or zero radius names its path, value and range", "[scene]") {
    json s = base_scene();
    SECTION("a ball") {
        s["bodies"][1]["radius"] = -0.01;
        CHECK_THAT(load_error(s), Contains("scene.bodies[1].radius") && Contains("-0.01") && Contains("(0, inf)"));
    }
    SECTION("a lattice") {
        s["bodies"][0]["radius"] = 0;
        CHECK_THAT(load_error(s), Contains("scene.bodies[0].radius") && Contains("value 0 ") && Contains("(0, inf)"));
    }
    SECTION("one end of a random fill's radius range") {
        s["bodies"][0] = {{"type", "random_fill"}, {"box", {{"min", {0.1, 0.1}}, {"max", {0.3, 0.3}}}},
                          {"radius", {-0.01, 0.01}}, {"density", 2500}, {"count", 10}};
        CHECK_THAT(load_error(s), Contains("scene.bodies[0].radius[0]") && Contains("-0.01") && Contains("(0, inf)"));
    }
}

TEST_CASE("a zero or negative density names its path, value and range", "[scene]") {
    json s = base_scene();
    SECTION("zero") {
        s["bodies"][1]["density"] = 0;
        CHECK_THAT(load_error(s), Contains("scene.bodies[1].density") && Contains("value 0 ") && Contains("(0, inf)"));
    }
    SECTION("negative") {
        s["bodies"][0]["density"] = -2500;
        CHECK_THAT(load_error(s), Contains("scene.bodies[0].density") && Contains("-2500") && Contains("(0, inf)"));
    }
}

TEST_CASE("overlapping generator regions name both generators and both regions", "[scene]") {
    json s = base_scene();
    s["bodies"].push_back({{"type", "lattice"}, {"box", {{"min", {0.2, 0.2}}, {"max", {0.4, 0.4}}}},
                           {"radius", 0.01}, {"density", 2500}});
    CHECK_THAT(load_error(s), Contains("scene.bodies[2]") && Contains("[0.2 0.2] .. [0.4 0.4]") &&
                                  Contains("[0.1 0.1] .. [0.3 0.3] of scene.bodies[0]") && Contains("overlap"));
}

TEST_CASE("a ball or a generator region outside the domain names the generator, the ball and the domain", "[scene]") {
    json s = base_scene();
    SECTION("a single ball") {
        s["bodies"][1]["position"] = {1.5, 0.5};
        CHECK_THAT(load_error(s), Contains("scene.bodies[1]") && Contains("ball at 1.5 0.5 (radius 0.02)") &&
                                      Contains("outside the domain [0 0] .. [1 1]"));
    }
    SECTION("a lattice box reaching past the domain") {
        s["bodies"][0]["box"] = {{"min", {0.8, 0.8}}, {"max", {1.2, 1.2}}};
        CHECK_THAT(load_error(s), Contains("scene.bodies[0]") && Contains("(radius 0.01)") &&
                                      Contains("outside the domain [0 0] .. [1 1]"));
    }
}

TEST_CASE("a fixed timestep above the stable one names the factor and the stable limit", "[scene]") {
    json s = base_scene();
    s["timestep"] = {{"fixed", 0.01}};
    const std::string msg = load_error(s);
    CHECK_THAT(msg, Contains("scene.timestep.fixed") && Contains("fixed timestep 0.01 s") &&
                        Contains("x the stable limit") && Contains("valid range (0, ") &&
                        Contains("timestep.allow_unstable = true"));

    // the factor and the limit are those of the world's nominal stable step
    s["timestep"]["allow_unstable"] = true;
    plab::Simulation sim(s, ".");
    const double critical = nominal_timestep(sim.world()).critical;
    std::ostringstream expected;
    expected << 0.01 / critical << "x the stable limit " << critical << " s";
    CHECK_THAT(msg, Contains(expected.str()));
}

TEST_CASE("allow_unstable accepts a fixed timestep above the stable one and keeps a note", "[scene]") {
    json s = base_scene();
    s["timestep"] = {{"fixed", 0.01}, {"allow_unstable", true}};
    std::unique_ptr<plab::Simulation> sim;
    REQUIRE_NOTHROW(sim = std::make_unique<plab::Simulation>(s, "."));
    const std::string note = sim->summary()["timestep"]["note"].get<std::string>();
    CHECK_THAT(note, Contains("x the stable limit") && !Contains("set timestep.allow_unstable"));
    SECTION("allow_unstable must be a boolean") {
        s["timestep"]["allow_unstable"] = "yes";
        CHECK_THAT(load_error(s), Contains("scene.timestep.allow_unstable") && Contains("\"yes\"") &&
                                      Contains("true or false"));
    }
}

TEST_CASE("a vector of the wrong dimension names its path, the value and the size expected", "[scene]") {
    json s = base_scene();
    SECTION("gravity") {
        s["gravity"] = {1, 2, 3};
        CHECK_THAT(load_error(s), Contains("scene.gravity") && Contains("[1,2,3]") && Contains("expected 2 numbers"));
    }
    SECTION("a ball position") {
        s["bodies"][1]["position"] = {0.5, 0.5, 0.0};
        CHECK_THAT(load_error(s), Contains("scene.bodies[1].position") && Contains("[0.5,0.5,0.0]") &&
                                      Contains("(a 2D vector)"));
    }
    SECTION("a wall corner") {
        s["walls"][0]["max"] = {1};
        CHECK_THAT(load_error(s), Contains("scene.walls[0].max") && Contains("[1]") && Contains("expected 2 numbers"));
    }
}

TEST_CASE("an unknown group in a contact rule lists the scene's groups", "[scene]") {
    json s = base_scene();
    s["contact_models"][0]["groups"] = {"grains", "wals"};
    CHECK_THAT(load_error(s), Contains("scene.contact_models[0].groups[1]") && Contains("\"wals\"") &&
                                  Contains("groups in this scene: grains, probe, walls"));
    SECTION("a rule needs two groups") {
        s["contact_models"][0]["groups"] = {"*"};
        CHECK_THAT(load_error(s), Contains("scene.contact_models[0].groups") && Contains("[\"*\"]") &&
                                      Contains("two group names"));
    }
}

TEST_CASE("an unknown command names its path and lists the commands", "[scene]") {
    json s = base_scene();
    s["commands"] = json::array({{{"cycles", 10}}});
    CHECK_THAT(load_error(s), Contains("scene.commands[0]") && Contains("\"cycles\"") &&
                                  Contains("cycle, solve, set, bond, servo, histories, output"));
}

TEST_CASE("a solve with neither time nor ratio names its path and the choices", "[scene]") {
    json s = base_scene();
    SECTION("neither") {
        s["commands"] = json::array({{{"solve", json::object()}}});
        CHECK_THAT(load_error(s), Contains("scene.commands[0].solve") && Contains("exactly one of: time (s), ratio") &&
                                      Contains("got {}"));
    }
    SECTION("both") {
        s["commands"] = json::array({{{"solve", {{"time", 1.0}, {"ratio", 1e-3}}}}});
        CHECK_THAT(load_error(s), Contains("scene.commands[0].solve") && Contains("\"ratio\":0.001"));
    }
}

TEST_CASE("a set command with an unknown target or an empty selection says what the scene holds", "[scene]") {
    json s = base_scene();
    SECTION("an unknown group lists the groups") {
        s["commands"] = json::array({{{"set", {{"group", "sand"}, {"velocity", {0, 0}}}}}});
        CHECK_THAT(load_error(s), Contains("scene.commands[0].set.group") && Contains("\"sand\"") &&
                                      Contains("groups in this scene: grains, probe, walls"));
    }
    SECTION("an unknown wall lists the walls") {
        s["commands"] = json::array({{{"set", {{"wall", "lid"}, {"velocity", {0, 1}}}}}});
        CHECK_THAT(load_error(s), Contains("scene.commands[0].set.wall") && Contains("\"lid\"") &&
                                      Contains("walls in this scene: container"));
    }
    SECTION("a region holding no ball when the command runs shows the region and the number of balls") {
        const json region = {{"min", {5, 5}}, {"max", {6, 6}}};
        s["commands"] = json::array({{{"set", {{"region", region}, {"velocity", {0, 0}}}}}});
        plab::Simulation sim(s, ".");  // regions select when the command runs, not at load
        sim.set_quiet(true);
        CHECK_THROWS_WITH(sim.run(), Contains("scene.commands[0].set") && Contains("selects no ball at t = 0") &&
                                         Contains("\"max\":[6,6]") && Contains("none of the 106 balls"));
    }
    SECTION("a history of an unknown wall lists the walls") {
        s["histories"]["record"] = json::array({{{"quantity", "wall.force.x"}, {"wall", "lid"}}});
        CHECK_THAT(load_error(s),
                   Contains("scene.histories.record[0].wall") && Contains("walls in this scene: container"));
    }
}

TEST_CASE("a lattice box too small for one ball names the box and the radius", "[scene]") {
    json s = base_scene();
    s["bodies"][0]["box"] = {{"min", {0.1, 0.1}}, {"max", {0.105, 0.105}}};
    CHECK_THAT(load_error(s), Contains("scene.bodies[0].box") && Contains("[0.1 0.1] .. [0.105 0.105]") &&
                                  Contains("radius 0.01") && Contains("at least 0.02"));
}

TEST_CASE("a --set override makes the keys on its way, and the loader refuses those it does not know", "[scene]") {
    json misspelt = base_scene();
    plab::apply_override(misspelt, "contact_models.0.propertys.kn=1e5");
    CHECK_THAT(load_error(misspelt), Contains("scene.contact_models[0].propertys") && Contains("unknown key 'propertys'") &&
                                         Contains("allowed here: groups, model, properties"));
    SECTION("a missing parent is made: output.png on a scene without output") {
        json s = base_scene();
        s.erase("output");
        plab::apply_override(s, "output.png.interval=0.01");
        CHECK(s["output"]["png"]["interval"] == 0.01);
    }
    SECTION("a path through a number") {
        CHECK_THAT(override_error(base_scene(), "dimension.x=1"),
                   Contains("scene.dimension") && Contains("cannot descend into 2"));
    }
    SECTION("no '='") {
        CHECK_THAT(override_error(base_scene(), "dimension"), Contains("--set dimension") && Contains("PATH=VALUE"));
    }
    SECTION("a new last key is allowed (an optional property)") {
        json s = base_scene();
        plab::apply_override(s, "contact_models.0.properties.rgap=0.001");
        CHECK(s["contact_models"][0]["properties"]["rgap"] == 0.001);
    }
}

TEST_CASE("a --set override with a bad array index names the index and the valid range", "[scene]") {
    SECTION("past the end") {
        CHECK_THAT(override_error(base_scene(), "contact_models.3.model=linear"),
                   Contains("scene.contact_models.3") && Contains("index \"3\"") && Contains("[0, 1)"));
    }
    SECTION("not a number") {
        CHECK_THAT(override_error(base_scene(), "bodies.first.radius=0.02"),
                   Contains("scene.bodies.first") && Contains("index \"first\"") && Contains("[0, 2)"));
    }
    SECTION("an empty segment is not index 0") {
        CHECK_THAT(override_error(base_scene(), "bodies..radius=0.02"),
                   Contains("index \"\"") && Contains("[0, 2)"));
    }
    SECTION("a bracketed index is not made a key: the message gives the dotted path") {
        CHECK_THAT(override_error(base_scene(), "contact_models[0].properties.kn=1e6"),
                   Contains("--set contact_models[0].properties.kn=1e6") &&
                       Contains("contact_models.0.properties.kn=1e6"));
    }
}

TEST_CASE("dimension 4 names its path, value and range", "[scene]") {
    json s = base_scene();
    s["dimension"] = 4;
    CHECK_THAT(load_error(s), Contains("scene.dimension") && Contains("value 4") && Contains("[2, 3]"));
    SECTION("and a fractional dimension is not a whole number") {
        s["dimension"] = 2.5;
        CHECK_THAT(load_error(s), Contains("scene.dimension") && Contains("2.5") && Contains("whole number"));
    }
}

TEST_CASE("an unknown generator or wall type lists the types", "[scene]") {
    json s = base_scene();
    SECTION("generator") {
        s["bodies"][0]["type"] = "grid";
        CHECK_THAT(load_error(s), Contains("scene.bodies[0].type") && Contains("\"grid\"") &&
                                      Contains("ball, lattice, random_fill"));
    }
    SECTION("wall") {
        s["walls"][0]["type"] = "circle";
        CHECK_THAT(load_error(s), Contains("scene.walls[0].type") && Contains("\"circle\"") &&
                                      Contains("segment, polyline, box, plane, rectangle, triangles"));
    }
}

TEST_CASE("a random fill that cannot hold its count fails at once with the largest possible count", "[scene]") {
    json s = base_scene();
    s["bodies"][0] = {{"type", "random_fill"}, {"box", {{"min", {0.1, 0.1}}, {"max", {0.2, 0.2}}}},
                      {"radius", 0.02}, {"density", 2500}, {"count", 100000}};
    CHECK_THAT(load_error(s), Contains("scene.bodies[0].count") && Contains("value 100000") &&
                                  Contains("at most [1, 7]"));
}
