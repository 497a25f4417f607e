// Typed plug-in properties (plug-in ABI 2, abi.h PLAB_KIND_*): the loader
// reads each kind as a scene writes it, refuses a bad value naming the JSON
// path, the value and the valid set, tells an old numeric code's new
// spelling, and mixes two materials' values by the property's rule.
#include <simulation.hpp>

#include <plab_host/errors.hpp>
#include <plab_host/plugins.hpp>
#include <plab/testing.hpp>

#include <catch2/catch.hpp>

#include <string>

using plab::json;
using Catch::Matchers::Contains;

namespace {

std::string test_plugin(const std::string& name) { return std::string(PLAB_TEST_PLUGIN_DIR) + "/" + name + ".so"; }

// Two touching balls, groups "grains" and "walls", one rule of `model`
// between them with `props`.
json scene(const std::string& model, const json& props) {
    json s = {{"dimension", 2},
              {"plugins", {"linear", test_plugin("kinds_probe")}},
              {"bodies", {{{"type", "ball"}, {"group", "grains"}, {"position", {0, 0}}, {"radius", 0.01}, {"density", 1000}},
                          {{"type", "ball"}, {"group", "walls"}, {"position", {0.0199, 0}}, {"radius", 0.01}, {"density", 1000}}}},
              {"contact_models", {{{"groups", {"grains", "walls"}}, {"model", model}, {"properties", props}}}}};
    return s;
}

json probe(json props) {
    if (!props.contains("target_group")) props["target_group"] = "walls";
    return scene("kinds_probe", props);
}

// The message the loader refuses the scene with ("" if it loads).
std::string refusal(const json& s) {
    try {
        plab::Simulation sim(s);
    } catch (const plab::InputError& e) {
        return e.what();
    }
    return "";
}

double property(const plab::Simulation& sim, const char* key) { return sim.world().model(0).property(key); }

} // namespace

TEST_CASE("each kind reaches the model as the number its law reads", "[scene][kinds]") {
    plab::Simulation sim(probe({{"layers", 3}, {"tension", true}, {"shape", "pointed"}, {"target_group", "grains"},
                                {"skip_group", "walls"}}));
    CHECK(property(sim, "layers") == 3);
    CHECK(property(sim, "tension") == 1);
    CHECK(property(sim, "shape") == 2);  // the index of "pointed"
    CHECK(property(sim, "target_group") == 0);  // groups in the order the scene names them
    CHECK(property(sim, "skip_group") == 1);
    plab::Simulation none(probe({{"skip_group", nullptr}}));
    CHECK(property(none, "skip_group") == -1);
    CHECK(property(none, "tension") == 0);   // the defaults
    CHECK(property(none, "shape") == 0);
    plab::Simulation none_word(probe({{"skip_group", "none"}}));
    CHECK(property(none_word, "skip_group") == -1);
    plab::Simulation linear(scene("linear", {{"dp_mode", "no_tension"}}));
    CHECK(property(linear, "dp_mode") == 2);  // the law's old code, the same bits
}

TEST_CASE("a number outside its range is refused with the path, the value and the range", "[scene][kinds]") {
    const std::string msg = refusal(scene("linear", {{"kn", -5}}));
    CHECK_THAT(msg, Contains("scene.contact_models[0].properties.kn: value -5 of normal stiffness is outside the valid "
                             "range (0, inf) N/m"));
}

TEST_CASE("an integer that is not whole is refused with its valid range", "[scene][kinds]") {
    const std::string msg = refusal(probe({{"layers", 2.5}}));
    CHECK_THAT(msg, Contains("scene.contact_models[0].properties.layers: value 2.5 of layer count is not a whole number; "
                             "valid: [1, 10], whole numbers"));
    CHECK_THAT(refusal(probe({{"layers", 11}})), Contains("value 11 of layer count is outside the valid range [1, 10]"));
}

TEST_CASE("a bool given a number is refused: use true or false", "[scene][kinds]") {
    CHECK_THAT(refusal(probe({{"tension", 1}})),
               Contains("scene.contact_models[0].properties.tension: 1 is a numeric code; write true (pulls too: true or false)"));
    CHECK_THAT(refusal(probe({{"tension", 0}})), Contains("0 is a numeric code; write false"));
    CHECK_THAT(refusal(probe({{"tension", 3}})),
               Contains("scene.contact_models[0].properties.tension: 3 is not true or false (pulls too); use true or false"));
    CHECK_THAT(refusal(probe({{"tension", "yes"}})), Contains("\"yes\" is not true or false"));
}

