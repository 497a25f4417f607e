// The host's lean path for SPH (issue 8): a rates stage whose sums nothing
// reads is skipped, and a model whose force acts between centres
// (PLAB_MODEL_FORCE_AT_CENTRES) gets packed rows without spin, moments,
// stiffness or energies. These change the work, not the physics: the forces
// must equal those of the full-column path bit for bit, and the sums must
// not depend on the thread count.
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <fstream>

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace plab;

namespace {

// The peer scene (bench/peers/sph_double_dam_break.json) with 0.1 x 0.1 m
// columns at both ends of a 0.5 m tank: 2 x 400 fluid balls, 150 steps.
json small_double_dam_break() {
    std::ifstream in(std::string(PLAB_SOURCE_DIR) + "/bench/peers/sph_double_dam_break.json");
    json s = json::parse(in);
    auto& b = s["bodies"];
    b[0]["box"]["max"] = {0.1, 0.1};
    b[1]["box"]["min"] = {0.4, 0.0};
    b[1]["box"]["max"] = {0.5, 0.1};
    b[2]["box"]["max"] = {0.515, 0.0};
    b[3]["box"]["max"] = {0.0, 0.2};
    b[4]["box"]["min"] = {0.5, 0.0};
    b[4]["box"]["max"] = {0.515, 0.2};
    s["commands"] = json::array();
    return s;
}

struct Outcome {
    std::uint64_t hash;
    double max_abs_drho_dt;
    bool drho_dt_computed;  // World::field_computed: outputs write it
    std::size_t contacts;   // active at the end
    std::vector<Eigen::Matrix3d> stress;  // per ball, from forces and contact points
    std::uint64_t rebuilds;
};

Outcome run(const json& scene, int threads) {
#ifdef _OPENMP
    omp_set_num_threads(threads);
    REQUIRE(omp_get_max_threads() == threads);
#endif
    Simulation sim(scene);
    sim.set_quiet(true);
    sim.world().parallel_min = 0;  // thread every loop, however short
    sim.cycle(150);
    World& w = sim.world();
    double rate = 0;
    for (double r : w.fields.column(w.fields.index("sph_drho_dt"))) rate = std::max(rate, std::fabs(r));
    return {state_hash(w), rate, field_computed(w, w.fields.index("sph_drho_dt")), active_contacts(w),
            ball_stress(w), rebuilds(w)};
}

} // namespace

TEST_CASE("SPH forces through the packed centre path equal the full-column path's bit for bit", "[sph][performance]") {
    const json lean = small_double_dam_break();
    // sph_density_integration reads sph_drho_dt: the rates stage runs and the
    // forces take the full-column path; the summation pass (stage 5)
    // overwrites the integrated density, so the flow must be the same
    json full = lean;
    full["passes"].push_back({{"name", "sph_density_integration"}, {"properties", {{"boundary_group", "boundary"}}}});
    const Outcome a = run(lean, 1), b = run(full, 1);
    CHECK(a.max_abs_drho_dt == 0.0);  // skipped: nothing read the continuity sum
    CHECK_FALSE(a.drho_dt_computed);  // so outputs must not write its zeros
    CHECK(b.max_abs_drho_dt > 0.0);   // it ran
    CHECK(b.drho_dt_computed);
    CHECK(a.hash == b.hash);
    // the lean path keeps no contact point: ball_stress() recomputes it from
    // the positions and the gap, and must find the stored one of the full path
    CHECK(a.rebuilds > 1);  // the rows were re-listed (sorted per end-1 run) and reused
    CHECK(a.contacts == b.contacts);
    REQUIRE(a.stress.size() == b.stress.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.stress.size(); ++i) differ += a.stress[i] != b.stress[i];
    CHECK(differ == 0);
}

TEST_CASE("a pass that needs the rates stage, added mid-run, unpacks the SPH set and the flow goes on unchanged",
          "[sph][performance]") {
    const json lean = small_double_dam_break();
    const std::uint64_t straight = run(lean, 1).hash;  // 150 steps on the lean path
    Simulation sim(lean);
    sim.set_quiet(true);
    sim.cycle(75);
    World& w = sim.world();
    REQUIRE(field_computed(w, w.fields.index("sph_drho_dt")) == false);
    // sph_density_integration reads sph_drho_dt: from now on the rates stage
    // runs over full columns, which the packed set must get back
    w.add_pass("sph_density_integration", {1.0});
    sim.cycle(75);
    CHECK(field_computed(w, w.fields.index("sph_drho_dt")));
    CHECK(state_hash(w) == straight);  // the summation pass overwrites the integrated density
}

TEST_CASE("an SPH double dam break gives bit-identical states with 1 and 2 threads", "[sph][determinism]") {
    const json scene = small_double_dam_break();
    CHECK(run(scene, 1).hash == run(scene, 2).hash);
#ifdef _OPENMP
    omp_set_num_threads(1);
#endif
}

TEST_CASE("centre forces between balls with every DOF fixed are not computed, and the flow is the same bits",
          "[sph][performance]") {
    // The boundary particles fixed in every DOF (`still`: the force pass
    // skips their boundary–boundary forces) or in translation only (their
    // spin is free, so those forces are computed). A centre force has no
    // moment on the packed path, so the spin stays zero and the flow must be
    // the same; the boundary–boundary rows must stay in range for the
    // density summation. The full-column path (a rates stage read) skips
    // them too and must give the same flow. (Its r x F of a centre force is
    // not exactly zero, so with free spin it is not compared.)
    const json still = small_double_dam_break();
    json free_spin = still;
    for (int b = 2; b < 5; ++b) free_spin["bodies"][b]["fix"] = {"translation"};
    json still_full = still;  // World::compute, not force_sweep
    still_full["passes"].push_back({{"name", "sph_density_integration"}, {"properties", {{"boundary_group", "boundary"}}}});
    struct Run { std::uint64_t hash; std::size_t in_range, with_force; };
    auto run_scene = [](const json& scene) {
        Simulation sim(scene);
        sim.set_quiet(true);
        sim.cycle(150);
        const World& w = sim.world();
        const ContactTable bb = w.model(2).balls();  // boundary–boundary (the scene's third rule)
        Run r{state_hash(w), 0, 0};
        for (std::size_t k = 0; k < bb.size(); ++k) {
            r.in_range += bb.active(k);
            r.with_force += bb.active(k) && bb.force(k).squaredNorm() > 0;
        }
        return r;
    };
    const Run a = run_scene(still), b = run_scene(free_spin), c = run_scene(still_full);
    CHECK(a.hash == b.hash);
    CHECK(a.hash == c.hash);
    CHECK(a.in_range == b.in_range);
    CHECK(a.in_range == c.in_range);
    CHECK(a.in_range > 1000);
    CHECK(a.with_force == 0);  // not computed
    CHECK(c.with_force == 0);
    CHECK(b.with_force > b.in_range / 2);  // computed
}
