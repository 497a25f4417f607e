// A damaged checkpoint never restarts into a wrong state (issue 38, item 2):
// single bits flipped all over a checkpoint, a few in every section and in
// the header, each either refused with a CheckpointError that names the
// damaged part, or harmless (the restart ends in the undamaged restart's
// state). A flip that restarts and ends anywhere else is a silent wrong
// restart, and there must be none.
#include "simulation.hpp"
#include "../core/settling_scene.hpp"

#include <plab_host/checkpoint.hpp>

#include "../support/file_bytes.hpp"

#include <catch2/catch.hpp>

#include <condition_variable>
#include <csignal>
#include <cstring>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <random>
#include <thread>
#include <unistd.h>

using namespace plab;
namespace fs = std::filesystem;

namespace {

using testing_support::slurp;
using testing_support::spit;

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("plab_damage_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir / name;
}

// A part of the file: the header, or one section from its name to the next.
struct Region {
    std::string name;
    std::size_t begin = 0, end = 0;
};

// The sections in file order, each found by its name as written (a u64
// length, then the characters), searched from where the one before began.
std::vector<Region> regions_of(const std::string& bytes) {
    static const char* names[] = {"plugins", "scene",  "world",       "assignment", "bodies",   "walls",
                                  "fields",  "contacts", "detection", "passes",     "bond_breaks", "rng",
                                  "stability", "clumps", "periodic_cell", "commands", "outputs", "flows", "end"};
    std::vector<Region> out{{"header", 0, 0}};
    std::size_t from = 0;
    for (const char* name : names) {
        const std::uint64_t n = std::strlen(name);
        const std::string tag = std::string(reinterpret_cast<const char*>(&n), sizeof n) + name;
        const std::size_t at = bytes.find(tag, from);
        INFO("section " << name);
        REQUIRE(at != std::string::npos);
        out.back().end = at;
        out.push_back({name, at, bytes.size()});
        from = at;
    }
    return out;
}

// Asks a run to stop (as SIGTERM would) if it is still going after
// `seconds`: a damaged command state must not hang the test.
class Watchdog {
public:
    explicit Watchdog(double seconds)
        : thread_([this, seconds] {
              std::unique_lock<std::mutex> lock(m_);
              if (!cv_.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return done_; })) request_stop(SIGTERM);
          }) {}
    ~Watchdog() {
        {
            std::lock_guard<std::mutex> lock(m_);
            done_ = true;
        }
        cv_.notify_one();
        thread_.join();
        clear_stop();
    }

private:
    std::mutex m_;
    std::condition_variable cv_;
    bool done_ = false;
    std::thread thread_;
};

enum class Outcome { refused, harmless, silent_wrong, other_error };

struct Restarted {
    Outcome outcome;
    std::string message;
};

// Restarts from `file` and runs the rest of its commands; `reference` is the
// final state hash of the undamaged restart (0: this is that restart).
Restarted restart_and_finish(const fs::path& file, std::uint64_t reference, std::uint64_t* hash,
                             const std::shared_ptr<PluginHost>& host) {
    try {
        auto sim = Simulation::restart(file.string(), {}, host);
        sim->set_quiet(true);
        sim->set_output_dir("");  // write nothing
        Watchdog dog(10.0);
        sim->run();
        if (hash) *hash = state_hash(sim->world());
        if (sim->interrupted()) return {Outcome::silent_wrong, "ran on past its end (stopped by the watchdog)"};
        return {state_hash(sim->world()) == reference ? Outcome::harmless : Outcome::silent_wrong, ""};
    } catch (const CheckpointError& e) {
        return {Outcome::refused, e.what()};
    } catch (const std::exception& e) {
        return {Outcome::other_error, e.what()};
    }
}

struct Tally {
    int refused = 0, harmless = 0, silent_wrong = 0, other_error = 0;
};

