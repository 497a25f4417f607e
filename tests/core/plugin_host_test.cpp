// The plug-in host refuses bad libraries with messages that say what to fix
// (issue: kernel acceptance 7; issue: SDK, errors for plug-in authors).
#include "simulation.hpp"
#include "settling_scene.hpp"

#include <plab_host/errors.hpp>
#include <plab_host/plugins.hpp>
#include <plab/contact_model.hpp>

#include <catch2/catch.hpp>

#include <cstdlib>
#include <tuple>

using namespace plab;
using Catch::Matchers::Contains;

namespace {
std::string test_plugin(const std::string& name) { return std::string(PLAB_TEST_PLUGIN_DIR) + "/" + name + ".so"; }

std::string refusal(PluginHost& host, const std::string& name) {
    try {
        host.load(test_plugin(name));
    } catch (const PluginError& e) {
        return e.what();
    }
    return "";
}

json two_balls(const std::string& model) {
    return {{"dimension", 2},
            {"plugins", {"linear", test_plugin(model)}},
            {"bodies", {{{"type", "ball"}, {"position", {0, 0}}, {"radius", 0.01}, {"density", 1000}},
                        {{"type", "ball"}, {"position", {0.0199, 0}}, {"radius", 0.01}, {"density", 1000}}}},
            {"contact_models", {{{"groups", {"*", "*"}}, {"model", model}}}}};
}
} // namespace

TEST_CASE("the host finds the linear model and the coordination pass in its build folder", "[host]") {
    PluginHost host;
    host.load(host.resolve("linear"));
    host.load(host.resolve("coordination_number"));
    REQUIRE(host.model("linear") != nullptr);
    REQUIRE(host.pass("coordination_number") != nullptr);
    CHECK(host.model("linear")->property_count == 7);
}

// The SPH passes joined the sph model in one library, plab_sph: a scene
// or checkpoint that names the former library sph_passes loads it.
TEST_CASE("the former library name sph_passes resolves to plab_sph, the SPH package's one library", "[host]") {
    PluginHost host;
    CHECK(PluginHost::merged_into("sph_passes") == "sph");
    CHECK(PluginHost::merged_into("linear").empty());
    CHECK(host.resolve("sph_passes") == host.resolve("sph"));
    const LoadedLibrary& lib = host.load(host.resolve("sph_passes"));
    CHECK(lib.models == std::vector<std::string>{"sph"});
    CHECK(host.pass("sph_eos") != nullptr);
    CHECK(host.pass("sph_xsph") != nullptr);
    CHECK(host.library_of_pass("sph_eos") == host.library_of_model("sph"));
}

TEST_CASE("a library built for another ABI version is refused, naming the file and both versions", "[host]") {
    PluginHost host;
    const std::string msg = refusal(host, "wrong_abi");
    CHECK_THAT(msg, Contains("wrong_abi.so"));
    CHECK_THAT(msg, Contains("ABI version 99"));
    CHECK_THAT(msg, Contains("it speaks ABI " + std::to_string(PLAB_ABI_MAJOR) + "." + std::to_string(PLAB_ABI_MINOR)));
    CHECK_THAT(msg, Contains("rebuild"));
}

TEST_CASE("a library without plab_plugin_init is refused and told how to define it", "[host]") {
    PluginHost host;
    const std::string msg = refusal(host, "missing_init");
    CHECK_THAT(msg, Contains("missing_init.so"));
    CHECK_THAT(msg, Contains("plab_plugin_init"));
    CHECK_THAT(msg, Contains("PLAB_PLUGIN"));
}

TEST_CASE("a second model named linear is refused, naming the library that owns the name", "[host]") {
    PluginHost host;
    host.load(host.resolve("linear"));
    const std::string msg = refusal(host, "duplicate_linear");
    CHECK_THAT(msg, Contains("duplicate_linear.so"));
    CHECK_THAT(msg, Contains("'linear' is already registered by"));
    CHECK_THAT(msg, Contains("plab_linear.so"));
    CHECK(host.model("linear") != nullptr);  // the first one is untouched
}

