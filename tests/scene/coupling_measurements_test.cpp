// The named measurements of the coupled cases (scripting/measurements/
// coupling_measurements.cpp), each on a tiny scene of its own: a field over
// a group, balls outside a box, the pieces of a bonded rod and its first
// break.
#include "simulation.hpp"
#include "world/cycle.hpp"  // (break_bond writes a contact row, as a model does)

#include <measurements/measurement.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace plab;
using Catch::Matchers::Contains;

namespace {

// The measurement `name` made from `with` on the world, as a history column would.
Measurement make(const std::string& name, const json& with, const World& w) {
    return measurements().at(name).make(Node(with, "scene.histories.record[0].with"), w);
}

// Balls at x = 0, 2, 4, 6 mm (groups a, a, a, b), touching, no gravity.
json four_balls() {
    json bodies = json::array();
    for (int k = 0; k < 4; ++k)
        bodies.push_back({{"type", "ball"}, {"group", k < 3 ? "a" : "b"}, {"position", {0.002 * k, 0}}, {"radius", 0.001},
                          {"density", 1000}});
    return {{"dimension", 2}, {"gravity", {0, 0}}, {"plugins", {"linear"}}, {"bodies", bodies},
            {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"}, {"properties", {{"kn", 1e3}}}}}}};
}

} // namespace

TEST_CASE("group_field reduces a per-body field over a group's balls: mean, max, min, sum", "[measurements]") {
    Simulation sim(four_balls());
    World& w = sim.world();
    const int f = w.register_field("probe", 0.0);
    w.fields.column(f) = {1.0, 5.0, 3.0, 100.0};  // the last ball is in group b
    CHECK(make("group_field", {{"group", "a"}, {"field", "probe"}}, w)(w) == Approx(3.0));
    CHECK(make("group_field", {{"group", "a"}, {"field", "probe"}, {"reduce", "max"}}, w)(w) == 5.0);
    CHECK(make("group_field", {{"group", "a"}, {"field", "probe"}, {"reduce", "min"}}, w)(w) == 1.0);
    CHECK(make("group_field", {{"group", "a"}, {"field", "probe"}, {"reduce", "sum"}}, w)(w) == 9.0);
    CHECK(make("group_field", {{"group", "b"}, {"field", "probe"}}, w)(w) == 100.0);
    // errors name the path and what there is
    CHECK_THROWS_WITH(make("group_field", {{"group", "a"}, {"field", "voidage"}}, w),
                      Contains("with.field") && Contains("\"voidage\"") && Contains("probe"));
    CHECK_THROWS_WITH(make("group_field", {{"group", "c"}, {"field", "probe"}}, w), Contains("with.group") && Contains("a, b"));
}

TEST_CASE("count_outside counts a group's centres outside a box, now", "[measurements]") {
    Simulation sim(four_balls());
    World& w = sim.world();
    const json tank = {{"group", "a"}, {"min", {-0.001, -0.001}}, {"max", {0.003, 0.001}}};
    const Measurement outside = make("count_outside", tank, w);
    CHECK(outside(w) == 1.0);  // the ball at x = 4 mm; the one of group b does not count
    w.bodies.position[2].x() = 0.002;
    w.bodies.position[0].y() = -0.0011;
    CHECK(outside(w) == 1.0);
    w.bodies.position[0].y() = -0.001;  // on the face: inside
    CHECK(outside(w) == 0.0);
}

namespace {

// A rod of four bonded balls 2 mm apart; its two halves fly apart at
// 2 x 0.1 m/s, so the middle bond breaks in tension first.
json splitting_rod() {
    json scene = four_balls();
    for (json& b : scene["bodies"]) {
        b["group"] = "rod";
        b["velocity"] = {b["position"][0].get<double>() < 0.003 ? -0.1 : 0.1, 0};
    }
    scene["plugins"] = {"linear_pbond"};
    scene["contact_models"] = {{{"groups", {"rod", "rod"}}, {"model", "linear_pbond"},
                                {"properties", {{"kn", 1e4}, {"pb_kn", 1e9}, {"pb_ks", 1e9}, {"pb_ten", 1e3}, {"pb_coh", 1e9}}}}};
    scene["timestep"] = {{"fixed", 1e-6}};
    return scene;
}

} // namespace

TEST_CASE("fragments, largest_fragment, fragmented_at and first_break follow a bonded rod that splits", "[measurements]") {
    Simulation sim(splitting_rod());
    sim.set_quiet(true);
    World& w = sim.world();
    REQUIRE(w.bond(w.find_group("rod"), w.find_group("rod"), 1e-9) == 3);
    const json rod = {{"group", "rod"}};
    const Measurement pieces = make("fragments", rod, w), largest = make("largest_fragment", rod, w),
                      split = make("fragmented_at", rod, w), three = make("fragmented_at", {{"group", "rod"}, {"pieces", 3}}, w),
                      when = make("first_break", {{"report", "time"}}, w), where = make("first_break", {{"report", "x"}}, w),
                      mode = make("first_break", {{"report", "mode"}}, w);
    CHECK(pieces(w) == 1.0);
    CHECK(largest(w) == 4.0);
    CHECK(std::isnan(split(w)));
    CHECK(std::isnan(when(w)));
    // sampled only every 100 steps: the split time is still the break's step
    while (w.bond_breaks.empty() && w.step_count < 100000) sim.cycle(100);
    REQUIRE_FALSE(w.bond_breaks.empty());
    const BondBreak first = w.bond_breaks.front();
    CHECK(first.step % 100 != 0);  // the break fell between samples
    CHECK(pieces(w) == double(w.bond_breaks.size() + 1));
    CHECK(largest(w) <= 3.0);
    CHECK(split(w) == first.time);
    CHECK(when(w) == first.time);
    CHECK(where(w) == Approx(0.003).margin(2e-4));  // the middle bond's contact point
    CHECK(mode(w) == double(PLAB_BREAK_TENSION));
    if (w.bond_breaks.size() < 2) CHECK(std::isnan(three(w)));
    CHECK_THROWS_WITH(make("first_break", {{"report", "angle"}}, w), Contains("with.report"));
}

namespace {

// Breaks the bond between bodies i and j by hand, as the host does when a
// model breaks it: the row unbonded and the break logged at `time`.
void break_bond(World& w, std::size_t i, std::size_t j, double time) {
    for (const auto& inst : w.cycle->instances) {  // (inside the kernel: a host has no write access to contacts)
        const int slot = inst->desc->persist_slot;
        if (slot < 0) continue;
        ContactSet& c = inst->balls;
        for (std::size_t k = 0; k < c.size(); ++k) {
            const auto a = std::size_t(c.end1[k]), b = std::size_t(c.end2[k]);
            if (!((a == i && b == j) || (a == j && b == i))) continue;
            c.history[k * std::size_t(inst->stride) + std::size_t(slot)] = 0;
            BondBreak br;
            br.time = time;
            br.id1 = w.bodies.id[i];
            br.id2 = w.bodies.id[j];
            br.mode = PLAB_BREAK_TENSION;
            w.bond_breaks.push_back(br);
            return;
        }
    }
    FAIL("no bond between " << i << " and " << j);
}

} // namespace

TEST_CASE("fragmented_at replays the break log: the break that split the group, not the first or the last", "[measurements]") {
    // a ring of four bonded balls (a square of side 2 mm): cutting one side
    // leaves it whole, the opposite side splits it, a third cut splits it more
    json scene = splitting_rod();
    const double corners[4][2] = {{0, 0}, {0.002, 0}, {0.002, 0.002}, {0, 0.002}};
    for (int k = 0; k < 4; ++k) {
        scene["bodies"][k]["position"] = {corners[k][0], corners[k][1]};
        scene["bodies"][k]["velocity"] = {0, 0};
    }
    Simulation sim(scene);
    sim.set_quiet(true);
    World& w = sim.world();
    REQUIRE(w.bond(w.find_group("rod"), w.find_group("rod"), 1e-9) == 4);
    const Measurement split = make("fragmented_at", {{"group", "rod"}}, w), pieces = make("fragments", {{"group", "rod"}}, w);
    break_bond(w, 0, 1, 0.1);  // still a chain 1-2-3-0
    CHECK(pieces(w) == 1.0);
    break_bond(w, 2, 3, 0.2);  // {0, 3} and {1, 2}
    break_bond(w, 1, 2, 0.3);  // {0, 3}, {1}, {2}
    CHECK(pieces(w) == 3.0);
    CHECK(split(w) == 0.2);  // sampled once, after all three
    CHECK(make("fragmented_at", {{"group", "rod"}, {"pieces", 3}}, w)(w) == 0.3);
}
