// Pseudo-springs of the SPH solid (physics/sph_solid; Islam 2023 §3.2–3.3):
// with interactions only between bonded immediate neighbours, the
// corrected gradient is still exact for a linear field (Hooke's stress in
// a stretched block, at its edges and corners too); each particle has the
// immediate neighbours of its lattice (8, 5 at an edge, 3 at a corner in
// 2D; 26 inside a cubic block); springs fail at the strain the geometry
// gives them and D counts the failed fraction; a fracturing bar gives the
// same bits on 1 and 2 threads and after a restart.
#include "simulation.hpp"
#include "../support/same_bits.hpp"
#include "../support/sph_solid_block.hpp"

#include <plab/sph_solid/elasticity.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

using namespace plab;
using namespace plab::testing_support;

namespace {

// An n-a-side block (2D square, 3D cubic lattice) of SPH solid with
// pseudo-springs between immediate neighbours (gap <= 0.5 dp in 2D, 0.75 dp
// in 3D: the diagonals of the square and of the cube), every particle
// moving with the held velocity `profile` for `cycles` steps of dt.
json spring_block(int dim, int n, const json& profile, int cycles, double dt, double failure_strain) {
    json scene = moving_block(dim, profile, cycles, dt, true, n);
    json& properties = scene["contact_models"][0]["properties"];
    properties["interactions"] = "pseudo_springs";
    if (failure_strain > 0) properties["failure_strain"] = failure_strain;
    const json bond = {{"bond", {{"groups", {"solid", "solid"}}, {"gap", (dim == 2 ? 0.5 : 0.75) * kDp}}}};
    scene["commands"].insert(scene["commands"].begin(), bond);
    return scene;
}

// how many of a particle's lattice coordinates (of n) lie on the block's faces
int on_faces(const World& w, std::size_t i, int dim, int n) {
    int faces = 0;
    for (int a = 0; a < dim; ++a) {
        const long c = std::lround(w.bodies.position[i][a] / kDp - 0.5);
        faces += c == 0 || c == n - 1;
    }
    return faces;
}

} // namespace

TEST_CASE("sph_solid pseudo-springs: a stretched block carries Hooke's stress through its immediate neighbours alone",
          "[sph_solid][pseudo_springs]") {
    const double bulk = kE / (3 * (1 - 2 * kNu)), shear = kE / (2 * (1 + kNu));
    const double rate = 1.0, dt = 1e-5;
    const int cycles = 100;
    for (int dim : {2, 3}) {
        INFO("dim " << dim);
        const int n = dim == 2 ? 10 : 5;
        Simulation sim(spring_block(dim, n, dim == 2 ? json{"1.0 * x", "0"} : json{"1.0 * x", "0", "0"}, cycles, dt, 0));
        sim.set_quiet(true);
        sim.run();
        const World& w = sim.world();
        const double strain = std::log1p(rate * cycles * dt);
        for (std::size_t i = 0; i < w.bodies.size(); ++i) {
            INFO("particle " << i << " at " << w.bodies.position[i].transpose());
            // the lattice's immediate neighbours: 3^d - 1 inside, fewer on faces, edges, corners
            const int faces = on_faces(w, i, dim, n);
            const double springs = std::pow(3.0, dim - faces) * std::pow(2.0, faces) - 1;
            CHECK(field_at(w, "sph_solid_initial_springs", i) == springs);
            CHECK(field_at(w, "sph_solid_damage", i) == 0.0);
            // the corrected gradient of the 9- (27-) point stencil is exact for the linear field
            CHECK(field_at(w, "sph_solid_stress_xx", i) == Approx((bulk + 4 * shear / 3) * strain).epsilon(2e-3));
            CHECK(field_at(w, "sph_solid_stress_yy", i) == Approx((bulk - 2 * shear / 3) * strain).epsilon(2e-3));
        }
        CHECK(w.bond_breaks.empty());
    }
}

TEST_CASE("sph_solid pseudo-springs: springs fail at the strain their direction takes, and D counts them",
          "[sph_solid][pseudo_springs]") {
    // a held stretch x(t) = x0 (1 + a), a = rate t: a spring along x has
    // strain a, a diagonal one sqrt(((1 + a)^2 + 1)/2) - 1 (0.0356 at a = 0.07),
    // one along y none; with eps_f 0.05, at a = 0.07 exactly the x springs
    // have failed
    const int n = 10;
    const double rate = 10.0, dt = 1e-5;
    const int cycles = 700;
    Simulation sim(spring_block(2, n, json{"10.0 * x", "0"}, cycles, dt, 0.05));
    sim.set_quiet(true);
    sim.run();
    const World& w = sim.world();
    REQUIRE(rate * cycles * dt == Approx(0.07));
    CHECK(w.bond_breaks.size() == std::size_t(n * (n - 1)));
    for (const BondBreak& b : w.bond_breaks) CHECK(b.time == Approx(0.05 / rate).margin(2 * dt));
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        INFO("particle " << i << " at " << w.bodies.position[i].transpose());
        const long cx = std::lround(w.bodies.position[i].x() / (kDp * 1.07) - 0.5);
        const bool x_end = cx == 0 || cx == n - 1;
        const double initial = field_at(w, "sph_solid_initial_springs", i);
        const double lost_x = x_end ? 1 : 2;  // its springs along x
        CHECK(field_at(w, "sph_solid_damage", i) == Approx(lost_x / initial).epsilon(1e-12));
    }
}

namespace {

// A 24 x 4 bar pulled apart at 0.5 m/s by its two end columns, eps_f 0.02:
// it cracks within a few hundred steps.
std::unique_ptr<Simulation> pulled_bar() {
    json scene = spring_block(2, 4, json{"0", "0"}, 0, 0, 0.02);
    scene["bodies"][0]["box"]["max"] = {24 * kDp, 4 * kDp};
    scene["timestep"] = {{"fixed", 1e-5}};
    scene["commands"] = {
        {{"bond", {{"groups", {"solid", "solid"}}, {"gap", 0.5 * kDp}}}},
        {{"set", {{"region", {{"min", {-1, -1}}, {"max", {kDp, 1}}}}, {"velocity", {-0.5, 0}}, {"fix", {"all"}}}}},
        {{"set", {{"region", {{"min", {23 * kDp, -1}}, {"max", {1, 1}}}}, {"velocity", {0.5, 0}}, {"fix", {"all"}}}}}};
    auto sim = std::make_unique<Simulation>(scene);
    sim->set_quiet(true);
    sim->run();
    return sim;
}

} // namespace

TEST_CASE("sph_solid pseudo-springs: a cracking bar gives the same bits on 1 and 2 threads and after a restart",
          "[sph_solid][pseudo_springs][determinism][restart]") {
    const auto hash = hashes_on_1_and_2_threads(pulled_bar, 600);
    CHECK(hash[0] == hash[1]);
    auto whole = pulled_bar();
    whole->cycle(600);
    CHECK(whole->world().bond_breaks.size() > 0);  // it cracked
    auto resumed = restarted_after(pulled_bar, 301, "plab_pulled_bar");
    resumed->cycle(299);
    CHECK(state_hash(resumed->world()) == state_hash(whole->world()));
    CHECK(resumed->world().bond_breaks.size() == whole->world().bond_breaks.size());
}
