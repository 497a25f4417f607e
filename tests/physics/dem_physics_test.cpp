// Physics of the kernel + linear model against analytical solutions
// (issue: kernel, acceptance 1–4): the validation cases' scenes
// (validation/free_fall, restitution, rolling, energy_conservation) and
// their own metrics.
#include "../support/case_scene.hpp"

#include <catch2/catch.hpp>

#include <cmath>


namespace {

using plab::json;
using namespace plab::testing_support;

std::string dim_file(const char* stem, int dim, const char* tail = "") {
    return std::string(stem) + "_" + std::to_string(dim) + "d" + tail + ".json";
}

// validation/restitution: e and the contact time of one impact, and their exact values
struct Impact {
    double restitution, duration, expected_restitution, expected_duration;
};
Impact normal_impact(int dim, bool on_wall, double beta, const char* dp_mode = "full") {
    const auto sim = run_scene(case_scene("restitution", {{"variables.beta", beta}, {"variables.dp_mode", dp_mode}},
                                          dim_file("scene", dim, on_wall ? "_wall" : "_ball")));
    return {metric(*sim, "restitution"), metric(*sim, "contact_time"), sim->scene()["variables"]["restitution"].get<double>(),
            sim->scene()["variables"]["contact_time"].get<double>()};
}

} // namespace

TEST_CASE("leapfrog free fall matches x0 + v0 t + g t^2/2 to 1e-10 relative", "[physics]") {
    for (int dim : {2, 3}) {
        const auto sim = run_scene(case_scene("free_fall", {{"variables.steps", 2000}}, dim_file("scene", dim)));
        CHECK(metric(*sim, "position", "error") < 1e-10);
        CHECK(sim->world().step_count == 2000);
    }
}

TEST_CASE("normal impact: restitution within 0.5 % and contact time within 1 % of the damped oscillator",
          "[physics]") {
    for (int dim : {2, 3})
        for (bool wall : {false, true})
            for (double beta : {0.0, 0.05, 0.2, 0.5}) {
                INFO("dim " << dim << (wall ? " wall" : " ball") << " beta " << beta);
                const Impact im = normal_impact(dim, wall, beta);
                CHECK(im.restitution == Approx(im.expected_restitution).epsilon(0.005));
                CHECK(im.duration == Approx(im.expected_duration).epsilon(0.01));
            }
}

TEST_CASE("no-tension dashpot mode gives a higher restitution than the full-dashpot formula", "[physics]") {
    // The full dashpot pulls the ball back as it leaves; clipping the total
    // normal force at zero removes that pull, so e exceeds exp(-βπ/√(1-β²)).
    const Impact full = normal_impact(2, true, 0.5, "full"), clipped = normal_impact(2, true, 0.5, "no_tension");
    CHECK(clipped.restitution > full.restitution * 1.2);
    CHECK(clipped.duration < full.duration);
}

TEST_CASE("a sliding disc ends rolling at 2/3 and a sphere at 5/7 of the launch speed", "[physics]") {
    CHECK(metric(*run_scene(case_scene("rolling", {}, "scene_2d.json")), "rolling_speed") == Approx(2.0 / 3.0).epsilon(0.01));
    CHECK(metric(*run_scene(case_scene("rolling", {}, "scene_3d.json")), "rolling_speed") == Approx(5.0 / 7.0).epsilon(0.01));
}

TEST_CASE("elastic packed balls conserve energy and the leapfrog error is second order", "[physics]") {
    for (int dim : {2, 3}) {
        INFO("dim " << dim);
        const std::string file = dim_file("scene_packed", dim);
        const auto coarse = run_scene(case_scene("energy_conservation", {{"variables.steps", 20000}}, file));
        const auto fine = run_scene(case_scene("energy_conservation", {{"variables.steps", 40000}, {"variables.fraction", 0.05}}, file));
        CHECK(metric(*coarse, "drift") < 1e-4);
        const double ratio = metric(*coarse, "fluctuation") / metric(*fine, "fluctuation");
        CHECK(ratio > 3.5);
        CHECK(ratio < 4.5);
    }
}
