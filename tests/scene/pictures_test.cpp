// Pictures: balls are drawn to scale where they are, in their field's
// colour; plots and validation reports are written; bad fields are named.
#include "pictures.hpp"
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
    opt.width = 710;  // 600 px of scene + the 110 px colour bar
    opt.view = {-0.03, -0.03, 0.09, 0.03};  // 0.12 m wide: 5000 px per metre
    write_snapshot_png(sim.world(), opt, png.string());
    cairo_surface_t* s = cairo_image_surface_create_from_png(png.string().c_str());
    REQUIRE(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS);
    const double scale = 600 / 0.12;
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
