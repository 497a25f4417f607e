// Contact detection finds exactly the overlapping pairs, and per-contact
// history survives re-detection by the ids of the two ends.
#include "simulation.hpp"
#include "contacts/contact_keys.hpp"
#include "world/cycle.hpp"  // (a test of the contact tables inside the kernel)

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>

using namespace plab;

namespace {

json pile(int dim) {
    auto v = [dim](double x, double y, double z) { return dim == 2 ? json::array({x, y}) : json::array({x, y, z}); };
    return {{"dimension", dim},
            {"plugins", {"linear"}},
            {"gravity", v(0, -9.81, 0)},
            {"skin", 0.0005},
            {"bodies", {{{"type", "random_fill"}, {"box", {{"min", v(0, 0, 0)}, {"max", v(0.08, 0.08, 0.08)}}},
                         {"radius", {0.002, 0.005}}, {"density", 2500}, {"count", dim == 2 ? 150 : 300}, {"seed", 5}}}},
            {"walls", {{{"type", "box"}, {"min", v(0, 0, 0)}, {"max", v(0.08, 0.2, 0.08)}}}},
            {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"},
                                 {"properties", {{"kn", 1e4}, {"ks", 1e4}, {"fric", 0.4}, {"dp_nratio", 0.3}}}}}}};
}

std::size_t brute_force_overlaps(const World& w) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < w.bodies.size(); ++i)
        for (std::size_t j = i + 1; j < w.bodies.size(); ++j)
            n += (w.bodies.position[i] - w.bodies.position[j]).norm() < w.bodies.radius[i] + w.bodies.radius[j];
    return n;
}

} // namespace

TEST_CASE("the cell list with a skin finds every overlapping pair, every step", "[detection]") {
    for (int dim : {2, 3}) {
        Simulation sim(pile(dim));
        sim.set_quiet(true);
        World& w = sim.world();
        std::size_t checked = 0, max_contacts = 0;
        for (int s = 0; s < 3000; ++s) {
            w.step();
            if (s % 25) continue;
            std::size_t active = 0;
            for (std::uint8_t a : w.cycle->instances[0]->balls.active) active += a;
            INFO("dim " << dim << " step " << s);
            REQUIRE(active == brute_force_overlaps(w));
            max_contacts = std::max(max_contacts, active);
            ++checked;
        }
        CHECK(max_contacts > 50);  // the pile really formed contacts
        CHECK(rebuilds(w) > 10);    // and the lists were rebuilt on the way
    }
}

TEST_CASE("shear-force history survives a neighbour-list rebuild", "[detection]") {
    Simulation sim(pile(2));
    sim.set_quiet(true);
    World& w = sim.world();
    sim.cycle(2000);
    const ContactSet& s = w.cycle->instances[0]->balls;
    std::map<std::pair<BodyId, BodyId>, double> before;
    for (std::size_t k = 0; k < s.size(); ++k)
        if (s.active[k]) before[row_key(w.bodies, w.walls, s, k)] = s.history[3 * k] + 2 * s.history[3 * k + 1];
    REQUIRE(before.size() > 20);
    w.mark_dirty();  // force a rebuild: rows are re-created and re-sorted
    w.prepare();
    std::size_t matched = 0;
    for (std::size_t k = 0; k < s.size(); ++k) {
        auto it = before.find(row_key(w.bodies, w.walls, s, k));
        if (it == before.end()) continue;
        // the re-evaluation re-projects the shear force: equal to rounding, not reset
        CHECK(s.history[3 * k] + 2 * s.history[3 * k + 1] == Approx(it->second).epsilon(1e-12));
        ++matched;
    }
    CHECK(matched == before.size());
}

TEST_CASE("the null model and unassigned group pairs create no contacts", "[detection]") {
    json scene = pile(2);
    scene["bodies"][0]["group"] = "grains";
    scene["contact_models"].push_back({{"groups", {"grains", "grains"}}, {"model", "null"}});
    Simulation sim(scene);
    sim.set_quiet(true);
    sim.cycle(500);
    CHECK(sim.world().cycle->instances[0]->balls.size() == 0);  // no candidate pairs at all: no cost
    CHECK(sim.world().cycle->instances[0]->walls.size() > 0);   // walls still assigned by "*"
}

