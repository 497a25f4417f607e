// Balls on mesh walls: a mesh floor bounces a ball as the same two
// triangles given in the scene do (the same bits) and as a plane does; a
// ball rolling over the shared edge of two coplanar triangles feels no
// kick; a closed mesh box carries the weight of the pile it holds.
#include "../support/mesh_files.hpp"
#include "simulation.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace plab;
using namespace plab::testing_support;

namespace {

constexpr double kR = 0.01, kRho = 2500, kKn = 1e4, kG = 9.81;
const double kMass = kRho * 4.0 / 3.0 * M_PI * kR * kR * kR;

// The floor z = 0 over [-1/8, 1/8]^2 as two triangles sharing the diagonal
// y = x (float32-exact corners: an STL holds floats).
std::vector<Triangle> floor_triangles() {
    const double h = 0.125;
    return {{Vec(-h, -h, 0), Vec(h, -h, 0), Vec(h, h, 0)}, {Vec(-h, -h, 0), Vec(h, h, 0), Vec(-h, h, 0)}};
}

json triangles_wall(const std::vector<Triangle>& t) {
    json vertices = json::array(), tris = json::array();
    for (const Triangle& tri : t) {
        for (const Vec& v : tri) vertices.push_back({v.x(), v.y(), v.z()});
        tris.push_back({vertices.size() - 3, vertices.size() - 2, vertices.size() - 1});
    }
    return {{"type", "triangles"}, {"name", "floor"}, {"vertices", vertices}, {"triangles", tris}};
}

json one_ball_scene(const json& walls, const json& position, const json& velocity, const json& spin) {
    return {{"dimension", 3},
            {"gravity", {0, 0, -kG}},
            {"plugins", {"linear"}},
            {"timestep", {{"fixed", 2e-5}}},
            {"bodies", {{{"type", "ball"}, {"group", "ball"}, {"position", position}, {"radius", kR}, {"density", kRho},
                         {"velocity", velocity}, {"angular_velocity", spin}}}},
            {"walls", walls},
            {"contact_models", {{{"groups", {"ball", "walls"}}, {"model", "linear"},
                                 {"properties", {{"kn", kKn}, {"ks", kKn}, {"fric", 0.5}, {"dp_nratio", 0.2}}}}}}};
}

// The ball's height after every step, and its vertical velocity.
struct Track {
    std::vector<Vec> position, velocity;
};
Track track(const json& scene, const std::string& dir, int steps) {
    Simulation sim(scene, dir);
    sim.set_quiet(true);
    World& w = sim.world();
    w.prepare();
    Track t;
    for (int k = 0; k < steps; ++k) {
        w.step();
        t.position.push_back(w.bodies.position[0]);
        t.velocity.push_back(w.bodies.velocity[0]);
    }
    return t;
}

// The highest the centre gets after the first bounce (its velocity has turned up).
double rebound_height(const Track& t) {
    std::size_t k = 0;
    while (k < t.velocity.size() && t.velocity[k].z() <= 0) ++k;
    double top = -kInf;
    for (; k < t.position.size(); ++k) top = std::max(top, t.position[k].z());
    return top;
}

} // namespace

TEST_CASE("a ball dropped on a mesh floor bounces as on the same triangles given in the scene (same bits) and on a "
          "plane (rebound height within 1e-9 relative)", "[mesh][physics]") {
    const auto dir = mesh_dir("bounce");
    write_file(dir / "floor.stl", binary_stl(floor_triangles()));
    const json at = {0.013, -0.021, 0.05}, still = {0, 0, 0};
    // 0.16 s: the fall of 0.04 m (0.09 s), the bounce (~3 ms), the rise to the top (~0.05 s)
    const int steps = 8000;
    const Track mesh = track(one_ball_scene({{{"type", "mesh"}, {"name", "floor"}, {"file", "floor.stl"}}}, at, still, still),
                             dir.string(), steps);
    const Track listed = track(one_ball_scene(json::array({triangles_wall(floor_triangles())}), at, still, still), dir.string(), steps);
    const Track plane = track(one_ball_scene({{{"type", "plane"}, {"point", {0, 0, 0}}, {"normal", {0, 0, 1}}}}, at, still, still),
                              dir.string(), steps);
    for (int k = 0; k < steps; ++k) REQUIRE(mesh.position[std::size_t(k)] == listed.position[std::size_t(k)]);
    const double h_mesh = rebound_height(mesh), h_plane = rebound_height(plane);
    // a bounce happened and lost energy (restitution ~0.53 for dp_nratio 0.2: rebound ~0.28 of the 0.04 m drop)
    CHECK(h_mesh - kR > 0.2 * 0.04);
    CHECK(h_mesh - kR < 0.4 * 0.04);
    CHECK(std::fabs(h_mesh - h_plane) <= 1e-9 * h_plane);
    std::filesystem::remove_all(dir);
}

