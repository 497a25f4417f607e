// The pebble fill (scripting/pebble_fill.cpp) on shapes built here, where
// the answer is known: a box and a rectangle (pebbles inside, the surface
// within the reported deviation, checked on a finer sampling of its own),
// an icosphere (one pebble, its inscribed sphere), a ring (no pebble in the
// hole), a count cap, the refusals, and bit-for-bit repeatability.
#include "pebble_fill.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>

using namespace plab;
using Catch::Matchers::Contains;

namespace {


// The triangle, turned if need be so that its normal points along `out`.
Triangle facing(const Vec& a, const Vec& b, const Vec& c, const Vec& out) {
    return (b - a).cross(c - a).dot(out) >= 0 ? Triangle{a, b, c} : Triangle{a, c, b};
}

// A box centred at the origin: two triangles per face, outward normals.
std::vector<Triangle> box(const Vec& half) {
    std::vector<Triangle> t;
    for (int axis = 0; axis < 3; ++axis)
        for (double side : {-1.0, 1.0}) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            std::array<Vec, 4> q;
            for (int k = 0; k < 4; ++k) {
                q[k][axis] = side * half[axis];
                q[k][u] = (k == 1 || k == 2 ? 1 : -1) * half[u];
                q[k][v] = (k >= 2 ? 1 : -1) * half[v];
            }
            const Vec out = side * Vec::Unit(axis);
            t.push_back(facing(q[0], q[1], q[2], out));
            t.push_back(facing(q[0], q[2], q[3], out));
        }
    return t;
}

// A closed polygon as edges (a -> b in each triangle's first two vertices).
std::vector<Triangle> polygon(const std::vector<Vec>& corners) {
    std::vector<Triangle> edges;
    for (std::size_t k = 0; k < corners.size(); ++k) {
        const Vec& a = corners[k];
        const Vec& b = corners[(k + 1) % corners.size()];
        edges.push_back({a, b, b});
    }
    return edges;
}

// A regular n-gon about the origin, counter-clockwise or clockwise, its
// corners at `corner_radius`.
std::vector<Triangle> circle(double corner_radius, int n, bool counter_clockwise) {
    std::vector<Vec> c;
    for (int k = 0; k < n; ++k) {
        const double a = 2 * kPi * k / n * (counter_clockwise ? 1 : -1);
        c.push_back(corner_radius * Vec(std::cos(a), std::sin(a), 0));
    }
    return polygon(c);
}

// An icosahedron on the sphere of `radius`, each triangle cut in four
// `levels` times, the new corners pushed out onto the sphere.
std::vector<Triangle> icosphere(double radius, int levels) {
    const double g = (1 + std::sqrt(5.0)) / 2;
    std::vector<Vec> v;
    for (double s : {-1.0, 1.0})
        for (double t : {-1.0, 1.0}) v.push_back({0, s, t * g}), v.push_back({s, t * g, 0}), v.push_back({t * g, 0, s});
    // The 20 faces: the triples of corners at the edge length 2 from each other.
    std::vector<Triangle> faces;
    for (std::size_t i = 0; i < v.size(); ++i)
        for (std::size_t j = i + 1; j < v.size(); ++j)
            for (std::size_t k = j + 1; k < v.size(); ++k)
                if (std::abs((v[i] - v[j]).norm() - 2) < 1e-9 && std::abs((v[j] - v[k]).norm() - 2) < 1e-9 &&
                    std::abs((v[k] - v[i]).norm() - 2) < 1e-9)
                    faces.push_back({v[i].normalized(), v[j].normalized(), v[k].normalized()});
    for (int level = 0; level < levels; ++level) {
        std::vector<Triangle> finer;
        for (const Triangle& f : faces) {
            const Vec ab = (f[0] + f[1]).normalized(), bc = (f[1] + f[2]).normalized(), ca = (f[2] + f[0]).normalized();
            for (const Triangle& t : {Triangle{f[0], ab, ca}, Triangle{ab, f[1], bc}, Triangle{ca, bc, f[2]}, Triangle{ab, bc, ca}})
                finer.push_back(t);
        }
        faces = finer;
    }
    std::vector<Triangle> out;
    for (const Triangle& f : faces) out.push_back(facing(radius * f[0], radius * f[1], radius * f[2], f[0] + f[1] + f[2]));
    return out;
}

// Distance from p, outside the pebbles, to their union.
double gap_to_union(const Vec& p, const std::vector<Pebble>& pebbles) {
    double gap = kInf;
    for (const Pebble& q : pebbles) gap = std::min(gap, (p - q.centre).norm() - q.radius);
    return gap;
}