TEST_CASE("a property without a unit or with a default outside its range is refused", "[host]") {
    PluginHost host;
    const std::string msg = refusal(host, "no_unit");
    CHECK_THAT(msg, Contains("property k has no SI unit"));
    CHECK_THAT(msg, Contains("default -1 is outside its range [0, 1e+12]"));
    CHECK(host.model("no_unit") == nullptr);
}

TEST_CASE("a model that reports no stable timestep is refused when the scene is loaded", "[host]") {
    CHECK_THROWS_WITH(Simulation(two_balls("no_timestep")), Contains("reports no stable timestep") &&
                                                               Contains("set_stiffness() or set_dt_limit()"));
}

TEST_CASE("a model returning NaN stops the run with a diagnostic naming the ball and the step", "[host]") {
    json scene = two_balls("nan_model");
    scene["bodies"][0]["velocity"] = {1.0, 0.0};
    Simulation sim(scene);
    sim.set_quiet(true);
    CHECK_THROWS_WITH(sim.cycle(20000), Contains("non-finite state") && Contains("ball id") && Contains("at step") &&
                                           Contains("contact model 'nan_model' returned a non-finite force") &&
                                           Contains("ball id 0 and ball id 1") && Contains("check its law") &&
                                           Contains("back at its last good state"));
}

TEST_CASE("a run that goes unstable keeps its last good state", "[host][stability]") {
    json scene = two_balls("nan_model");
    scene["bodies"][0]["velocity"] = {1.0, 0.0};
    Simulation sim(scene);
    sim.set_quiet(true);
    World& w = sim.world();
    std::uint64_t failed_at = 0;
    try {
        sim.cycle(20000);
    } catch (const RunError& e) {
        const std::string msg = e.what();
        failed_at = std::stoull(msg.substr(msg.find("at step ") + 8));
    }
    REQUIRE(failed_at > 0);
    CHECK(w.step_count % w.snapshot_interval == 0);  // the kept state, not the failed one
    CHECK(w.step_count < failed_at);
    CHECK(failed_at - w.step_count <= w.snapshot_interval);
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        CHECK(w.bodies.position[i].allFinite());
        CHECK(w.bodies.velocity[i].allFinite());
    }
    // and it can go on from there (with a change that avoids the failure)
    w.bodies.velocity[0] = Vec(-1.0, 0.0, 0.0);
    w.mark_dirty();
    CHECK_NOTHROW(sim.cycle(100));
}

TEST_CASE("an unknown model name lists the models that are available", "[host]") {
    CHECK_THROWS_WITH(Simulation(two_balls("no_such_model")), Contains("not found"));
    json scene = two_balls("duplicate_linear");
    scene["plugins"] = {"linear"};
    scene["contact_models"][0]["model"] = "lineer";
    CHECK_THROWS_WITH(Simulation(scene), Contains("unknown contact model \"lineer\"") && Contains("linear") &&
                                            Contains("scene.contact_models[0].model"));
}

TEST_CASE("PLAB_PLUGIN_PATH folders are searched before the build folder", "[host]") {
    setenv("PLAB_PLUGIN_PATH", PLAB_TEST_PLUGIN_DIR, 1);
    PluginHost host;
    unsetenv("PLAB_PLUGIN_PATH");
    CHECK(host.search_dirs().front() == PLAB_TEST_PLUGIN_DIR);
    CHECK_THAT(host.resolve("nan_model"), Contains("test_plugins/nan_model.so"));
}

// ABI 5: a model may declare the optional inputs it reads and outputs it
// writes (abi.h, PLAB_IO_*); the host then skips the others. A wrong
// declaration would give silently wrong forces, so the host checks it on a
// probe contact before the first step.
TEST_CASE("a model that reads an input its io does not declare is refused, told what to add", "[host][io]") {
    json scene = two_balls("reads_undeclared");
    scene["plugins"] = {"linear", test_plugin("undeclared_io")};
    CHECK_THROWS_WITH(Simulation(scene), Contains("contact model 'reads_undeclared'") &&
                                             Contains("inputs its `io` does not declare are NaN") &&
                                             Contains("add it to `io`"));
}

