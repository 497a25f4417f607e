// `plab restart --set` (issue 38, item 6): a change that a restart can make
// takes effect from the restart step and is logged; one that the checkpoint
// would silently undo (the bodies, the commands already run) is refused,
// naming its path.
#include "simulation.hpp"
#include "../core/settling_scene.hpp"

#include <plab_host/errors.hpp>

#include <catch2/catch.hpp>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <csignal>
#include <filesystem>
#include <sstream>
#include <unistd.h>

using namespace plab;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("plab_restart_set_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir / name;
}

json pile() {
    json scene = settling_scene(2, 150);
    scene["timestep"] = {{"fixed", 5e-4}};
    scene["commands"] = {{{"cycle", 300}}, {{"cycle", 100}}};
    return scene;
}

// What spdlog's default logger says while the object lives.
class LogCapture {
public:
    LogCapture() : old_(spdlog::default_logger()) {
        spdlog::set_default_logger(
            std::make_shared<spdlog::logger>("capture", std::make_shared<spdlog::sinks::ostream_sink_mt>(text_)));
    }
    ~LogCapture() { spdlog::set_default_logger(old_); }
    std::string text() const { return text_.str(); }

private:
    std::ostringstream text_;
    std::shared_ptr<spdlog::logger> old_;
};

// A checkpoint of the pile 200 steps in, before its commands begin.
fs::path checkpoint_before_commands() {
    const fs::path file = scratch("before.plab");
    Simulation sim(pile());
    sim.set_quiet(true);
    sim.cycle(200);
    sim.save_checkpoint(file.string());
    return file;
}

// A checkpoint of the pile one step into its first command (as SIGTERM leaves it).
fs::path checkpoint_in_first_command() {
    Simulation sim(pile());
    sim.set_quiet(true);
    sim.set_output_dir(scratch("in_first").string());
    sim.cycle(200);
    request_stop(SIGTERM);
    sim.run();
    clear_stop();
    REQUIRE(sim.interrupted());
    return sim.checkpoint_path();
}

std::string restart_refusal(const fs::path& file, const std::string& set) {
    try {
        Simulation::restart(file.string(), {set});
    } catch (const InputError& e) {
        return e.what();
    }
    return "<restarted>";
}

} // namespace

TEST_CASE("restart --set gravity takes effect from the restart step, as a set command there would, and is logged",
          "[restart][set]") {
    const fs::path file = checkpoint_before_commands();
    // the run that changes gravity at step 200 itself
    Simulation whole(pile());
    whole.set_quiet(true);
    whole.cycle(200);
    whole.world().gravity = Vec(0, -1, 0);
    whole.world().mark_dirty();
    whole.run();

    auto plain = Simulation::restart(file.string());
    plain->set_quiet(true);
    plain->run();
    REQUIRE(state_hash(plain->world()) != state_hash(whole.world()));  // gravity matters here

    auto changed = Simulation::restart(file.string(), {"gravity=[0,-1]"});
    CHECK(changed->world().gravity == Vec(0, -1, 0));
    LogCapture log;
    changed->run();
    CHECK(changed->world().step_count == whole.world().step_count);
    CHECK(state_hash(changed->world()) == state_hash(whole.world()));
    CHECK_THAT(log.text(), Contains("restart: set gravity = [0,-1]"));
}

TEST_CASE("restart --set of the timestep and of a later command is applied and logged", "[restart][set]") {
    const fs::path file = checkpoint_in_first_command();
    auto sim = Simulation::restart(file.string(), {"timestep.fixed=2.5e-4", "commands.1.cycle=50"});
    CHECK(sim->world().fixed_dt == 2.5e-4);
    LogCapture log;
    sim->run();
    CHECK(sim->world().step_count == 200 + 300 + 50);
    CHECK_THAT(log.text(), Contains("restart: set timestep.fixed = 0.00025") && Contains("restart: set commands.1.cycle = 50"));
}

TEST_CASE("restart --set of what the checkpoint restores is refused by path, with what can change", "[restart][set]") {
    const fs::path file = checkpoint_in_first_command();
    const std::string radius = restart_refusal(file, "bodies.0.radius=0.003");
    CHECK_THAT(radius, Contains("scene.bodies.0.radius: cannot be changed on restart (the bodies are restored from the "
                                "checkpoint); changeable on restart: timestep.*, gravity,"));
    CHECK_THAT(restart_refusal(file, "walls.0.max=[0.1,0.3]"),
               Contains("scene.walls.0.max: cannot be changed on restart (the walls are restored"));
    CHECK_THAT(restart_refusal(file, "contact_models.0.groups=[\"grains\",\"grains\"]"),
               Contains("scene.contact_models.0.groups: cannot be changed on restart (the contact-model assignment"));
    CHECK_THAT(restart_refusal(file, "commands.0.cycle=50"),
               Contains("scene.commands.0.cycle: cannot be changed on restart (the run is in this command; "
                        "commands.1 on can change)"));
    CHECK_THAT(restart_refusal(file, "commands=[{\"cycle\":5}]"), Contains("scene.commands: cannot be changed on restart"));
    // a property of a model is the scene's from the restart on
    CHECK(restart_refusal(file, "contact_models.0.properties.kn=2e4") == "<restarted>");
}
