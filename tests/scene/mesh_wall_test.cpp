// The "mesh" wall type (scripting/wall_generators.cpp): a mesh file found
// beside the scene, placed by scale, rotate and translate, one wall with a
// triangle facet per triangle; and its refusals by JSON path.
#include "../support/mesh_files.hpp"
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace plab;
using namespace plab::testing_support;
using Catch::Matchers::Contains;

namespace {

json cube_scene(const json& wall, int dim = 3) {
    return {{"dimension", dim},
            {"plugins", {"linear"}},
            {"bodies", {{{"type", "ball"}, {"group", "grains"}, {"position", dim == 3 ? json{0.5, 0.5, 0.5} : json{0.5, 0.5}},
                         {"radius", 0.05}, {"density", 1000}}}},
            {"walls", {wall}},
            {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"}, {"properties", {{"kn", 1e4}, {"ks", 1e4}}}}}},
            {"commands", {{{"cycle", 1}}}}};
}

} // namespace

TEST_CASE("a mesh wall is the file's triangles, found beside the scene, scaled, rotated and translated in that order",
          "[mesh][scene]") {
    const auto dir = mesh_dir("placement");
    std::filesystem::create_directories(dir / "parts");
    write_file(dir / "parts" / "cube.stl", binary_stl(cube_triangles()));
    const json wall = {{"type", "mesh"}, {"name", "bin"}, {"group", "bin"}, {"file", "parts/cube.stl"},
                       {"scale", {2.0, 1.0, 0.5}}, {"rotate", {{"axis", {0, 0, 1}}, {"angle", 90}}},
                       {"translate", {10, 20, 30}}, {"velocity", {0, 0, -1}}};
    Simulation sim(cube_scene(wall), dir.string());  // relative to the scene's folder, not the working one
    const Walls& w = sim.world().walls;
    REQUIRE(w.walls.size() == 1);
    CHECK(w.walls[0].name == "bin");
    CHECK(w.walls[0].velocity == Vec(0, 0, -1));
    REQUIRE(w.walls[0].facets.size() == 12);
    const std::vector<Triangle> cube = cube_triangles();
    for (std::size_t t = 0; t < 12; ++t) {
        const Facet& f = w.facets[std::size_t(w.walls[0].facets[t])];
        CHECK(f.kind == FacetKind::triangle);
        CHECK(f.wall == 0);
        const Vec* got[] = {&f.a, &f.b, &f.c};
        for (std::size_t v = 0; v < 3; ++v) {
            // (x, y, z) -> scale (2x, y, z/2) -> 90 deg about z (-y, 2x, z/2) -> + (10, 20, 30)
            const Vec& p = cube[t][v];
            const Vec expected(10 - p.y(), 20 + 2 * p.x(), 30 + 0.5 * p.z());
            CHECK((*got[v] - expected).norm() < 1e-14);
        }
    }
    std::filesystem::remove_all(dir);
}

TEST_CASE("a mesh wall is refused in 2D, and its keys by path: scale, rotate, a missing file, a duplicated triangle",
          "[mesh][scene]") {
    const auto dir = mesh_dir("refusals");
    write_file(dir / "cube.stl", binary_stl(cube_triangles()));
    const json wall = {{"type", "mesh"}, {"file", "cube.stl"}};
    auto refused = [&](const json& w, int dim = 3) {
        try {
            Simulation sim(cube_scene(w, dim), dir.string());
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK_THAT(refused(wall, 2), Contains("scene.walls[0].type") && Contains("needs a 3D scene") && Contains("polyline"));
    json w = wall;
    w["spin"] = {0, 0, 1};
    CHECK_THAT(refused(w), Contains("scene.walls[0].spin") && Contains("angular_velocity") && Contains("file, scale, translate, rotate"));
    w = wall;
    w["scale"] = 0;
    CHECK_THAT(refused(w), Contains("scene.walls[0].scale") && Contains("outside the valid range (0, inf)"));
    w["scale"] = {1, -1, 1};
    CHECK_THAT(refused(w), Contains("scene.walls[0].scale[1]") && Contains("(0, inf)"));
    w["scale"] = {1, 1};
    CHECK_THAT(refused(w), Contains("scene.walls[0].scale") && Contains("a number or 3 numbers"));
    w = wall;
    w["rotate"] = {{"axis", {0, 0, 0}}, {"angle", 10}};
    CHECK_THAT(refused(w), Contains("scene.walls[0].rotate.axis") && Contains("must not be zero"));
    w["rotate"] = {{"axis", {0, 0, 1}}, {"degrees", 10}};
    CHECK_THAT(refused(w), Contains("scene.walls[0].rotate.degrees") && Contains("axis, angle"));
    w = wall;
    w["file"] = "nowhere.stl";
    CHECK_THAT(refused(w), Contains("scene.walls[0].file") && Contains("\"nowhere.stl\": cannot open") &&
                               Contains((dir / "nowhere.stl").string()));
    std::vector<Triangle> twice = cube_triangles();
    twice.push_back(twice[4]);
    write_file(dir / "twice.stl", binary_stl(twice));
    w["file"] = "twice.stl";
    CHECK_THAT(refused(w), Contains("scene.walls[0]") && Contains("coincides with one of scene.walls[0] (itself)"));
    std::filesystem::remove_all(dir);
}