// The largest gap to the union over the box's faces sampled every `step`
// (finer than the fill's own samples, and not on them).
double box_surface_gap(const Vec& half, const std::vector<Pebble>& pebbles, int dim, double step) {
    double worst = 0;
    for (int axis = 0; axis < dim; ++axis)
        for (double side : {-1.0, 1.0}) {
            const int u = (axis + 1) % dim, v = (axis + 2) % dim;
            const int nu = int(std::ceil(2 * half[u] / step)), nv = dim == 2 ? 0 : int(std::ceil(2 * half[v] / step));
            for (int i = 0; i <= nu; ++i)
                for (int j = 0; j <= nv; ++j) {
                    Vec p = Vec::Zero();
                    p[axis] = side * half[axis];
                    p[u] = -half[u] + 2 * half[u] * i / nu;
                    if (dim == 3) p[v] = -half[v] + 2 * half[v] * j / nv;
                    worst = std::max(worst, gap_to_union(p, pebbles));
                }
        }
    return worst;
}

void require_inside_box(const std::vector<Pebble>& pebbles, const Vec& half, int dim) {
    for (const Pebble& p : pebbles) {
        REQUIRE(p.radius > 0);
        for (int c = 0; c < dim; ++c) REQUIRE(std::abs(p.centre[c]) + p.radius <= half[c] + 1e-12);
        if (dim == 2) REQUIRE(p.centre.z() == 0);
    }
}

PebbleFillOptions with(int dim, double tolerance) {
    PebbleFillOptions o;
    o.dim = dim;
    o.tolerance = tolerance;
    return o;
}

} // namespace

TEST_CASE("A box is filled to the tolerance with pebbles inside it", "[pebble_fill]") {
    const Vec half(0.5, 0.3, 0.2);
    std::map<double, std::size_t> count;
    for (double t : {0.1, 0.05}) {
        const PebbleFill fill = fill_with_pebbles(box(half), with(3, t));
        INFO("tolerance " << t << ": " << fill.pebbles.size() << " pebbles, deviation " << fill.deviation);
        require_inside_box(fill.pebbles, half, 3);
        CHECK(fill.reached);
        CHECK(fill.deviation <= t);
        CHECK(fill.sampled_deviation <= fill.deviation);
        // The bound holds between the samples too, on a sampling 10 times finer.
        CHECK(box_surface_gap(half, fill.pebbles, 3, t / 10) <= fill.deviation + 1e-12);
        count[t] = fill.pebbles.size();
    }
    CHECK(count[0.05] >= count[0.1]);
}

TEST_CASE("A 2D rectangle is filled with discs in the plane", "[pebble_fill]") {
    const Vec half(0.5, 0.25, 0);
    const std::vector<Triangle> edges =
        polygon({{-half.x(), -half.y(), 0}, {half.x(), -half.y(), 0}, {half.x(), half.y(), 0}, {-half.x(), half.y(), 0}});
    std::map<double, std::size_t> count;
    for (double t : {0.05, 0.02}) {
        const PebbleFill fill = fill_with_pebbles(edges, with(2, t));
        INFO("tolerance " << t << ": " << fill.pebbles.size() << " discs, deviation " << fill.deviation);
        require_inside_box(fill.pebbles, half, 2);
        CHECK(fill.reached);
        CHECK(fill.deviation <= t);
        CHECK(box_surface_gap(half, fill.pebbles, 2, t / 20) <= fill.deviation + 1e-12);
        count[t] = fill.pebbles.size();
    }
    CHECK(count[0.02] >= count[0.05]);
}

TEST_CASE("A sphere's first pebble is its inscribed sphere", "[pebble_fill]") {
    const double R = 1;
    const std::vector<Triangle> mesh = icosphere(R, 2);
    REQUIRE(mesh.size() == 320);
    REQUIRE(mesh_properties(mesh).volume > 0);  // outward normals
    // Chord error: how far inside the sphere the mesh's flattest point lies
    // (the nearest face plane to the centre).
    double chord = 0;
    for (const Triangle& f : mesh) chord = std::max(chord, R - std::abs(f[0].dot((f[1] - f[0]).cross(f[2] - f[0]).normalized())));
    REQUIRE(chord < 0.02);
    PebbleFillOptions o = with(3, 0.2);
    o.max_radius = 2 * R;
    const PebbleFill fill = fill_with_pebbles(mesh, o);
    REQUIRE(!fill.pebbles.empty());
    const Pebble& first = fill.pebbles.front();
    INFO("first pebble r = " << first.radius << " at " << first.centre.transpose() << ", chord error " << chord);
    CHECK(first.radius <= R);
    CHECK(R - first.radius <= chord + 1e-12);
    CHECK(first.centre.norm() <= chord);
    // Within 0.2 of every surface point on its own: the cover needs no other.
    CHECK(fill.pebbles.size() == 1);
    CHECK(fill.reached);
}