TEST_CASE("a misspelt choice is refused with the names it may take", "[scene][kinds]") {
    CHECK_THAT(refusal(scene("linear", {{"dp_mode", "no_tensoin"}})),
               Contains("scene.contact_models[0].properties.dp_mode: \"no_tensoin\" is not one of full, slip_shear, "
                        "no_tension, no_tension_slip_shear (dashpot mode)"));
    CHECK_THAT(refusal(probe({{"shape", 2.5}})),
               Contains("properties.shape: 2.5 is not one of round, flat, pointed (tip shape; write the name, in quotes)"));
}

TEST_CASE("a choice given its old numeric code is told the name to write", "[scene][kinds]") {
    CHECK_THAT(refusal(scene("linear", {{"dp_mode", 2}})),
               Contains("scene.contact_models[0].properties.dp_mode: 2 is a numeric code; write \"no_tension\" "
                        "(dashpot mode: one of full, slip_shear, no_tension, no_tension_slip_shear)"));
    CHECK_THAT(refusal(probe({{"shape", 1}})), Contains("1 is a numeric code; write \"flat\""));
}

TEST_CASE("an unknown group is refused with the groups of the scene", "[scene][kinds]") {
    CHECK_THAT(refusal(probe({{"target_group", "grians"}})),
               Contains("scene.contact_models[0].properties.target_group: \"grians\" is not a group of this scene "
                        "(target group); groups in this scene: grains, walls"));
    CHECK_THAT(refusal(probe({{"skip_group", "grians"}})),
               Contains("groups in this scene: grains, walls, or null for none"));
    CHECK_THAT(refusal(probe({{"target_group", nullptr}})),
               Contains("properties.target_group: null: target group must name a group; groups in this scene: grains, walls"));
}

TEST_CASE("a group given by its old index is told the group's name", "[scene][kinds]") {
    CHECK_THAT(refusal(probe({{"target_group", 1}})),
               Contains("scene.contact_models[0].properties.target_group: 1 is a numeric code (a group index); write "
                        "\"walls\" (target group: a group name; groups in this scene: grains, walls)"));
    CHECK_THAT(refusal(probe({{"skip_group", -1}})),
               Contains("properties.skip_group: -1 is a numeric code; write null for none"));
    CHECK_THAT(refusal(probe({{"target_group", 7}})),
               Contains("properties.target_group: 7 is not a group name (target group); groups in this scene: grains, walls"));
}

TEST_CASE("a group property the scene must give is refused when missing", "[scene][kinds]") {
    json s = probe({});
    s["contact_models"][0]["properties"].erase("target_group");
    CHECK_THAT(refusal(s), Contains("scene.contact_models[0].properties.target_group: missing: model kinds_probe needs "
                                    "target group named; groups in this scene: grains, walls"));
}

TEST_CASE("a pass's bool and group properties are read by kind too", "[scene][kinds][sph]") {
    json s = json::parse(R"({
      "dimension": 2, "plugins": ["sph"],
      "bodies": [{"type": "ball", "group": "fluid", "position": [0, 0.01], "radius": 0.005, "mass": 0.1, "fix": ["all"]},
                 {"type": "ball", "group": "boundary", "position": [0, 0], "radius": 0.0025, "mass": 0.025, "fix": ["all"]}],
      "contact_models": [{"groups": ["fluid", "boundary"], "model": "sph"}],
      "passes": [{"name": "sph_wall_pressure", "properties": {"boundary_group": 1, "no_slip": true}}]
    })");
    CHECK_THAT(refusal(s), Contains("scene.passes[0].properties.boundary_group: 1 is a numeric code (a group index); "
                                    "write \"boundary\""));
    s["passes"][0]["properties"] = {{"boundary_group", "boundary"}, {"no_slip", 0}};
    CHECK_THAT(refusal(s), Contains("scene.passes[0].properties.no_slip: 0 is a numeric code; write false"));
    s["passes"][0]["properties"] = {{"boundary_group", "boundary"}, {"no_slip", false}};
    CHECK(refusal(s).empty());
}

// Materials of the two sides of a rule (scripting/materials.cpp): sand
// against glass takes the declared mixing rule of each property.
namespace {
json sand_and_glass(const json& glass) {
    json s = scene("linear", json::object());
    s["bodies"][0]["group"] = "sand";
    s["bodies"][1]["group"] = "glass";
    s["contact_models"] = {{{"groups", {"sand", "glass"}}, {"model", "linear"}}};
    s["materials"] = {{"sand", {{"groups", {"sand"}}, {"kn", 1e6}, {"fric", 0.5}, {"dp_nratio", 0.2}}},
                      {"glass", glass}};
    return s;
}
} // namespace