// Writes a checkpoint of `scene` after `k` cycles, then flips `flips` single
// bits, the same number in each region (deterministic seed), and restarts
// from each damaged copy. Prints the outcomes per region.
void flip_bits(const std::string& label, const json& scene, long k, int flips) {
    const auto host = std::make_shared<PluginHost>();
    const fs::path good = scratch(label + ".plab"), bad = scratch(label + "_damaged.plab");
    {
        Simulation sim(scene, ".", host);
        sim.set_quiet(true);
        sim.cycle(k);
        sim.save_checkpoint(good.string());
    }
    std::uint64_t reference = 0;
    const Restarted undamaged = restart_and_finish(good, 0, &reference, host);
    REQUIRE(undamaged.message.empty());
    const std::string bytes = slurp(good);
    const std::vector<Region> regions = regions_of(bytes);

    std::mt19937_64 rng(38);
    std::map<std::string, Tally> tally;
    int silent = 0, other = 0;
    for (int f = 0; f < flips; ++f) {
        const Region& r = regions[std::size_t(f) % regions.size()];
        const std::uint64_t bit = std::uniform_int_distribution<std::uint64_t>(8 * r.begin, 8 * r.end - 1)(rng);
        std::string damaged = bytes;
        damaged[bit / 8] = char(damaged[bit / 8] ^ (1 << (bit % 8)));
        spit(bad, damaged);
        const Restarted got = restart_and_finish(bad, reference, nullptr, host);
        Tally& t = tally[r.name];
        INFO(label << ": bit " << bit << " (byte " << bit / 8 << ", region '" << r.name << "'): " << got.message);
        switch (got.outcome) {
        case Outcome::refused:
            ++t.refused;
            // the message names the damaged part: the section, or the file for its header
            CHECK_THAT(got.message, Catch::Matchers::Contains(r.name == "header" ? bad.string() : "'" + r.name + "'"));
            break;
        case Outcome::harmless: ++t.harmless; break;
        case Outcome::silent_wrong: ++t.silent_wrong; ++silent; break;
        case Outcome::other_error: ++t.other_error; ++other; break;
        }
        CHECK(got.outcome != Outcome::silent_wrong);
        CHECK(got.outcome != Outcome::other_error);
    }
    std::printf("%s: %d bit flips in a %zu-byte checkpoint\n%-12s %8s %8s %8s %8s\n", label.c_str(), flips, bytes.size(),
                "region", "refused", "harmless", "wrong", "other");
    for (const Region& r : regions) {
        const Tally& t = tally[r.name];
        std::printf("%-12s %8d %8d %8d %8d\n", r.name.c_str(), t.refused, t.harmless, t.silent_wrong, t.other_error);
    }
    CHECK(silent == 0);
    CHECK(other == 0);
}

} // namespace

TEST_CASE("300 single-bit flips over every section of a pile's checkpoint: each refused by name or harmless",
          "[restart][damage]") {
    json scene = settling_scene(2, 150);
    scene["timestep"] = {{"fixed", 5e-4}};
    scene["histories"] = {{"every", 50}, {"record", {{{"quantity", "time"}}, {{"name", "ke"}, {"quantity", "energy.kinetic"}}}}};
    scene["commands"] = {{{"cycle", 200}}, {{"set", {{"gravity", {0, -4.0}}}}}, {{"cycle", 100}}};
    flip_bits("pile", scene, 300, 300);  // the grains have landed: contacts with shear history
}

TEST_CASE("300 single-bit flips over every section of an SPH tank's checkpoint: each refused by name or harmless",
          "[restart][damage][sph]") {
    json scene = read_scene_file(std::string(PLAB_SOURCE_DIR) + "/validation/static_tank/scene.json");
    for (const char* k : {"output", "histories", "metrics"}) scene.erase(k);
    scene["variables"]["columns"] = 8;
    scene["variables"]["rows"] = 8;
    scene["commands"] = {{{"cycle", 30}}};
    flip_bits("tank", scene, 20, 300);  // fields and the EOS pass's private state
}