TEST_CASE("A count cap stops the fill short of the tolerance and says so", "[pebble_fill]") {
    PebbleFillOptions o = with(3, 0.03);
    o.max_count = 3;
    const PebbleFill fill = fill_with_pebbles(box({0.5, 0.3, 0.2}), o);
    CHECK(fill.pebbles.size() <= 3);
    CHECK_FALSE(fill.reached);
    CHECK(fill.deviation > o.tolerance);
    CHECK(fill.sampled_deviation > o.tolerance / 2);  // some sample is left uncovered
}

TEST_CASE("A 2D ring's discs stay out of its hole", "[pebble_fill]") {
    const double outer = 1, inner = 0.5;
    // The outer polygon inside its circle, the hole's outside its circle
    // (corners at inner / cos(pi / n)): the ring polygon lies within the ring.
    std::vector<Triangle> edges = circle(outer, 96, true);
    for (const Triangle& e : circle(inner / std::cos(kPi / 48), 48, false)) edges.push_back(e);
    const PebbleFill fill = fill_with_pebbles(edges, with(2, 0.05));
    INFO(fill.pebbles.size() << " discs, deviation " << fill.deviation);
    CHECK(fill.reached);
    for (const Pebble& p : fill.pebbles) {
        REQUIRE(p.centre.z() == 0);
        REQUIRE(p.centre.norm() - p.radius >= inner - 1e-12);
        REQUIRE(p.centre.norm() + p.radius <= outer + 1e-12);
    }
}

TEST_CASE("The pebble fill refuses bad input naming what is wrong", "[pebble_fill]") {
    const std::vector<Triangle> b = box({0.5, 0.3, 0.2});
    CHECK_THROWS_WITH(fill_with_pebbles(b, with(3, 0)), Contains("tolerance must be positive") && Contains("got 0 m"));
    CHECK_THROWS_AS(fill_with_pebbles(b, with(3, -1)), std::invalid_argument);
    CHECK_THROWS_WITH(fill_with_pebbles({}, with(3, 0.1)), Contains("no triangles"));
    PebbleFillOptions o = with(3, 0.1);
    o.min_radius = 0.3;  // the box's smallest half-extent is 0.2
    CHECK_THROWS_WITH(fill_with_pebbles(b, o), Contains("no pebble of min_radius 0.3 m fits") && Contains("the largest that does is 0.2 m"));
    o.max_radius = 0.1;
    CHECK_THROWS_WITH(fill_with_pebbles(b, o), Contains("min_radius 0.3 m is larger than max_radius 0.1 m"));
    std::vector<Triangle> inverted = b;
    for (Triangle& t : inverted) std::swap(t[1], t[2]);
    CHECK_THROWS_WITH(fill_with_pebbles(inverted, with(3, 0.1)), Contains("encloses no volume") && Contains("outward normals"));
}

TEST_CASE("The pebble fill repeats itself bit for bit", "[pebble_fill]") {
    std::vector<Triangle> ring = circle(1, 64, true);
    for (const Triangle& e : circle(0.4, 32, false)) ring.push_back(e);
    for (const auto& [surface, dim] : {std::pair{box({0.5, 0.3, 0.2}), 3}, std::pair{ring, 2}}) {
        const PebbleFill a = fill_with_pebbles(surface, with(dim, 0.05));
        const PebbleFill b = fill_with_pebbles(surface, with(dim, 0.05));
        REQUIRE(a.pebbles.size() == b.pebbles.size());
        for (std::size_t k = 0; k < a.pebbles.size(); ++k) {
            REQUIRE(std::memcmp(a.pebbles[k].centre.data(), b.pebbles[k].centre.data(), 3 * sizeof(double)) == 0);
            REQUIRE(std::memcmp(&a.pebbles[k].radius, &b.pebbles[k].radius, sizeof(double)) == 0);
        }
        CHECK(std::memcmp(&a.deviation, &b.deviation, sizeof(double)) == 0);
    }
}