TEST_CASE("the coordination-number pass counts the contacts of each ball", "[detection][pass]") {
    // a hexagonal packing of touching discs pressed by gravity: interior discs have 6 contacts
    json scene = {{"dimension", 2},
                  {"plugins", {"linear", "coordination_number"}},
                  {"gravity", {0, -9.81}},
                  {"bodies", {{{"type", "lattice"}, {"packing", "hexagonal"}, {"box", {{"min", {0, 0}}, {"max", {0.1, 0.05}}}},
                               {"radius", 0.005}, {"density", 2500}}}},
                  {"walls", {{{"type", "box"}, {"min", {0, 0}}, {"max", {0.1, 0.2}}}}},
                  {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"}, {"properties", {{"kn", 1e6}}}}}},
                  {"passes", {{{"name", "coordination_number"}}}}};
    Simulation sim(scene);
    sim.set_quiet(true);
    World& w = sim.world();
    w.fixed_dt = 1e-5;
    sim.cycle(3000);
    const int field = w.fields.index("coordination_number");
    REQUIRE(field >= 0);
    std::vector<double> expected(w.bodies.size(), 0.0);
    const ContactSet& s = w.cycle->instances[0]->balls;
    for (std::size_t k = 0; k < s.size(); ++k)
        if (s.active[k]) { expected[s.end1[k]] += 1; expected[s.end2[k]] += 1; }
    const ContactSet& walls = w.cycle->instances[0]->walls;
    for (std::size_t k = 0; k < walls.size(); ++k)
        if (walls.active[k]) expected[walls.end1[k]] += 1;
    CHECK(w.fields.column(field) == expected);
    CHECK(*std::max_element(expected.begin(), expected.end()) == 6);
}

// A settled pile whose contacts follow field_probe (tests/plugins).
json field_probe_pile() {
    json scene = pile(2);
    scene["plugins"].push_back(std::string(PLAB_TEST_PLUGIN_DIR) + "/field_probe.so");
    scene["contact_models"] = {{{"groups", {"*", "*"}}, {"model", "field_probe"}, {"properties", {{"k", 1e5}}}}};
    return scene;
}

TEST_CASE("a contact model reads body fields and accumulates into them through its batch", "[detection][fields]") {
    Simulation sim(field_probe_pile());
    sim.set_quiet(true);
    World& w = sim.world();
    sim.cycle(2000);
    const int value = w.fields.index("probe_value"), sum = w.fields.index("probe_sum");
    REQUIRE(value >= 0);
    REQUIRE(sum >= 0);
    for (std::size_t i = 0; i < w.bodies.size(); ++i) w.fields.column(value)[i] = double(i);
    sim.cycle(1);
    std::vector<double> expected(w.bodies.size(), 0.0);
    const ContactSet& s = w.cycle->instances[0]->balls;
    for (std::size_t k = 0; k < s.size(); ++k)
        if (s.active[k]) {
            expected[s.end1[k]] += s.end2[k];
            expected[s.end2[k]] += s.end1[k];
        }
    // a ball touching a wall gets NaN: reading a wall end's body field is loud, not silently wrong
    const ContactSet& wl = w.cycle->instances[0]->walls;
    for (std::size_t k = 0; k < wl.size(); ++k)
        if (wl.active[k]) expected[wl.end1[k]] = std::nan("");
    for (std::size_t i = 0; i < expected.size(); ++i) {
        INFO("ball " << i);
        if (std::isnan(expected[i])) CHECK(std::isnan(w.fields.column(sum)[i]));
        else CHECK(w.fields.column(sum)[i] == expected[i]);
    }
    CHECK(std::count_if(expected.begin(), expected.end(), [](double x) { return x > 0; }) > 10);
}

// ABI 7: body_fields_at_default lets a model skip gathering a field that
// holds its default everywhere (SPH's wall velocity corrections without a
// wall pass); a claim must be true, and must go the moment a value leaves it.
TEST_CASE("the batch says which read fields hold their default, and says it no longer once a value leaves it",
          "[detection][fields]") {
    Simulation sim(field_probe_pile());
    sim.set_quiet(true);
    World& w = sim.world();
    sim.cycle(2000);
    const int value = w.fields.index("probe_value"), claims = w.fields.index("probe_claims");
    REQUIRE(claims >= 0);
    const auto claimed = [&] {
        double sum = 0;
        for (double c : w.fields.column(claims)) sum += c;
        return sum;
    };
    const auto touching = [&] {
        std::size_t n = 0;
        for (const ContactSet* s : {&w.cycle->instances[0]->balls, &w.cycle->instances[0]->walls})
            for (std::size_t k = 0; k < s->size(); ++k) n += s->active[k] != 0;
        return double(n);
    };
    sim.cycle(1);  // nothing writes probe_value and it is 2.0 (its default) everywhere: claimed on every contact
    REQUIRE(touching() > 10);
    CHECK(claimed() == touching());
    w.fields.column(value)[3] = 2.5;  // one value set from outside: no claim from the next force pass on
    sim.cycle(1);
    CHECK(claimed() == 0.0);
    w.fields.column(value)[3] = 2.0;  // back at the default everywhere: claimed again
    sim.cycle(1);
    CHECK(claimed() == touching());
}

#include "forces/row_lists.hpp"
#include <random>

// The lists of flagged rows (the range test's in-range and just-left lists,
// the active rows of scatter and geometry): every length around the vector
// width, flags at random, rows and values in order; nothing written past n.
TEST_CASE("the list of flagged rows holds exactly the flagged rows in order, with their values", "[detection]") {
    std::mt19937 rng(7);
    for (std::size_t n : {0u, 1u, 15u, 16u, 17u, 31u, 32u, 33u, 255u, 256u}) {
        for (double p : {0.0, 0.3, 0.7, 1.0}) {
            std::bernoulli_distribution on(p);
            std::vector<std::uint8_t> flag(n);
            std::vector<double> value(n);
            for (std::size_t r = 0; r < n; ++r) { flag[r] = on(rng); value[r] = 0.5 * double(r) - 3.0; }
            std::vector<std::uint32_t> out(n + 1, 0xdeadbeef);
            std::vector<double> value_out(n + 1, -1.0);
            const std::size_t count = list_flagged_rows(flag.data(), n, 1000, out.data(), value.data(), value_out.data());
            std::size_t expected = 0;
            for (std::size_t r = 0; r < n; ++r) {
                if (!flag[r]) continue;
                REQUIRE(out[expected] == 1000 + r);
                REQUIRE(value_out[expected] == value[r]);
                ++expected;
            }
            REQUIRE(count == expected);
            CHECK(out[n] == 0xdeadbeef);  // the guard past n is untouched
            CHECK(value_out[n] == -1.0);
        }
    }
}
