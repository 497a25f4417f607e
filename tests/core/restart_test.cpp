// Checkpoint–restart is bit-identical (issue 9): a run stopped at step k,
// written to a checkpoint and continued in a fresh Simulation reaches the
// same state hash at step n as the run that never stopped — for a granular
// pile, a bonded plate whose bonds break, and an SPH tank, with 1 and 2
// threads. A checkpoint that cannot load says exactly why.
#include "simulation.hpp"
#include "settling_scene.hpp"

#include <plab_host/checkpoint.hpp>

#include "../support/file_bytes.hpp"

#include <catch2/catch.hpp>
#include <zlib.h>

#include <csignal>
#include <cstring>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <unistd.h>

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace plab;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

using testing_support::slurp;
using testing_support::spit;

void use_threads(int threads) {
#ifdef _OPENMP
    omp_set_num_threads(threads);
    REQUIRE(omp_get_max_threads() == threads);
#else
    (void)threads;
#endif
}

struct ThreadsBack {
    ~ThreadsBack() {
#ifdef _OPENMP
        omp_set_num_threads(1);
#endif
    }
};

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("plab_restart_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir / name;
}

json pile(int dim = 2) { return settling_scene(dim, dim == 2 ? 150 : 250); }


// with_options: also XSPH (a pre-drift pass, the drift velocity
// correction) and the normalised summation density filter
json tank_scene(bool with_options = false) {
    json scene = read_scene_file(std::string(PLAB_SOURCE_DIR) + "/validation/static_tank/scene.json");
    for (const char* k : {"commands", "output", "histories", "metrics"}) scene.erase(k);
    if (with_options) {
        scene["passes"].push_back({{"name", "sph_xsph"}, {"material", "water"}, {"properties", {{"boundary_group", "boundary"}}}});
        scene["passes"].push_back({{"name", "sph_density_summation"}, {"material", "water"},
                                   {"properties", {{"boundary_group", "boundary"}, {"normalised", true}}}});
    }
    return scene;
}

std::unique_ptr<Simulation> start(const json& scene, bool bond) {
    auto sim = std::make_unique<Simulation>(scene);
    sim->set_quiet(true);
    sim->world().parallel_min = 0;  // thread every loop, however short
    if (bond) {
        World& w = sim->world();
        w.bond(w.find_group("plate"), w.find_group("plate"), 1e-9);
    }
    return sim;
}

struct Outcome {
    std::uint64_t hash = 0;
    std::vector<std::uint64_t> breaks;  // step, ids, mode of every broken bond
    std::size_t breaks_at_k = 0;
};

std::vector<std::uint64_t> break_log(const World& w) {
    std::vector<std::uint64_t> log;
    for (const BondBreak& b : w.bond_breaks) log.insert(log.end(), {b.step, b.id1, b.id2, std::uint64_t(b.mode)});
    return log;
}

Outcome uninterrupted(const json& scene, bool bond, long n) {
    auto sim = start(scene, bond);
    sim->cycle(n);
    return {state_hash(sim->world()), break_log(sim->world()), 0};
}

// k steps, checkpoint, a new Simulation from the file, n - k more steps.
Outcome interrupted(const json& scene, bool bond, long k, long n, const std::string& file) {
    std::size_t breaks_at_k = 0;
    {
        auto sim = start(scene, bond);
        sim->cycle(k);
        breaks_at_k = sim->world().bond_breaks.size();
        sim->save_checkpoint(scratch(file).string());
    }
    auto sim = Simulation::restart(scratch(file).string());
    sim->set_quiet(true);
    sim->world().parallel_min = 0;
    REQUIRE(sim->world().step_count == std::uint64_t(k));
    sim->cycle(n - k);
    return {state_hash(sim->world()), break_log(sim->world()), breaks_at_k};
}

} // namespace

TEST_CASE("a settling pile restarted at step k reaches the uninterrupted state at step n, 2D and 3D, 1 and 2 threads",
          "[restart]") {
    ThreadsBack back;
    for (int dim : {2, 3})
        for (int threads : {1, 2}) {
            INFO(dim << "D, " << threads << " threads");
            use_threads(threads);
            const long n = dim == 2 ? 700 : 300, k = dim == 2 ? 437 : 151;
            const Outcome whole = uninterrupted(pile(dim), false, n);
            const Outcome resumed = interrupted(pile(dim), false, k, n, "pile.plab");
            CHECK(resumed.hash == whole.hash);
        }
}

