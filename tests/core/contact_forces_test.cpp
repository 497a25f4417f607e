// Contact forces are written only on the steps whose forces something reads
// (World::contact_forces_wanted): the motion is the same bits either way,
// and the forces read are those a run that writes every step would give.
#include "simulation.hpp"
#include "settling_scene.hpp"

#include <catch2/catch.hpp>

#include <cstring>

using namespace plab;

namespace {

std::uint64_t bits(double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
}

// Active ball–ball rows of both worlds whose force differs in any bit
// (the two worlds hold the same rows: the same scene, the same steps).
std::size_t forces_differing(const World& a, const World& b) {
    std::size_t differ = 0;
    for (std::size_t m = 0; m < a.model_count(); ++m) {
        const ContactTable sa = a.model(m).balls(), sb = b.model(m).balls();
        REQUIRE(sa.size() == sb.size());
        for (std::size_t k = 0; k < sa.size(); ++k) {
            REQUIRE(sa.active(k) == sb.active(k));
            if (!sa.active(k)) continue;
            for (int c = 0; c < 3; ++c) differ += bits(sa.force(k)[c]) != bits(sb.force(k)[c]);
        }
    }
    return differ;
}

} // namespace

TEST_CASE("contact forces written only on the steps that read them are those of every step", "[determinism]") {
    Simulation every(settling_scene(3, 600)), some(settling_scene(3, 600));
    World &a = every.world(), &b = some.world();
    b.contact_forces_wanted = [&b] { return b.step_count % 50 == 0; };
    std::size_t stale_rows = 0, in_contact = 0;
    for (int s = 0; s < 3000; ++s) {
        a.step();
        b.step();
        REQUIRE(state_hash(a) == state_hash(b));
        REQUIRE(contact_forces_current(a));
        if (b.step_count % 50 == 0) {
            REQUIRE(contact_forces_current(b));
            REQUIRE(forces_differing(a, b) == 0);
            for (std::size_t m = 0; m < a.model_count(); ++m)
                for (std::size_t k = 0; k < a.model(m).balls().size(); ++k) in_contact += a.model(m).balls().active(k);
        } else {
            REQUIRE(!contact_forces_current(b));
            stale_rows += forces_differing(a, b);
        }
    }
    CHECK(in_contact > 100);  // (balls touch: a test of something)
    CHECK(stale_rows > 0);  // the other steps wrote none: their columns lag
}

TEST_CASE("a run's history rows read the contact forces of their own step", "[determinism]") {
    json scene = settling_scene(3, 600);
    scene["histories"] = {{"every", 70}, {"record", {{{"name", "ratio"}, {"quantity", "unbalanced_ratio"}}}}};
    Simulation run(scene);
    run.set_quiet(true);
    run.cycle(3000);  // (the cycle writes forces only for its history rows and its last step)
    const std::vector<double> ratio = run.history("ratio");
    // the same scene stepped by hand, which writes every step's forces
    Simulation by_hand(settling_scene(3, 600));
    World& w = by_hand.world();
    std::vector<double> expected{(w.prepare(), unbalanced_force_ratio(w))};
    for (int s = 0; s < 3000; ++s) {
        w.step();
        if (w.step_count % 70 == 0) expected.push_back(unbalanced_force_ratio(w));
    }
    REQUIRE(ratio.size() == expected.size());
    for (std::size_t r = 0; r < ratio.size(); ++r) {
        INFO("row " << r);
        CHECK(bits(ratio[r]) == bits(expected[r]));
    }
    CHECK(contact_forces_current(run.world()));  // after the cycle's last step
    CHECK(forces_differing(run.world(), w) == 0);
}
