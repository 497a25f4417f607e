// The host turns the history a model declares tangential (abi.h,
// PLAB_HISTORY_TANGENTIAL) into each contact's current plane before the law
// reads it, on every path a batch takes, keeping the vector's magnitude.
#include "simulation.hpp"

#include <forces/tangential_history.hpp>
#include <plab/contact_model.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

using namespace plab;
namespace fs = std::filesystem;

namespace {

// A packing of touching balls pressed by gravity into a box, its contacts
// following one of the probes of tests/plugins/tangential_probe.cpp.
json probe_pile(int dim, const std::string& model) {
    auto v = [dim](double x, double y, double z) { return dim == 2 ? json::array({x, y}) : json::array({x, y, z}); };
    return {{"dimension", dim},
            {"plugins", {std::string(PLAB_TEST_PLUGIN_DIR) + "/tangential_probe.so"}},
            {"gravity", v(0, -9.81, 0)},
            {"bodies", {{{"type", "lattice"}, {"packing", dim == 2 ? "hexagonal" : "hcp"},
                         {"box", {{"min", v(0, 0, 0)}, {"max", v(0.1, 0.05, 0.04)}}}, {"radius", 0.005},
                         {"density", 2500}}}},
            {"walls", {{{"type", "box"}, {"min", v(0, 0, 0)}, {"max", v(0.1, 0.2, 0.04)}}}},
            {"contact_models", {{{"groups", {"*", "*"}}, {"model", model}, {"properties", {{"k", 1e5}}}}}}};
}

// In the rows of s in contact for a second step or more, what the law read
// of the vector it stored the step before (magnitude `stored`, out of the
// plane): in the plane, with that magnitude. Returns how many rows it saw.
std::size_t check_rows(const ContactTable& s, double stored) {
    enum { vec_x, vec_y, vec_z, seen_along_normal, seen_magnitude };
    std::size_t seen = 0;
    for (std::size_t k = 0; k < s.size(); ++k) {
        const double* h = s.history(k);
        if (!s.active(k) || h[seen_magnitude] == 0.0) continue;  // (first touch: the default, zero)
        INFO("row " << k);
        CHECK(std::fabs(h[seen_along_normal]) <= 1e-12 * stored);
        CHECK(h[seen_magnitude] == Approx(stored).epsilon(1e-12));
        ++seen;
    }
    return seen;
}

} // namespace

TEST_CASE("a tangential history vector reaches the law in the current contact plane with its magnitude",
          "[forces][history]") {
    for (const char* model : {"tangential_probe", "tangential_probe_centres", "tangential_probe_summed"})
        for (int dim : {2, 3}) {
            INFO("model " << model << ", dim " << dim);
            Simulation sim(probe_pile(dim, model));
            sim.set_quiet(true);
            sim.cycle(200);
            const ModelView inst = sim.world().model(0);
            const double stored = dim == 3 ? 1.3 : 0.5;  // |(0.3, -0.4, 1.2)|, |(0.3, -0.4, 0)|
            CHECK(check_rows(inst.balls(), stored) > 50);  // (packed, centre-force or full columns, by model)
            CHECK(check_rows(inst.walls(), stored) > 5);   // (full columns)
        }
}

TEST_CASE("the host's turn of tangential history: in the plane, magnitude kept, zero kept, only active rows",
          "[forces][history]") {
    const plab_history_desc slots[] = {
        plab::history_desc("state", 0.0, PLAB_SWAP_KEEP, "a scalar before the vector"),
        plab::history_desc("f_x", 0.0, PLAB_SWAP_NEGATE, "x", PLAB_HISTORY_TANGENTIAL),
        plab::history_desc("f_y", 0.0, PLAB_SWAP_NEGATE, "y"), plab::history_desc("f_z", 0.0, PLAB_SWAP_NEGATE, "z")};
    plab_contact_model_desc d{};
    d.history = slots;
    d.history_count = 4;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    const std::size_t n = 40;
    std::vector<double> history(4 * n), normal(3 * n);
    std::vector<std::uint8_t> active(n);
    for (std::size_t a = 0; a < n; ++a) {
        const Vec nv = Vec(u(rng), u(rng), u(rng)).normalized();
        for (int c = 0; c < 3; ++c) normal[3 * a + c] = nv[c];
        for (int c = 0; c < 4; ++c) history[4 * a + c] = u(rng);
        active[a] = a % 3 != 0;
    }
    for (int c = 1; c < 4; ++c) history[4 * 1 + c] = 0.0;  // a zero vector
    normal[3 * 2] = normal[3 * 2 + 1] = 0.0;                 // one along the normal, nothing of it in the plane
    normal[3 * 2 + 2] = 1.0;
    history[4 * 2 + 1] = history[4 * 2 + 2] = 0.0;
    history[4 * 2 + 3] = 2.0;
    const std::vector<double> before = history;
    turn_tangential_history(d, history.data(), 4, normal.data(), active.data(), n);
    for (std::size_t a = 0; a < n; ++a) {
        INFO("row " << a);
        const Vec old(&before[4 * a + 1]), now(&history[4 * a + 1]), nv(&normal[3 * a]);
        CHECK(history[4 * a] == before[4 * a]);  // the scalar slot is not touched
        if (!active[a]) {
            CHECK(now == old);
            continue;
        }
        if (a == 1 || a == 2) {
            CHECK(now == Vec::Zero());  // zero stays zero; along the normal has no part in the plane
            continue;
        }
        CHECK(std::fabs(now.dot(nv)) <= 1e-14 * old.norm());
        CHECK(now.norm() == Approx(old.norm()).epsilon(1e-14));
        CHECK((now - (old - old.dot(nv) * nv)).norm() <= old.norm() * std::fabs(old.normalized().dot(nv)) + 1e-15);
    }
}