TEST_CASE("a plate whose bonds break restarts bit-identically, break log included, 1 and 2 threads",
          "[restart][bonds]") {
    ThreadsBack back;
    for (int threads : {1, 2}) {
        INFO(threads << " threads");
        use_threads(threads);
        const Outcome whole = uninterrupted(breaking_plate_scene(), true, 1000);
        const Outcome resumed = interrupted(breaking_plate_scene(), true, 750, 1000, "plate.plab");
        // the stop falls while bonds are breaking: some before it, more after
        REQUIRE(resumed.breaks_at_k > 0);
        REQUIRE(whole.breaks.size() / 4 > resumed.breaks_at_k);
        CHECK(resumed.hash == whole.hash);
        CHECK(resumed.breaks == whole.breaks);
    }
}

TEST_CASE("an SPH tank restarts bit-identically (fields and the EOS pass state carried, with XSPH too), 1 and 2 threads",
          "[restart][sph]") {
    ThreadsBack back;
    for (int threads : {1, 2}) {
        INFO(threads << " threads");
        use_threads(threads);
        for (bool options : {false, true}) {
            INFO((options ? "with XSPH and the summation density filter" : "continuity only"));
            const Outcome whole = uninterrupted(tank_scene(options), false, 60);
            const Outcome resumed = interrupted(tank_scene(options), false, 27, 60, "tank.plab");
            CHECK(resumed.hash == whole.hash);
        }
    }
}

namespace {
// The oscillating plate of SPH solid particles (rows 5), free, every
// particle with a random velocity so that stresses build everywhere.
json solid_plate_scene() {
    json scene = read_scene_file(std::string(PLAB_SOURCE_DIR) + "/validation/oscillating_plate/scene.json");
    for (const char* k : {"commands", "output", "histories", "metrics"}) scene.erase(k);
    scene["variables"]["rows"] = 5;
    scene["bodies"][0]["jitter"] = {{"velocity", 0.05}, {"seed", 7}};
    return scene;
}
} // namespace

TEST_CASE("an SPH solid restarts bit-identically (its stress fields carried), and 1 and 2 threads give the same bits",
          "[restart][sph_solid]") {
    ThreadsBack back;
    std::uint64_t hash_one_thread = 0;
    for (int threads : {1, 2}) {
        INFO(threads << " threads");
        use_threads(threads);
        const Outcome whole = uninterrupted(solid_plate_scene(), false, 60);
        const Outcome resumed = interrupted(solid_plate_scene(), false, 27, 60, "solid_plate.plab");
        CHECK(resumed.hash == whole.hash);
        if (threads == 1) hash_one_thread = whole.hash;
        else CHECK(whole.hash == hash_one_thread);
    }
}

TEST_CASE("a coupled SPH-DEM scene (sedimentation) restarts bit-identically, 1 and 2 threads", "[restart][coupling]") {
    json scene = read_scene_file(std::string(PLAB_SOURCE_DIR) + "/validation/sedimentation/scene.json");
    scene.erase("commands");
    scene.erase("output");
    ThreadsBack back;
    for (int threads : {1, 2}) {
        INFO(threads << " threads");
        use_threads(threads);
        const Outcome whole = uninterrupted(scene, false, 40);
        const Outcome resumed = interrupted(scene, false, 17, 40, "coupled.plab");
        CHECK(resumed.hash == whole.hash);
    }
}

TEST_CASE("a run stopped by a signal mid-command writes a checkpoint from which the commands finish identically",
          "[restart]") {
    json scene = pile();
    scene["histories"] = {{"every", 50}, {"record", {{{"quantity", "time"}}, {{"name", "ke"}, {"quantity", "energy.kinetic"}}}}};
    scene["commands"] = {{{"cycle", 300}}, {{"set", {{"gravity", {0, -4.0}}}}}, {{"solve", {{"time", 0.02}}}}};
    const fs::path whole_dir = scratch("whole"), cut_dir = scratch("cut");
    // both first settle 400 steps outside the commands, so the stop falls
    // among contacts (where a force recomputed after restart would differ)
    Simulation whole(scene);
    whole.set_quiet(true);
    whole.set_output_dir(whole_dir.string());
    whole.cycle(400);
    whole.run();
    REQUIRE_FALSE(whole.interrupted());

    Simulation cut(scene);
    cut.set_quiet(true);
    cut.set_output_dir(cut_dir.string());
    cut.cycle(400);
    REQUIRE(active_contacts(cut.world()) > 0);
    request_stop(SIGTERM);  // as if the signal came during the first step of the commands
    cut.run();
    clear_stop();
    REQUIRE(cut.interrupted());
    CHECK(cut.world().step_count == 401);
    auto resumed = Simulation::restart(cut.checkpoint_path());
    resumed->set_quiet(true);
    resumed->run();
    CHECK_FALSE(resumed->interrupted());
    CHECK(resumed->world().step_count == whole.world().step_count);
    CHECK(state_hash(resumed->world()) == state_hash(whole.world()));
    CHECK(resumed->history_rows() == whole.history_rows());  // histories continue, none lost or doubled
}