TEST_CASE("two materials mix by the property's rule: kn harmonic, fric min, damping arithmetic", "[scene][kinds][materials]") {
    plab::Simulation sim(sand_and_glass({{"groups", {"glass"}}, {"kn", 4e6}, {"fric", 0.3}, {"dp_nratio", 0.1}}));
    CHECK(property(sim, "kn") == Approx(2 * 1e6 * 4e6 / 5e6).epsilon(1e-15));  // 1.6e6
    CHECK(property(sim, "fric") == 0.3);
    CHECK(property(sim, "dp_nratio") == Approx(0.15).epsilon(1e-15));
    // a rule within one material takes its value unmixed
    json same = sand_and_glass({{"groups", {"glass"}}, {"kn", 4e6}});
    same["contact_models"] = {{{"groups", {"glass", "glass"}}, {"model", "linear"}}};
    same["materials"].erase("sand");
    plab::Simulation one(same);
    CHECK(property(one, "kn") == 4e6);
}

TEST_CASE("two materials that differ on a property without a mixing rule are refused, naming both", "[scene][kinds][materials]") {
    json s = sand_and_glass({{"groups", {"glass"}}, {"kn", 1e6}, {"rgap", 1e-4}});
    s["materials"]["sand"]["rgap"] = 0;
    CHECK_THAT(refusal(s), Contains("scene.contact_models[0]: the groups of this rule have different values of rgap: 0 at "
                                    "scene.materials.sand.rgap and 0.0001 at scene.materials.glass.rgap; rgap has no "
                                    "mixing rule (mixing none"));
    CHECK_THAT(refusal(s), Contains("the two materials must agree, or rgap must leave them and be given in the rule's properties"));
}

TEST_CASE("a library built against plug-in ABI 1 is refused and told to rebuild against ABI 2", "[host][kinds]") {
    plab::PluginHost host;
    std::string msg;
    try {
        host.load(test_plugin("abi1"));
    } catch (const plab::PluginError& e) {
        msg = e.what();
    }
    CHECK_THAT(msg, Contains("abi1.so was built against plug-in ABI 1 (version 7); rebuild it against ABI 2"));
}

TEST_CASE("a description smaller than this host's struct is refused, naming the library", "[host][kinds]") {
    plab::PluginHost host;
    std::string msg;
    try {
        host.load(test_plugin("small_desc"));
    } catch (const plab::PluginError& e) {
        msg = e.what();
    }
    CHECK_THAT(msg, Contains("small_desc.so refused: a contact model description is ") &&
                        Contains("bytes (its `size`), smaller than the") && Contains("plab_contact_model_desc") &&
                        Contains("rebuild it against this ParticleLab's headers"));
    CHECK(host.model("small_desc") == nullptr);
}

// The SDK's Probe (plab/testing.hpp) takes a choice by its name's index and
// refuses a value the kind cannot take, as the loader does.

namespace {
constexpr const char* probe_modes[] = {"off", "on", "twice"};
struct ModeSpring {
    static constexpr const char* name = "mode_spring";
    static constexpr const char* doc = "test";
    static constexpr const char* timestep_rule = "sqrt(m/k)";
    static constexpr uint32_t range_kind = PLAB_RANGE_GAP;
    static constexpr uint32_t io = 0;
    static constexpr plab_property_desc properties[] = {
        plab::prop::choice("mode", "spring mode", probe_modes, 1, "off, on, twice"),
        plab::prop::boolean("flip", "flip", false, "negate the force"),
    };
    static double activity_range(const double*) { return 0.0; }
    explicit ModeSpring(const double* p) : mode(p[0]), flip(p[1] != 0) {}
    void law(const plab::Contact& c) const {
        c.set_force((flip ? -1.0 : 1.0) * mode * 1e5 * c.overlap() * c.normal());
        c.set_stiffness(1e5);
    }
    double mode;
    bool flip;
};
} // namespace

TEST_CASE("the SDK probe takes a choice by name and refuses a value its kind cannot take", "[sdk][kinds]") {
    const plab_contact_model_desc* d = plab::contact_model_desc<ModeSpring>();
    CHECK(d->size == sizeof(plab_contact_model_desc));
    CHECK(d->properties[0].size == sizeof(plab_property_desc));
    CHECK(plab::testing::choice_index(d, "mode", "twice") == 2);
    plab::testing::Probe p(d, {{"mode", plab::testing::choice_index(d, "mode", "twice")}});
    CHECK(p.force(-1e-4).x == Approx(2 * 1e5 * 1e-4));
    CHECK_THROWS_WITH(plab::testing::choice_index(d, "mode", "thrice"), Contains("'thrice' is not a choice of property 'mode'"));
    CHECK_THROWS_WITH(plab::testing::Probe(d, {{"mode", 3}}), Contains("is not a value property 'mode' can take"));
    CHECK_THROWS_WITH(plab::testing::Probe(d, {{"flip", 0.5}}), Contains("property 'flip'"));
}
