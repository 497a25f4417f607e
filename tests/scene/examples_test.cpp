// Every example scene loads and runs a few cycles (house style: examples
// stay runnable as the code changes).
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <filesystem>

namespace fs = std::filesystem;
using namespace plab;

TEST_CASE("every example scene loads and runs 20 cycles", "[examples]") {
    std::size_t ran = 0;
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(PLAB_SOURCE_DIR) / "examples")) {
        if (entry.path().extension() != ".json") continue;
        if (entry.path().parent_path().filename() == "unstable") continue;  // meant to stop: tested below
        INFO(entry.path().string());
        json scene = read_scene_file(entry.path().string());
        json commands = json::array();
        for (const auto& c : scene.value("commands", json::array()))  // keep set-up commands (bond, set)
            if (c.contains("bond") || c.contains("set")) commands.push_back(c);
        commands.push_back({{"cycle", 20}});
        scene["commands"] = commands;
        Simulation sim(scene, entry.path().parent_path().string());
        sim.set_quiet(true);
        REQUIRE_NOTHROW(sim.run());
        CHECK(sim.world().step_count == 20);
        ++ran;
    }
    CHECK(ran >= 3);
}

// examples/unstable/ holds one deliberately unstable scene per model: each
// must stop with the detector's diagnostic (never finish, never crash) and
// keep a last good state with finite positions.
TEST_CASE("every deliberately unstable example stops with a diagnostic and keeps its last good state", "[examples][stability]") {
    std::size_t ran = 0;
    for (const auto& entry : fs::directory_iterator(fs::path(PLAB_SOURCE_DIR) / "examples" / "unstable")) {
        if (entry.path().extension() != ".json") continue;
        INFO(entry.path().string());
        Simulation sim(read_scene_file(entry.path().string()), entry.path().parent_path().string());
        sim.set_quiet(true);
        std::string message;
        try {
            sim.run();
        } catch (const RunError& e) {
            message = e.what();
        }
        CHECK_THAT(message, Catch::Matchers::Contains("unstable: ") && Catch::Matchers::Contains("likely cause") &&
                                Catch::Matchers::Contains("last good state"));
        for (const Vec& x : sim.world().bodies.position) REQUIRE(x.allFinite());
        ++ran;
    }
    CHECK(ran >= 3);
}