TEST_CASE("periodic checkpoints of a run restart to the same final state", "[restart]") {
    json scene = pile();
    scene["timestep"] = {{"fixed", 5e-4}};  // 500 steps: the grains land and touch
    scene["commands"] = {{{"cycle", 500}}};
    Simulation whole(scene);
    whole.set_quiet(true);
    whole.set_output_dir(scratch("periodic").string());
    whole.set_checkpoint_every(300 * 5e-4);  // one checkpoint, near step 300
    whole.run();
    auto resumed = Simulation::restart(whole.checkpoint_path());
    resumed->set_quiet(true);
    const std::uint64_t k = resumed->world().step_count;
    CHECK(k >= 299);
    CHECK(k <= 301);
    resumed->run();
    CHECK(resumed->world().step_count == 500);
    CHECK(state_hash(resumed->world()) == state_hash(whole.world()));
}

namespace {

std::string restart_error(const fs::path& p) {
    try {
        Simulation::restart(p.string());
    } catch (const std::exception& e) {
        return e.what();
    }
    return "<loaded>";
}
std::uint64_t u64_at(const std::string& bytes, std::size_t at) {
    std::uint64_t v = 0;
    std::memcpy(&v, bytes.data() + at, sizeof v);
    return v;
}
std::uint32_t crc_of(std::uint32_t crc, const std::string& bytes, std::size_t at, std::size_t n) {
    return std::uint32_t(crc32_z(crc, reinterpret_cast<const Bytef*>(bytes.data() + at), n));
}
// Every CRC-32 of a checkpoint made to match its bytes again (the layout of
// checkpoint.hpp): a file changed on purpose, to reach the checks behind them.
std::string resealed(std::string bytes) {
    std::uint32_t crc = crc_of(0, bytes, 0, 16);
    std::memcpy(&bytes[16], &crc, sizeof crc);
    for (std::size_t at = 20; at < bytes.size();) {
        const std::size_t contents = at + 16 + u64_at(bytes, at), length = u64_at(bytes, contents - 8);
        REQUIRE(contents + length + 4 <= bytes.size());
        crc = crc_of(crc_of(0, bytes, contents, length), bytes, at, contents - at);
        std::memcpy(&bytes[contents + length], &crc, sizeof crc);
        at = contents + length + 4;
    }
    return bytes;
}
// Replaces the first occurrence of `from` by `to` (same length), checksums
// made to match.
std::string patched(std::string bytes, const std::string& from, const std::string& to) {
    const auto at = bytes.find(from);
    REQUIRE(at != std::string::npos);
    REQUIRE(from.size() == to.size());
    return resealed(bytes.replace(at, from.size(), to));
}

} // namespace

TEST_CASE("a checkpoint that cannot load says why: foreign, newer, damaged, truncated, missing plug-in, lost history slot",
          "[restart][errors]") {
    const fs::path good = scratch("good.plab");
    {
        auto sim = start(pile(), false);
        sim->cycle(20);
        sim->save_checkpoint(good.string());
    }
    const std::string bytes = slurp(good);
    REQUIRE(restart_error(good) == "<loaded>");

    const fs::path bad = scratch("bad.plab");
    spit(bad, "{\"dimension\": 2}");
    CHECK_THAT(restart_error(bad), Contains("is not a plab checkpoint"));

    std::string newer = bytes;
    newer[8] = char(kCheckpointFormat + 1);
    spit(bad, resealed(newer));
    CHECK_THAT(restart_error(bad), Contains("format version " + std::to_string(kCheckpointFormat + 1)) &&
                                       Contains("newer than this plab reads"));
    spit(bad, newer);  // the version's bit flipped: the header's CRC-32 is of the true one
    CHECK_THAT(restart_error(bad), Contains("the header is damaged (format version " +
                                            std::to_string(kCheckpointFormat + 1) + " where its CRC-32 says " +
                                            std::to_string(kCheckpointFormat) + ")"));

    std::string swapped = bytes;
    std::reverse(swapped.begin() + 12, swapped.begin() + 16);
    spit(bad, swapped);
    CHECK_THAT(restart_error(bad), Contains("other byte order"));

    std::string damaged = bytes;
    damaged[bytes.find(std::string("\x06\0\0\0\0\0\0\0bodies", 14)) + 200] ^= 4;  // in the bodies' columns
    spit(bad, damaged);
    CHECK_THAT(restart_error(bad), Contains("section 'bodies' is damaged (CRC-32 mismatch: stored 0x"));

    spit(bad, bytes.substr(0, bytes.size() / 2));
    CHECK_THAT(restart_error(bad), Contains("ends early") || Contains("runs past the end"));

    spit(bad, patched(bytes, "linear", "lineaz"));
    CHECK_THAT(restart_error(bad), Contains("needs plug-in 'lineaz'") && Contains("model linear") &&
                                       Contains("not found"));

    spit(bad, patched(bytes, "shear_force_y", "shear_force_q"));
    CHECK_THAT(restart_error(bad), Contains("history slot 'shear_force_q' of model 'linear'") &&
                                       Contains("shear_force_x, shear_force_y, shear_force_z"));
}