TEST_CASE("plab plugins --describe names the tangential history a model declares", "[forces][history][cli]") {
    const fs::path out = fs::temp_directory_path() / "plab_describe_linear.txt";
    const std::string cmd = std::string(PLAB_EXE) + " plugins --describe linear > " + out.string() + " 2>&1";
    REQUIRE(std::system(cmd.c_str()) == 0);
    std::ifstream f(out);
    std::string line, x_line, y_line;
    while (std::getline(f, line)) {
        if (line.find("shear_force_x (") != std::string::npos) x_line = line;
        if (line.find("shear_force_y (") != std::string::npos) y_line = line;
    }
    fs::remove(out);
    INFO(x_line << "\n" << y_line);
    CHECK(x_line.find("a vector in the contact plane, turned with it by the host") != std::string::npos);
    CHECK(!y_line.empty());
    CHECK(y_line.find("contact plane") == std::string::npos);  // (the flag is on the vector's first slot only)
}

namespace {

// A settling pile bouncing in its box, following one of the probes of
// tests/plugins/active_rows_probe.cpp: contacts made, lost and made again.
json bouncing_probe_pile(int dim, const std::string& model) {
    json scene = probe_pile(dim, model);
    scene["plugins"] = {std::string(PLAB_TEST_PLUGIN_DIR) + "/active_rows_probe.so"};
    scene["bodies"][0]["velocity"] = dim == 2 ? json::array({0.0, -0.5}) : json::array({0.0, -0.5, 0.0});
    return scene;
}

// Rows of s out of range whose history is not back at its default (0), and
// rows in range, counted.
struct RowsSeen { std::size_t remembered = 0, out_of_range = 0, in_range = 0; };
RowsSeen check_forgotten(const ContactTable& s) {
    RowsSeen r;
    for (std::size_t k = 0; k < s.size(); ++k) {
        if (s.active(k)) { ++r.in_range; continue; }
        ++r.out_of_range;
        r.remembered += s.history(k)[0] != 0.0;
    }
    return r;
}

} // namespace

TEST_CASE("every batch reaches its model with active rows only, and a separated contact's history is forgotten",
          "[forces][history]") {
    for (const char* model : {"active_rows_probe", "active_rows_probe_centres", "active_rows_probe_summed"})
        for (int dim : {2, 3}) {
            INFO("model " << model << ", dim " << dim);
            Simulation sim(bouncing_probe_pile(dim, model));
            sim.set_quiet(true);
            RowsSeen balls, walls;
            for (int c = 0; c < 20; ++c) {
                sim.cycle(50);  // (an inactive row in a batch would give a NaN force: a RunError)
                const ModelView inst = sim.world().model(0);
                for (auto [seen, table] : {std::pair{&balls, inst.balls()}, std::pair{&walls, inst.walls()}}) {
                    const RowsSeen now = check_forgotten(table);
                    seen->remembered += now.remembered;
                    seen->out_of_range += now.out_of_range;
                    seen->in_range += now.in_range;
                }
            }
            CHECK(balls.remembered == 0);
            CHECK(walls.remembered == 0);
            CHECK(balls.out_of_range > 100);  // (candidates out of range, and contacts, on both kinds)
            CHECK(walls.out_of_range > 10);
            CHECK(balls.in_range > 100);
            CHECK(walls.in_range > 10);
        }
}