TEST_CASE("a model that writes an output its io does not declare is refused, naming the column", "[host][io]") {
    json scene = two_balls("writes_undeclared");
    scene["plugins"] = {"linear", test_plugin("undeclared_io")};
    CHECK_THROWS_WITH(Simulation(scene), Contains("contact model 'writes_undeclared' writes moment1") &&
                                             Contains("does not declare it"));
}

TEST_CASE("a model that does not declare its io is refused, by name", "[host][io]") {
    PluginHost host;
    CHECK_THROWS_WITH(host.load(test_plugin("no_io")), Contains("no_io") && Contains("does not declare its io"));
}

TEST_CASE("linear with its io declaration gives bit for bit the state of the same law declaring every column", "[host][io]") {
    // the settling pile (friction, dashpots, walls): the declared path skips
    // packing spin, radii and masses and reading back moments; nothing the law
    // uses may change
    auto run = [](int dim, const std::string& model, const std::string& plugin) {
        json scene = settling_scene(dim, dim == 2 ? 150 : 400);
        scene["plugins"] = {"linear", plugin};
        scene["contact_models"][0]["model"] = model;
        Simulation sim(scene);
        sim.set_quiet(true);
        sim.cycle(1500);
        const auto& e = sim.world().energies;
        return std::make_tuple(state_hash(sim.world()), e.kinetic, e.dashpot, e.slip, stable_timestep(sim.world()).critical);
    };
    for (int dim : {2, 3}) {
        INFO("dim " << dim);
        const auto declared = run(dim, "linear", "linear");
        const auto everything = run(dim, "linear_all_io", test_plugin("linear_all_io"));
        CHECK(std::get<1>(declared) > 0);  // the pile moves, and its contacts dissipate
        CHECK(std::get<2>(declared) > 0);
        CHECK(std::get<3>(declared) > 0);
        CHECK(declared == everything);
    }
}

// ABI 2.1: materials (abi.h plab_material_desc), the properties a package's
// models and passes share, registered once or alike by each user.
TEST_CASE("a material is registered with the model and pass that take from it, alike each time", "[host][materials]") {
    PluginHost host;
    const LoadedLibrary& lib = host.load(test_plugin("material_probe"));
    CHECK(lib.materials == std::vector<std::string>{"probe_solid"});
    const plab_material_desc* m = host.material("probe_solid");
    REQUIRE(m != nullptr);
    CHECK(m->property_count == 2);
    CHECK(std::string(host.model("material_spring")->material) == "probe_solid");
    CHECK(std::string(host.pass("material_pass")->material) == "probe_solid");
    CHECK(material_property(m, "k") != nullptr);
    CHECK(material_property(m, "c") == nullptr);  // the model's own
    CHECK(host.material("no_such") == nullptr);
    // the shipped models of ABI 2.0 style name none
    host.load(host.resolve("coordination_number"));
    CHECK(host.pass("coordination_number")->material == nullptr);
}

TEST_CASE("a second registration of a material with other properties is refused, naming the first library", "[host][materials]") {
    PluginHost host;
    host.load(test_plugin("material_probe"));
    const std::string msg = refusal(host, "material_conflict");
    CHECK_THAT(msg, Contains("material_conflict.so refused: material 'probe_solid' is already registered by") &&
                        Contains("material_probe.so with other properties (1 properties against 2)"));
    CHECK(host.material("probe_solid")->property_count == 2);
    // loaded alone, the same library is well-formed
    PluginHost fresh;
    CHECK(refusal(fresh, "material_conflict").empty());
}