namespace {

// The checkpoint as format 2 wrote it: no header CRC, sections without
// lengths and CRCs, and none of the sections of later formats (clumps, flows, periodic_cell).
std::string as_format_2(const std::string& bytes) {
    std::string out = bytes.substr(0, 16);
    const std::uint32_t two = 2;
    std::memcpy(&out[8], &two, sizeof two);
    for (std::size_t at = 20; at < bytes.size();) {
        const std::size_t name = 8 + u64_at(bytes, at), length = u64_at(bytes, at + name);
        bool later = false;
        for (const char* s : {"clumps", "flows", "periodic_cell"}) later |= bytes.compare(at + 8, name - 8, s) == 0;
        if (!later) out += bytes.substr(at, name) + bytes.substr(at + name + 8, length);
        at += name + 8 + length + 4;
    }
    return out;
}

} // namespace

TEST_CASE("a checkpoint of format 2 (no checksums) still restarts to the same state", "[restart]") {
    const fs::path file = scratch("v3.plab"), old = scratch("v2.plab");
    {
        auto sim = start(pile(), false);
        sim->cycle(300);
        sim->save_checkpoint(file.string());
    }
    spit(old, as_format_2(slurp(file)));
    std::uint64_t hash[2] = {0, 0};
    for (int v = 0; v < 2; ++v) {
        auto sim = Simulation::restart((v ? old : file).string());
        sim->set_quiet(true);
        sim->cycle(100);
        hash[v] = state_hash(sim->world());
    }
    CHECK(hash[1] == hash[0]);
}

TEST_CASE("a run that goes unstable leaves its last good state as a checkpoint that a smaller timestep finishes",
          "[restart][stability]") {
    json scene = pile();
    // planes hold the grains in, so a timestep 3x the stable limit blows up
    // instead of letting them fly away
    scene["walls"] = {{{"type", "plane"}, {"point", {0, 0}}, {"normal", {0, 1}}},
                      {{"type", "plane"}, {"point", {0, 0}}, {"normal", {1, 0}}},
                      {{"type", "plane"}, {"point", {0.1, 0}}, {"normal", {-1, 0}}},
                      {{"type", "plane"}, {"point", {0, 0.2}}, {"normal", {0, -1}}}};
    scene["timestep"] = {{"fixed", 4e-3}, {"allow_unstable", true}};
    scene["commands"] = {{{"cycle", 3000}}};
    Simulation sim(scene);
    sim.set_quiet(true);
    sim.set_output_dir(scratch("unstable").string());
    // the NaN check fires late (positions ~1e200 by then): keep the start as
    // the last good state, so the restart begins from a state worth keeping
    sim.world().snapshot_interval = 1000;
    std::string message;
    try {
        sim.run();
    } catch (const RunError& e) {
        message = e.what();
    }
    REQUIRE_THAT(message, Contains("last good state is saved in") && Contains("plab restart") &&
                              Contains("--set timestep.fixed=0.002"));
    const std::string file = (scratch("unstable") / "last_good.plab").string();
    auto resumed = Simulation::restart(file, {"timestep.fixed=2e-4", "timestep.allow_unstable=false"});
    resumed->set_quiet(true);
    CHECK(resumed->world().step_count == 0);
    resumed->run();  // finishes the cycle command: 3000 steps in all
    CHECK(resumed->world().step_count == 3000);
    CHECK(resumed->world().energies.kinetic < 1.0);  // settled, not blown up
}
