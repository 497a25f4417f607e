// Balls removed during a run (remove_bodies, the outlet's kernel
// operation): the others keep their ids, order and contact history, so a
// pile far from the balls removed moves as if those had never been there.
// (A removal re-evaluates the forces at the state it leaves, as any change
// of the scene does, World::mark_dirty: the run without them does too.)
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <cstring>

using namespace plab;
using nlohmann::json;

namespace {

// Two piles settling on a floor 0.5 m apart, linear springs with friction
// and dashpots. `with_second`: the second pile too.
json two_piles(int dim, bool with_second) {
    auto v = [dim](double x, double y, double z) { return dim == 2 ? json::array({x, y}) : json::array({x, y, z}); };
    auto pile = [&](double x0, const char* group) {
        return json{{"type", "random_fill"}, {"group", group}, {"box", {{"min", v(x0, 0, 0)}, {"max", v(x0 + 0.05, 0.05, 0.05)}}},
                    {"radius", {0.002, 0.003}}, {"density", 2500}, {"count", dim == 2 ? 60 : 150}, {"seed", 5}};
    };
    json scene = {{"dimension", dim},
                  {"plugins", {"linear"}},
                  {"gravity", v(0, -9.81, 0)},
                  {"timestep", {{"fixed", 2e-5}}},
                  {"bodies", {pile(0.0, "first")}},
                  {"walls", {{{"type", "plane"}, {"point", v(0, 0, 0)}, {"normal", v(0, 1, 0)}}}},
                  {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"},
                                       {"properties", {{"kn", 1e4}, {"ks", 5e3}, {"fric", 0.5}, {"dp_nratio", 0.3}}}}}}};
    if (with_second) scene["bodies"].push_back(pile(0.5, "second"));
    return scene;
}

std::uint64_t bits(double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
}

} // namespace

TEST_CASE("balls removed mid-run: the rest keep ids, order and history, and move as if the removed were never there",
          "[bodies][removal]") {
    for (int dim : {2, 3}) {
        INFO("dim " << dim);
        Simulation alone(two_piles(dim, false)), both(two_piles(dim, true));
        alone.set_quiet(true);
        both.set_quiet(true);
        alone.cycle(8000);
        both.cycle(8000);  // (both piles in contact with the floor and among themselves by now)
        World& w = both.world();
        const int second = w.find_group("second");
        const std::size_t n_first = alone.world().bodies.size();
        std::vector<std::uint8_t> gone(w.bodies.size());
        for (std::size_t i = 0; i < gone.size(); ++i) gone[i] = w.bodies.group[i] == second;
        const std::size_t contacts_before = active_contacts(w);
        std::size_t n_second = 0;
        for (std::uint8_t g : gone) n_second += g;
        REQUIRE(n_second == w.bodies.size() - n_first);
        REQUIRE(remove_bodies(w, gone) == n_second);
        REQUIRE(w.bodies.size() == n_first);
        alone.world().mark_dirty();
        alone.cycle(1500);
        both.cycle(1500);
        const Bodies &a = alone.world().bodies, &b = w.bodies;
        std::size_t differing = 0;
        for (std::size_t i = 0; i < n_first; ++i) {
            REQUIRE(a.id[i] == b.id[i]);
            for (int c = 0; c < 3; ++c)
                differing += bits(a.position[i][c]) != bits(b.position[i][c]) || bits(a.velocity[i][c]) != bits(b.velocity[i][c]);
        }
        CHECK(differing == 0);
        CHECK(active_contacts(w) == active_contacts(alone.world()));
        CHECK(contacts_before > active_contacts(w));  // (the second pile's contacts went with it)
        CHECK(active_contacts(w) > n_first / 2);      // (a pile, not loose balls: history mattered)
    }
}

TEST_CASE("a clump's pebble cannot be removed on its own", "[bodies][removal]") {
    json scene = two_piles(3, false);
    scene["bodies"].push_back({{"type", "clump"}, {"position", {0.3, 0.05, 0.0}},
                               {"pebbles", {{{"position", {0, 0, 0}}, {"radius", 0.003}}, {{"position", {0.004, 0, 0}}, {"radius", 0.003}}}},
                               {"density", 2500}});
    Simulation sim(scene);
    World& w = sim.world();
    std::vector<std::uint8_t> gone(w.bodies.size());
    gone.back() = 1;
    CHECK_THROWS_WITH(remove_bodies(w, gone), Catch::Contains("pebble of a clump"));
    CHECK(w.bodies.size() == gone.size());
}
