// Rigid-body shapes (scripting/body_shapes.cpp): a union's mass properties
// against the one body it makes, the surfaces closed and facing out (their
// enclosed volume is the shape's, to the polygon's error), overlapping parts
// refused; and the bodies' surfaces in the VTK series.
#include "body_shapes.hpp"
#include "simulation.hpp"
#include "vtk_output.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <regex>

using namespace plab;
using Catch::Matchers::Contains;

namespace {

BodyShape shape(const json& j, int dim) { return read_shape(Node(j, "scene.shape"), dim, "."); }

// The area a 2D surface's edges enclose (the shoelace sum; holes clockwise).
double enclosed_area(const BodySurface& s) {
    double twice = 0;
    for (const auto& f : s.faces) {
        const Vec &a = s.vertices[f[0]], &b = s.vertices[f[1]];
        twice += a.x() * b.y() - a.y() * b.x();
    }
    return twice / 2;
}

void check_same(const MassProperties& a, const MassProperties& b) {
    CHECK(a.volume == Approx(b.volume).epsilon(1e-12));
    CHECK((a.centroid - b.centroid).norm() < 1e-12);
    CHECK((a.inertia - b.inertia).norm() < 1e-12 * b.inertia.norm());
}

} // namespace

TEST_CASE("a union of touching boxes has the mass properties of the box they make", "[clump][shape]") {
    const json halves = {{"type", "union"},
                         {"parts", {{{"type", "box"}, {"size", {1.0, 1, 1}}, {"position", {-0.5, 0, 0}}},
                                    {{"type", "box"}, {"size", {1.0, 1, 1}}, {"position", {0.5, 0, 0}}}}}};
    check_same(shape(halves, 3).properties, box_properties(Vec(1, 0.5, 0.5)));
    // an L of two rectangles, 2D (1 m thick): the 2 x 1 bar and a 1 x 1 square on its left end
    const json l_shape = {{"type", "union"},
                          {"parts", {{{"type", "box"}, {"size", {2.0, 1}}, {"position", {0, 0}}},
                                     {{"type", "box"}, {"size", {1.0, 1}}, {"position", {-0.5, 1}}}}}};
    const MassProperties l = shape(l_shape, 2).properties;
    CHECK(l.volume == Approx(3));
    CHECK(l.centroid.x() == Approx(-1.0 / 6));  // (2 * 0 + 1 * -0.5) / 3
    CHECK(l.centroid.y() == Approx(1.0 / 3));   // (2 * 0 + 1 * 1) / 3
    // about z: each part's own (a^2 + b^2) / 12 per area, plus area * d^2
    const double bar = 2 * (4 + 1) / 12.0 + 2 * (std::pow(1.0 / 6, 2) + std::pow(1.0 / 3, 2));
    const double square = 1 * (1 + 1) / 12.0 + 1 * (std::pow(0.5 - 1.0 / 6, 2) + std::pow(1 - 1.0 / 3, 2));
    CHECK(l.inertia(2, 2) == Approx(bar + square).epsilon(1e-12));
    // a turned part: a box along y is the box along x turned 90 degrees about z
    const json turned = {{"type", "union"},
                         {"parts", {{{"type", "box"}, {"size", {0.3, 0.1, 0.2}}, {"orientation", {{"axis", {0, 0, 1}}, {"angle", 90}}}}}}};
    check_same(shape(turned, 3).properties, box_properties(Vec(0.05, 0.15, 0.1)));
}

TEST_CASE("a union's parts may touch but not overlap", "[clump][shape][errors]") {
    const json overlapping = {{"type", "union"},
                              {"parts", {{{"type", "box"}, {"size", {1.0, 1, 1}}},
                                         {{"type", "sphere"}, {"radius", 0.3}, {"position", {0.6, 0, 0}}}}}};
    CHECK_THROWS_WITH(shape(overlapping, 3), Contains("scene.shape.parts[1]") && Contains("overlaps part 0"));
    const json mesh_part = {{"type", "union"}, {"parts", {{{"type", "mesh"}, {"file", "x.stl"}}}}};
    CHECK_THROWS_WITH(shape(mesh_part, 3), Contains("scene.shape.parts[0].type"));
}