TEST_CASE("a model that declares a property of its material otherwise is refused, naming the difference", "[host][materials]") {
    PluginHost host;
    const std::string msg = refusal(host, "material_mismatch");
    CHECK_THAT(msg, Contains("model 'mismatch_spring': property k is a property of its material 'stiff_solid', declared "
                             "differently (default 100000 against 200000 in the material)"));
    CHECK(host.model("mismatch_spring") == nullptr);
    CHECK(host.material("stiff_solid") == nullptr);  // rolled back with the library
}

TEST_CASE("a model that names a material no library registered is refused", "[host][materials]") {
    PluginHost host;
    CHECK_THAT(refusal(host, "material_unregistered"),
               Contains("model 'lone_spring': takes its shared properties from the material 'nowhere_solid', which is "
                        "not registered"));
}

TEST_CASE("a library built against ABI 2.0 loads, its descriptions read as naming no material and no tangential slot",
          "[host][materials]") {
    PluginHost host;
    CHECK(refusal(host, "abi20").empty());
    const plab_contact_model_desc* d = host.model("abi20_spring");
    REQUIRE(d != nullptr);
    CHECK(d->material == nullptr);
    REQUIRE(d->history_count == 3);
    for (uint32_t h = 0; h < 3; ++h) {
        INFO("slot " << h);
        CHECK(d->history[h].size == sizeof(plab_history_desc));  // the host's copy, read with the plug-in's stride
        CHECK(d->history[h].flags == 0);
    }
    CHECK(std::string(d->history[2].name) == "shear_force_z");
    REQUIRE(host.pass("abi20_pass") != nullptr);
    CHECK(host.pass("abi20_pass")->material == nullptr);
}

namespace {
// A spring whose three history slots `flags` marks (abi.h PLAB_HISTORY_*).
struct FlaggedSpring {
    static constexpr const char* name = "flagged_spring";
    static constexpr const char* doc = "test spring";
    static constexpr const char* timestep_rule = "sqrt(m/k)";
    static constexpr uint32_t range_kind = PLAB_RANGE_GAP;
    static constexpr uint32_t io = 0;
    static constexpr plab_property_desc properties[] = {
        plab::prop::number("k", "stiffness", "N/m", 1e5, 0.0, 1e12, PLAB_MIN_EXCLUSIVE, "spring")};
    static constexpr plab_history_desc history[] = {plab::history_desc("a", 0.0, PLAB_SWAP_NEGATE, "x"),
                                                    plab::history_desc("b", 0.0, PLAB_SWAP_NEGATE, "y"),
                                                    plab::history_desc("c", 0.0, PLAB_SWAP_NEGATE, "z")};
    static double activity_range(const double*) { return 0.0; }
    explicit FlaggedSpring(const double*) {}
    void law(const plab::Contact& c) const { c.set_stiffness(1e5); }
};
std::string flag_problems(std::initializer_list<uint32_t> flags) {
    plab_contact_model_desc d = *plab::contact_model_desc<FlaggedSpring>();
    std::vector<plab_history_desc> slots(FlaggedSpring::history, FlaggedSpring::history + 3);
    std::size_t h = 0;
    for (uint32_t f : flags) slots[h++].flags = f;
    d.history = slots.data();
    std::string all;
    for (const std::string& b : check_model_desc(d)) all += b + "; ";
    return all;
}
} // namespace

TEST_CASE("a tangential history vector is three slots, x, y and z, and flags the host does not know are refused", "[host]") {
    CHECK(flag_problems({PLAB_HISTORY_TANGENTIAL, 0, 0}).empty());
    CHECK_THAT(flag_problems({0, PLAB_HISTORY_TANGENTIAL, 0}),
               Contains("history slot 1 is flagged tangential, the x of a vector, but fewer than two slots follow it"));
    CHECK_THAT(flag_problems({PLAB_HISTORY_TANGENTIAL, PLAB_HISTORY_TANGENTIAL, 0}),
               Contains("history slot 0 is flagged tangential, the x of a vector, and so is its y or z"));
    CHECK_THAT(flag_problems({0, 0, 4}), Contains("history slot 2 has flags this host does not know"));
}
