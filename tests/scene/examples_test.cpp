// Every example scene loads and runs a few cycles (house style: examples
// stay runnable as the code changes).
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
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

namespace {
// A scene that simulates an SPH fluid: it loads the sph plug-ins or a
// fluid-structure coupling.
bool is_sph_scene(const json& scene) {
    for (const auto& p : scene.value("plugins", json::array()))
        if (p.is_string() && (p.get<std::string>().rfind("sph", 0) == 0 || p.get<std::string>().rfind("coupling", 0) == 0))
            return true;
    return false;
}

// Sum of the scene's solve times: where the run must get to.
double end_time(const json& scene) {
    double t = 0;
    for (const auto& c : scene.value("commands", json::array()))
        if (c.contains("solve") && c["solve"].contains("time")) t += c["solve"]["time"].get<double>();
    return t;
}

// Runs a scene to its end; the stop message when it stopped, else "".
std::string run_to_end(const json& scene, const fs::path& dir) {
    Simulation sim(scene, dir.string());
    sim.set_quiet(true);
    try {
        sim.run();
    } catch (const RunError& e) {
        return e.what();
    }
    const double end = end_time(sim.scene());
    return sim.world().time >= end * (1 - 1e-9) ? "" : "ended at t = " + std::to_string(sim.world().time) + " s";
}
} // namespace

// Issue 37: every shipped SPH example runs to its own end time, as shipped
// (each takes under a second); examples/unstable/ is tested above. The SPH
// validation scenes run to their ends in their quick forms (validate_*_quick,
// which fail on a run that stopped).
TEST_CASE("every sph example scene runs to its own end time without stopping", "[examples][sph]") {
    std::size_t ran = 0;
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(PLAB_SOURCE_DIR) / "examples")) {
        const fs::path& p = entry.path();
        if (p.extension() != ".json" || p.parent_path().filename() == "unstable") continue;
        const json scene = read_scene_file(p.string());
        if (!is_sph_scene(scene)) continue;
        INFO(p.string());
        CHECK(run_to_end(scene, p.parent_path()) == "");
        ++ran;
    }
    CHECK(ran >= 2);  // piston.json, soft_repulsive_bounce.json
}

// Issue 37's report: the shipped dam break run on to t = 0.5 s, through the
// surge's impact on the far wall (t ~ 0.25 s) and the jet up it. With
// c0 = 10 x 2 sqrt(g H) (the material's dam_break_height rule) it keeps
// every density within the 5 % band; at c0 = 10 sqrt(2 g H) = 19.8 m/s it
// stopped at step 4859, t = 0.297 s, density 1.05 rho0. The shipped a/dp 20
// (at a/dp 10 the old c0 survives: the test would not see the fault).
TEST_CASE("the dam break runs through the wall impact to t = 0.5 s (sph)", "[examples][sph]") {
    const fs::path dir = fs::path(PLAB_SOURCE_DIR) / "validation" / "dam_break";
    json scene = read_scene_file((dir / "scene.json").string());
    scene["commands"] = json::array({{{"solve", {{"time", 0.5}}}}});
    CHECK(run_to_end(scene, dir) == "");
}

// examples/teaching/gate_models: gate.json (a linear_pbond gate) and the same
// scene with the structure swapped by sph_solid.sets (an sph_solid gate coupled
// through coupling_soft_repulsive), each run to its shipped end (2 ms). The
// swap must load (the sets file is what run.sh and the README give students)
// and change the gate only: the same water and tank, a gate of another
// particle count. In both the water pushes the free end downstream (+x) from
// the first steps: 0.12 mm (linear_pbond) and 0.31 mm (sph_solid) at 2 ms,
// where a gate the water did not push would move by gravity alone (x ~ 0).
TEST_CASE("the teaching gate example runs with either structure model and the water pushes its free end out", "[examples][sph]") {
    const fs::path dir = fs::path(PLAB_SOURCE_DIR) / "examples" / "teaching" / "gate_models";
    const json base = read_scene_file((dir / "gate.json").string());
    json swapped = base;
    std::ifstream sets(dir / "sph_solid.sets");
    REQUIRE(sets);
    std::size_t lines = 0;
    for (std::string line; std::getline(sets, line);) {
        if (line.empty() || line[0] == '#') continue;
        apply_override(swapped, line);
        ++lines;
    }
    CHECK(lines == 6);
    CHECK(swapped["contact_models"][3]["model"] == "sph_solid");
    CHECK(swapped["contact_models"][2]["model"] == "coupling_soft_repulsive");
    std::vector<std::size_t> gate_balls, other_balls;
    for (const json& scene : {base, swapped}) {
        INFO(scene["plugins"].dump());
        Simulation sim(scene, dir.string());
        sim.set_quiet(true);
        REQUIRE_NOTHROW(sim.run());
        const auto dx = sim.history("tip_dx");
        REQUIRE(!dx.empty());
        CHECK(dx.back() > 5e-5);
        CHECK(dx.back() < 1e-3);
        const auto& w = sim.world();
        std::size_t gate = 0;
        const int g = w.find_group("gate");
        REQUIRE(g >= 0);
        for (std::size_t i = 0; i < w.bodies.size(); ++i) gate += w.bodies.group[i] == g;
        gate_balls.push_back(gate);
        other_balls.push_back(w.bodies.size() - gate);
    }
    CHECK(gate_balls[0] == 78);   // 2 x 39 bonded balls
    CHECK(gate_balls[1] == 150);  // 3 x 50 SPH particles
    CHECK(other_balls[0] == other_balls[1]);  // the same water and tank
}
