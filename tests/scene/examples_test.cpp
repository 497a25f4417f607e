// Every example scene loads and runs a few cycles (house style: examples
// stay runnable as the code changes).
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <vector>

namespace fs = std::filesystem;
using namespace plab;

// Every example scene, and every validation case's scene (each runs as a
// plain scene too: plab run validation/<case>/scene.json).
std::vector<fs::path> runnable_scenes() {
    std::vector<fs::path> out;
    for (const char* folder : {"examples", "validation"})
        for (const auto& entry : fs::recursive_directory_iterator(fs::path(PLAB_SOURCE_DIR) / folder)) {
            const fs::path& p = entry.path();
            if (p.extension() != ".json" || p.filename() == "case.json") continue;
            if (p.parent_path().filename() == "unstable") continue;  // meant to stop: tested below
            out.push_back(p);
        }
    return out;
}

TEST_CASE("every example and validation scene loads and runs 20 cycles", "[examples]") {
    std::size_t ran = 0;
    for (const fs::path& path : runnable_scenes()) {
        INFO(path.string());
        json scene = read_scene_file(path.string());
        json commands = json::array();
        for (const auto& c : scene.value("commands", json::array()))  // keep set-up commands (bond, set)
            if (c.contains("bond") || c.contains("set")) commands.push_back(c);
        commands.push_back({{"cycle", 20}});
        scene["commands"] = commands;
        Simulation sim(scene, path.parent_path().string());
        sim.set_quiet(true);
        REQUIRE_NOTHROW(sim.run());
        CHECK(sim.world().step_count == 20);
        ++ran;
    }
    CHECK(ran >= 10);
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
