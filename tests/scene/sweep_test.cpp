// plab sweep's Pareto front and picture (issue 7): the front is the set of
// runs no other run beats in both cost and error, and the PNG shows it.
#include "sweep.hpp"

#include <cairo.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

using namespace plab;
namespace fs = std::filesystem;

TEST_CASE("the Pareto front keeps exactly the runs no other run beats in both cost and error", "[sweep]") {
    // cost, error: A (1, 0.5) cheapest; B (2, 0.2); C (3, 0.3) is beaten by B;
    // D (4, 0.1); E (4, 0.15) ties D in cost and loses in error; F (8, 0.1)
    // ties D in error at twice the cost; G has no error (a failed run)
    const std::vector<double> cost = {1, 2, 3, 4, 4, 8, 0.5};
    const std::vector<double> error = {0.5, 0.2, 0.3, 0.1, 0.15, 0.1, std::nan("")};
    const std::vector<bool> front = pareto_front(cost, error);
    CHECK(front == std::vector<bool>{true, true, false, true, false, false, false});
    // two identical runs beat neither: both stay on the front
    CHECK(pareto_front({1, 1}, {0.1, 0.1}) == std::vector<bool>{true, true});
    // one run is its own front; an empty sweep has none
    CHECK(pareto_front({3}, {0.2}) == std::vector<bool>{true});
    CHECK(pareto_front({}, {}).empty());
}

namespace {
struct Count {
    long white = 0, front = 0, runs = 0;
};
bool near(int r, int g, int b, int R, int G, int B) { return std::abs(r - R) + std::abs(g - G) + std::abs(b - B) < 30; }
// White pixels, and pixels in the front's colour (blue, the first of the
// plot palette) and the runs' (vermilion, the second).
Count colours(cairo_surface_t* s) {
    Count c;
    const int w = cairo_image_surface_get_width(s), h = cairo_image_surface_get_height(s);
    for (int y = 0; y < h; ++y) {
        const auto* row = reinterpret_cast<const uint32_t*>(cairo_image_surface_get_data(s) + y * cairo_image_surface_get_stride(s));
        for (int x = 0; x < w; ++x) {
            const int r = (row[x] >> 16) & 255, g = (row[x] >> 8) & 255, b = row[x] & 255;
            c.white += r == 255 && g == 255 && b == 255;
            c.front += near(r, g, b, 0, 114, 178);
            c.runs += near(r, g, b, 213, 94, 0);
        }
    }
    return c;
}
} // namespace

TEST_CASE("a sweep's picture of error against cost is written, with its points and front drawn", "[sweep]") {
    const fs::path dir = fs::temp_directory_path() / "plab_sweep_png_test";
    fs::remove_all(dir);
    // costs over two decades: the cost axis is logarithmic
    const std::vector<SweepPoint> points = {{"dp=0.02", 0.1, 0.12}, {"dp=0.01", 0.6, 0.043}, {"dp=0.005", 3.7, 0.04},
                                            {"dp=0.005 h=1.5", 6.6, 0.038}, {"dp=0.01 h=1.5", 0.9, 0.063}};
    auto draw = [&](const std::vector<SweepPoint>& p, const std::string& name) {
        const std::string png = (dir / name).string();
        write_sweep_png(p, "test sweep", "cpu_s", "front error", png);
        REQUIRE(fs::exists(png));
        cairo_surface_t* s = cairo_image_surface_create_from_png(png.c_str());
        REQUIRE(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS);
        CHECK(cairo_image_surface_get_width(s) == 1000);
        const Count c = colours(s);
        cairo_surface_destroy(s);
        return std::pair{c, fs::file_size(png)};
    };
    const auto [all, bytes] = draw(points, "sweep.png");
    CHECK(bytes > 10000);     // axes, ticks, five labelled points and a legend
    CHECK(all.runs > 5 * 20); // five markers of the runs' colour
    CHECK(all.front > 4 * 40);
    CHECK(all.white > 10 * (all.runs + all.front));
    // the front of four runs joined by a line has more of its colour than
    // the same four runs when only one of them is on the front
    std::vector<SweepPoint> one_best = points;
    for (auto& p : one_best) p.error = p.label == "dp=0.02" ? 0.01 : p.error;  // the cheapest is also the best
    const auto [single, single_bytes] = draw(one_best, "single.png");
    CHECK(single.front < all.front);
    fs::remove_all(dir);
}