TEST_CASE("a ball rolling across the shared edge of two coplanar mesh triangles keeps its vertical velocity ~0 "
          "(< 1e-6 m/s), where two separate walls kick it", "[mesh][physics]") {
    const auto dir = mesh_dir("rolling");
    write_file(dir / "floor.stl", binary_stl(floor_triangles()));
    const std::vector<Triangle> t = floor_triangles();
    // resting on the floor (the linear model's overlap m g / kn), rolling at 0.5 m/s along x without slip
    // (the contact point is in the middle of the overlap, r - overlap / 2 below the centre), across the
    // diagonal y = x at x = 0.04: at t ~ 0.12 s
    const double v = 0.5, overlap = kMass * kG / kKn;
    const json at = {-0.02, 0.04, kR - overlap}, velocity = {v, 0, 0}, spin = {0, v / (kR - overlap / 2), 0};
    const int steps = 8000;  // 0.16 s: 0.08 m of travel
    auto max_vz = [](const Track& tr) {
        double m = 0;
        for (const Vec& u : tr.velocity) m = std::max(m, std::fabs(u.z()));
        return m;
    };
    const Track mesh = track(one_ball_scene({{{"type", "mesh"}, {"name", "floor"}, {"file", "floor.stl"}}}, at, velocity, spin),
                             dir.string(), steps);
    REQUIRE(mesh.position.back().x() > 0.05);  // it crossed the edge (at x = 0.04 on its line)
    json one = triangles_wall({t[0]}), other = triangles_wall({t[1]});
    other["name"] = "floor2";
    const Track apart = track(one_ball_scene(json::array({one, other}), at, velocity, spin), dir.string(), steps);
    const Track plane = track(one_ball_scene({{{"type", "plane"}, {"point", {0, 0, 0}}, {"normal", {0, 0, 1}}}}, at, velocity, spin),
                              dir.string(), steps);
    INFO("max |vz|: mesh " << max_vz(mesh) << ", plane " << max_vz(plane) << ", two walls " << max_vz(apart));
    CHECK(max_vz(plane) < 1e-6);
    CHECK(max_vz(mesh) < 1e-6);
    CHECK(max_vz(apart) > 1e-3);  // the test can see a kick: each wall pushes on its own
    INFO("x after 0.16 s: mesh " << mesh.position.back().x() << ", plane " << plane.position.back().x());
    CHECK(std::fabs(mesh.position.back().x() - plane.position.back().x()) < 1e-9);
    std::filesystem::remove_all(dir);
}

TEST_CASE("the force on a closed mesh box holding a resting pile is the pile's weight within 1 %", "[mesh][physics]") {
    const auto dir = mesh_dir("pile");
    write_file(dir / "box.stl", binary_stl(cube_triangles()));
    const json scene = {
        {"dimension", 3},
        {"gravity", {0, 0, -kG}},
        {"plugins", {"linear"}},
        {"bodies", {{{"type", "random_fill"}, {"group", "grains"}, {"box", {{"min", {0.01, 0.01, 0.01}}, {"max", {0.19, 0.19, 0.19}}}},
                     {"radius", kR}, {"count", 300}, {"density", kRho}, {"local_damping", 0.7}}}},
        {"walls", {{{"type", "mesh"}, {"name", "box"}, {"file", "box.stl"}, {"scale", 0.2}}}},
        {"contact_models", {{{"groups", {"*", "*"}}, {"model", "linear"},
                             {"properties", {{"kn", 1e5}, {"ks", 1e5}, {"fric", 0.5}, {"dp_nratio", 0.2}}}}}},
        {"commands", {{{"solve", {{"ratio", 1e-4}, {"max_cycles", 200000}}}}}}};
    Simulation sim(scene, dir.string());
    sim.set_quiet(true);
    sim.run();
    const World& w = sim.world();
    double weight = 0;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) weight += w.bodies.mass[i] * kG;
    for (const Vec& x : w.bodies.position) REQUIRE((x.array() > 0).all());  // none left through a face
    const Vec f = w.walls.walls[0].force;
    INFO("wall force " << f.transpose() << " N, weight " << weight << " N");
    CHECK(std::fabs(-f.z() - weight) <= 0.01 * weight);
    CHECK(std::hypot(f.x(), f.y()) <= 0.01 * weight);  // the side faces' pushes cancel
    std::filesystem::remove_all(dir);
}