TEST_CASE("every shape's surface is closed and faces out: it encloses the shape's volume", "[clump][shape]") {
    const json shapes3[] = {{{"type", "sphere"}, {"radius", 0.5}},
                            {{"type", "box"}, {"size", {0.1, 0.2, 0.3}}},
                            {{"type", "cylinder"}, {"radius", 0.2}, {"height", 0.5}},
                            {{"type", "ring"}, {"outer_radius", 0.2}, {"inner_radius", 0.1}, {"height", 0.1}}};
    for (const json& j : shapes3) {
        INFO(j.dump());
        const BodyShape b = shape(j, 3);
        const MassProperties enclosed = mesh_properties(surface_triangles(b.surface));
        // the polyhedron's vertices lie on the true surface: a little less volume
        // (a 48-gon keeps 99.7 % of a circle, the 320-face sphere 96.6 %)
        CHECK(enclosed.volume / b.properties.volume == Approx(1).margin(0.04));
        CHECK(enclosed.volume <= b.properties.volume * (1 + 1e-12));
        CHECK(enclosed.centroid.norm() < 1e-12);
    }
    const json shapes2[] = {{{"type", "sphere"}, {"radius", 0.5}},
                            {{"type", "box"}, {"size", {0.1, 0.2}}},
                            {{"type", "ring"}, {"outer_radius", 0.2}, {"inner_radius", 0.1}}};
    for (const json& j : shapes2) {
        INFO(j.dump());
        const BodyShape b = shape(j, 2);
        CHECK(b.surface.edges);
        CHECK(enclosed_area(b.surface) / b.properties.volume == Approx(1).margin(0.005));  // 1 m thick: volume = area
    }
}

TEST_CASE("the VTK series draws each body's surface where the body is, and can leave the pebbles out", "[clump][vtk]") {
    const json scene = {{"dimension", 3},
                        {"gravity", {0, 0, 0}},
                        {"bodies", {{{"type", "rigid"}, {"shape", {{"type", "box"}, {"size", {0.1, 0.2, 0.3}}}}, {"density", 1000},
                                     {"pebbles", {{{"position", {0, 0, 0}}, {"radius", 0.05}}}}, {"position", {1, 2, 3}}},
                                    {{"type", "ball"}, {"position", {5, 0, 0}}, {"radius", 0.01}, {"density", 1000}}}}};
    Simulation sim(scene);
    VtkOptions opt;
    opt.encoding = VtkOptions::Encoding::ascii;
    const std::string bodies = bodies_vtp(sim.world(), opt);
    CHECK_THAT(bodies, Contains("NumberOfPoints=\"8\"") && Contains("NumberOfPolys=\"12\""));
    // the corners are at the centre plus and minus the half edges
    std::smatch m;
    REQUIRE(std::regex_search(bodies, m, std::regex("<Points>\\n<DataArray[^>]*>\\n([^<]*)")));
    std::istringstream coords(m[1].str());
    Vec lo = Vec::Constant(kInf), hi = -lo;
    for (Vec p; coords >> p.x() >> p.y() >> p.z();) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    CHECK((lo - Vec(0.95, 1.9, 2.85)).norm() < 1e-12);
    CHECK((hi - Vec(1.05, 2.1, 3.15)).norm() < 1e-12);
    CHECK_THAT(balls_vtp(sim.world(), opt), Contains("NumberOfPoints=\"2\""));
    opt.pebbles = false;
    CHECK_THAT(balls_vtp(sim.world(), opt), Contains("NumberOfPoints=\"1\""));
}

TEST_CASE("a clump's pebbles can be filled from its shape to a surface tolerance", "[clump][shape][pebble_fill]") {
    json scene = {{"dimension", 3},
                  {"gravity", {0, 0, 0}},
                  {"timestep", {{"fixed", 1e-3}}},
                  {"bodies", {{{"type", "rigid"}, {"shape", {{"type", "box"}, {"size", {0.1, 0.2, 0.3}}}}, {"density", 1000},
                               {"pebbles", {{"fill", {{"tolerance", 0.02}}}}}, {"position", {1, 2, 3}}}}}};
    {
        Simulation sim(scene);
        const World& w = sim.world();
        REQUIRE(w.clumps.size() == 1);
        CHECK(w.clumps.pebbles_of(0) > 1);
        // every pebble inside the box; the clump's mass the box's, not the pebbles'
        for (std::size_t i = 0; i < w.bodies.size(); ++i) {
            const Vec d = (w.bodies.position[i] - Vec(1, 2, 3)).cwiseAbs() + Vec::Constant(w.bodies.radius[i]);
            CHECK((d.array() <= Vec(0.05, 0.1, 0.15).array() + 1e-12).all());
        }
        CHECK(w.clumps.mass[0] == Approx(1000 * 0.1 * 0.2 * 0.3));
    }
    scene["bodies"][0]["pebbles"]["fill"]["tolerance"] = 0.003;  // would need more than 1000 (sharp edges need small pebbles)
    CHECK_THROWS_WITH(Simulation(scene), Contains("scene.bodies[0].pebbles.fill.tolerance") && Contains("more than 1000 pebbles"));
    scene["bodies"][0]["pebbles"]["fill"]["count"] = 5;  // the user's cap: a warning, and five pebbles
    CHECK(Simulation(scene).world().clumps.pebbles_of(0) == 5);
    scene["bodies"][0].erase("shape");
    CHECK_THROWS_WITH(Simulation(scene), Contains("scene.bodies[0].pebbles") && Contains("give one"));
}
