// Pictures: balls are drawn to scale where they are, in their field's
// colour; plots and validation reports are written; bad fields are named.
#include "pictures.hpp"
#include "quantities.hpp"
#include "simulation.hpp"
#include "validation.hpp"

#include <cairo.h>

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

using namespace plab;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {
json two_discs() {
    return {{"dimension", 2},
            {"plugins", {"linear"}},
            {"bodies", {{{"type", "ball"}, {"group", "left"}, {"position", {0.0, 0.0}}, {"radius", 0.01}, {"density", 1000}},
                        {{"type", "ball"}, {"group", "right"}, {"position", {0.05, 0.0}}, {"radius", 0.02}, {"density", 1000}}}},
            {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"}}}}};
}

struct Pixel {
    unsigned r, g, b;
    bool white() const { return r == 255 && g == 255 && b == 255; }
};

Pixel pixel(cairo_surface_t* s, double x, double y) {
    const unsigned char* row = cairo_image_surface_get_data(s) + int(y) * cairo_image_surface_get_stride(s);
    const uint32_t v = reinterpret_cast<const uint32_t*>(row)[int(x)];
    return {(v >> 16) & 255u, (v >> 8) & 255u, v & 255u};
}
} // namespace

TEST_CASE("a snapshot draws each disc to scale, at its place, in its group's colour", "[pictures]") {
    Simulation sim(two_discs());
    const fs::path png = fs::temp_directory_path() / "plab_pictures_test.png";
    SnapshotOptions opt;
    opt.field = "group";
    opt.width = 720;  // 600 px of scene + the 120 px colour bar
    opt.axes = false;
    opt.view = {-0.03, -0.03, 0.09, 0.03};  // 0.12 m wide: 5000 px per metre
    write_snapshot_png(sim.world(), opt, png.string());
    cairo_surface_t* s = cairo_image_surface_create_from_png(png.string().c_str());
    REQUIRE(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS);
    const double scale = 600 / 0.12;
    REQUIRE(snapshot_layout(opt, opt.view).scale == Approx(scale));
    auto at = [&](double x, double y) { return pixel(s, (x + 0.03) * scale, (0.03 - y) * scale); };
    const Pixel left = at(0.0, 0.0), right = at(0.05, 0.0);
    CHECK_FALSE(left.white());
    CHECK_FALSE(right.white());
    CHECK((left.r != right.r || left.g != right.g || left.b != right.b));  // two groups, two colours
    CHECK(at(0.0, 0.008).r == left.r);   // inside the small disc (R = 1 cm)
    CHECK(at(0.0, 0.012).white());       // just outside it
    CHECK(at(0.05, 0.018).r == right.r); // inside the large disc (R = 2 cm)
    CHECK(at(0.05, 0.022).white());
    CHECK(at(0.025, 0.0).white());       // the gap between them
    cairo_surface_destroy(s);
    fs::remove(png);
}

namespace {
// Three discs 5 cm apart without gravity: 0 at rest, 1 at 1 m/s, 2 at rest
// until a command sets it to 2 m/s (the run's largest speed comes last).
json three_speeds(const std::string& range) {
    json scene = {{"dimension", 2},
                  {"plugins", {"linear"}},
                  {"bodies", json::array()},
                  {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"}}}},
                  {"timestep", {{"fixed", 1e-4}}},
                  {"output", {{"png", {{"interval", 5e-4}, {"field", "velocity"}, {"range", range}, {"axes", true},
                                       {"view", {{"min", {-0.03, -0.03}}, {"max", {0.13, 0.03}}}}}}}},
                  {"commands", {{{"cycle", 10}}, {{"set", {{"id", 2}, {"velocity", {2.0, 0.0}}}}}, {{"cycle", 10}}}}};
    for (int k = 0; k < 3; ++k)
        scene["bodies"].push_back({{"type", "ball"}, {"position", {0.05 * k, 0.0}}, {"radius", 0.01}, {"density", 1000},
                                   {"velocity", {k == 1 ? 1.0 : 0.0, 0.0}}});
    if (range != "run" && range != "frame") scene["output"]["png"]["range"] = {0.0, 4.0};
    return scene;
}

// The colour of disc 1 in the first and the last frame of a run.
std::pair<Pixel, Pixel> disc_one_colours(const std::string& range, const fs::path& out) {
    fs::remove_all(out);
    Simulation sim(three_speeds(range));
    sim.set_quiet(true);
    sim.set_output_dir(out.string());
    sim.run();
    SnapshotOptions opt;
    opt.view = {-0.03, -0.03, 0.13, 0.03};
    const SnapshotLayout L = snapshot_layout(opt, opt.view);
    const double x = L.left + (0.05 + 1e-3 - opt.view[0]) * L.scale, y = L.top + (opt.view[3] - 0.0) * L.scale;
    std::vector<Pixel> colours;
    for (const char* frame : {"png/frame_00000.png", "png/frame_00004.png"}) {
        cairo_surface_t* s = cairo_image_surface_create_from_png((out / frame).string().c_str());
        REQUIRE(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS);
        colours.push_back(pixel(s, x, y));
        cairo_surface_destroy(s);
    }
    fs::remove_all(out);
    return {colours[0], colours[1]};
}

bool same(const Pixel& a, const Pixel& b) { return a.r == b.r && a.g == b.g && a.b == b.b; }
} // namespace

TEST_CASE("a frame series colours one speed alike in every frame unless asked for each frame's own range", "[pictures]") {
    const fs::path out = fs::temp_directory_path() / "plab_png_range_test";
    // disc 1 moves at 1 m/s throughout; the run's range grows to 2 m/s at step 10
    const auto [run_first, run_last] = disc_one_colours("run", out);
    CHECK(same(run_first, run_last));        // drawn again in the run's range [0, 2]
    const auto [fixed_first, fixed_last] = disc_one_colours("fixed", out);
    CHECK(same(fixed_first, fixed_last));    // [0, 4] throughout
    CHECK_FALSE(same(fixed_first, run_first));  // 1/4 and 1/2 of the bar are different colours
    const auto [own_first, own_last] = disc_one_colours("frame", out);
    CHECK_FALSE(same(own_first, own_last));  // the top of [0, 1], then the middle of [0, 2]
    CHECK(same(own_last, run_last));
}

TEST_CASE("a plug-in field's unit reaches the picture and the history columns", "[pictures]") {
    Simulation sim(two_discs());
    World& w = sim.world();
    const int f = w.register_field("probe_density", 1000.0, "kg/m3");
    CHECK(w.fields.unit(f) == "kg/m3");
    CHECK(w.register_field("probe_density", 1000.0, "ignored") == f);
    CHECK(w.fields.unit(f) == "kg/m3");  // the first unit declared stays
    CHECK(w.fields.unit(w.register_field("plain", 0.0)) == "");
    std::string unit;
    snapshot_values(w, "probe_density", unit);
    CHECK(unit == "kg/m3");
    CHECK(quantity_unit("probe.probe_density", w) == "kg/m3");
    CHECK(quantity_unit("ball.velocity.x", w) == "m/s");
    CHECK(quantity_unit("group.mean.angular_velocity.z", w) == "rad/s");
    CHECK(quantity_unit("wall.moment.z", w) == "N m");
    CHECK(quantity_unit("energy.kinetic", w) == "J");
    CHECK(quantity_unit("measure.max_displacement", w) == "m");
    CHECK(quantity_unit("measure.first_bond_break", w) == "");  // its unit depends on what it reports
}

TEST_CASE("a snapshot of an unknown field names the fields it knows", "[pictures]") {
    Simulation sim(two_discs());
    SnapshotOptions opt;
    opt.field = "temperature";
    CHECK_THROWS_WITH(write_snapshot_png(sim.world(), opt, "/tmp/never.png"),
                      Contains("unknown field 'temperature'") && Contains("velocity") && Contains("broken_bonds"));
    json scene = two_discs();
    scene["output"] = {{"png", {{"interval", 0.1}, {"field", "temperature"}}}};
    CHECK_THROWS_WITH(Simulation(scene), Contains("scene.output.png.field") && Contains("velocity"));
    scene["dimension"] = 3;
    scene["bodies"][0]["position"] = {0, 0, 0};
    scene["bodies"][1]["position"] = {0.05, 0, 0};
    CHECK_THROWS_WITH(Simulation(scene), Contains("2D scenes only"));
}

TEST_CASE("the validation report lists every case with its verdict, error, tolerance and CPU time, and its plots", "[pictures]") {
    const fs::path dir = fs::temp_directory_path() / "plab_report_test";
    fs::remove_all(dir);
    CaseResult pass{0.001, 0.01, "relative error", "    detail line\n", {}};
    pass.plots.push_back({"a plot", "x", "y", {{"measured", {0, 1, 2}, {1, 2, 3}, false, 0}, {"reference", {0, 2}, {1, 3}, true, 0.05}}});
    CaseResult fail{0.2, 0.01, "relative error", "", {}};
    fail.failed_checks = 1;  // as the runner counts a check above its tolerance
    const std::string md = write_validation_report(dir.string(), {{"good", "a case that passes", pass, 1.5, ""},
                                                                   {"bad", "a case that fails", fail, 0.25, "stopped here"}},
                                                   true);
    std::ifstream f(md);
    const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    CHECK_THAT(text, Contains("| [good](#good) | PASS | 0.001 | 0.01 | relative error | 1.50 |"));
    CHECK_THAT(text, Contains("| [bad](#bad) | **FAIL** | 0.2 | 0.01 | relative error | 0.25 |"));
    CHECK_THAT(text, Contains("1 passed, 1 failed"));
    CHECK_THAT(text, Contains("![a plot](good_0.png)"));
    CHECK_THAT(text, Contains("Stopped: `stopped here`"));
    CHECK(fs::file_size(dir / "good_0.png") > 1000);
    fs::remove_all(dir);
}
