// Body shapes (body_shapes.hpp). Mass properties are exact (analytic, or
// the divergence theorem for a mesh); the surface of a round shape is a
// polygon or polyhedron with its vertices on the true surface, for drawing
// and sampling only.
#include "body_shapes.hpp"

#include "generators.hpp"
#include "mesh_reader.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace plab {

namespace {

constexpr int kCircleSides = 48;       // a circle's polygon on the surface
// an icosahedron's subdivisions: a sphere shape's 320 triangles, a pebble's 80
constexpr int kShapeSubdivisions = 2, kPebbleSubdivisions = 1;

std::int32_t add_vertex(BodySurface& s, const Vec& v) {
    s.vertices.push_back(v);
    return std::int32_t(s.vertices.size() - 1);
}

// The circle of radius r about the z axis at height z, kCircleSides points.
std::vector<std::int32_t> circle(BodySurface& s, double r, double z) {
    std::vector<std::int32_t> ring;
    for (int k = 0; k < kCircleSides; ++k) {
        const double a = 2 * kPi * k / kCircleSides;
        ring.push_back(add_vertex(s, Vec(r * std::cos(a), r * std::sin(a), z)));
    }
    return ring;
}

// 2D: a circle's edges, counter-clockwise (an outside boundary) or not (a hole).
void circle_edges(BodySurface& s, double r, bool counter_clockwise) {
    const std::vector<std::int32_t> c = circle(s, r, 0);
    for (int k = 0; k < kCircleSides; ++k) {
        const std::int32_t a = c[k], b = c[(k + 1) % kCircleSides];
        s.faces.push_back(counter_clockwise ? std::array<std::int32_t, 3>{a, b, a} : std::array<std::int32_t, 3>{b, a, b});
    }
}

// An icosahedron, each triangle split in four `levels` times, pushed out to
// the sphere.
BodySurface sphere_surface(double r, int levels) {
    BodySurface s;
    const double t = (1 + std::sqrt(5.0)) / 2;
    for (const Vec& v : {Vec(-1, t, 0), Vec(1, t, 0), Vec(-1, -t, 0), Vec(1, -t, 0), Vec(0, -1, t), Vec(0, 1, t),
                         Vec(0, -1, -t), Vec(0, 1, -t), Vec(t, 0, -1), Vec(t, 0, 1), Vec(-t, 0, -1), Vec(-t, 0, 1)})
        add_vertex(s, r * v.normalized());
    s.faces = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
               {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> middle;
        const auto mid = [&](std::int32_t a, std::int32_t b) {
            const auto key = std::minmax(a, b);
            const auto it = middle.find(key);
            if (it != middle.end()) return it->second;
            const std::int32_t m = add_vertex(s, r * (s.vertices[a] + s.vertices[b]).normalized());
            return middle[key] = m;
        };
        std::vector<std::array<std::int32_t, 3>> finer;
        for (const auto& [a, b, c] : s.faces) {
            const std::int32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
            finer.insert(finer.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
        }
        s.faces = std::move(finer);
    }
    return s;
}

// 2D: the rectangle's edges, counter-clockwise; 3D: the box's 12 triangles.
BodySurface box_surface(const Vec& h, int dim) {
    BodySurface s;
    if (dim == 2) {
        s.edges = true;
        for (const Vec& v : {Vec(-h.x(), -h.y(), 0), Vec(h.x(), -h.y(), 0), Vec(h.x(), h.y(), 0), Vec(-h.x(), h.y(), 0)})
            add_vertex(s, v);
        s.faces = {{0, 1, 0}, {1, 2, 1}, {2, 3, 2}, {3, 0, 3}};
        return s;
    }
    for (int k = 0; k < 8; ++k) add_vertex(s, Vec(k & 1 ? h.x() : -h.x(), k & 2 ? h.y() : -h.y(), k & 4 ? h.z() : -h.z()));
    s.faces = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
               {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    return s;
}

// A cylinder (inner = 0) or a ring about z, height h centred at the origin:
// its caps and walls as triangles.
BodySurface prism_surface(double outer, double inner, double h) {
    BodySurface s;
    const auto bottom = circle(s, outer, -h / 2), top = circle(s, outer, h / 2);
    std::vector<std::int32_t> inner_bottom, inner_top;
    if (inner > 0) {
        inner_bottom = circle(s, inner, -h / 2);
        inner_top = circle(s, inner, h / 2);
    } else {
        inner_bottom.assign(kCircleSides, add_vertex(s, Vec(0, 0, -h / 2)));  // a fan about the axis
        inner_top.assign(kCircleSides, add_vertex(s, Vec(0, 0, h / 2)));
    }
    for (int k = 0; k < kCircleSides; ++k) {
        const int n = (k + 1) % kCircleSides;
        s.faces.push_back({bottom[k], bottom[n], top[k]});  // the outer wall, facing out
        s.faces.push_back({bottom[n], top[n], top[k]});
        s.faces.push_back({top[k], top[n], inner_top[k]});  // the top cap, facing +z
        if (inner > 0) s.faces.push_back({top[n], inner_top[n], inner_top[k]});
        s.faces.push_back({bottom[k], inner_bottom[k], bottom[n]});  // the bottom cap, facing -z
        if (inner > 0) {
            s.faces.push_back({bottom[n], inner_bottom[k], inner_bottom[n]});
            s.faces.push_back({inner_bottom[k], inner_top[k], inner_bottom[n]});  // the inner wall, facing the axis
            s.faces.push_back({inner_bottom[n], inner_top[k], inner_top[n]});
        }
    }
    return s;
}

// `part` moved by the turn q and the shift t, added to `into`.
void append(BodySurface& into, const BodySurface& part, const Eigen::Quaterniond& q, const Vec& t) {
    const std::int32_t base = std::int32_t(into.vertices.size());
    for (const Vec& v : part.vertices) into.vertices.push_back(q * v + t);
    for (const auto& f : part.faces) into.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
    into.edges = part.edges;
}

// The mass properties of a part turned by q and shifted by t.
MassProperties moved(const MassProperties& p, const Eigen::Quaterniond& q, const Vec& t) {
    const Eigen::Matrix3d R = q.toRotationMatrix();
    return {p.volume, q * p.centroid + t, R * p.inertia * R.transpose()};
}

// Parts that do not overlap: volumes add, the inertia about the common
// centroid by the parallel-axis theorem.
MassProperties combined(const std::vector<MassProperties>& parts) {
    MassProperties sum;
    for (const MassProperties& p : parts) {
        sum.volume += p.volume;
        sum.centroid += p.volume * p.centroid;
    }
    sum.centroid /= sum.volume;
    for (const MassProperties& p : parts) {
        const Vec d = p.centroid - sum.centroid;
        sum.inertia += p.inertia + p.volume * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
    }
    return sum;
}

double planar_radius2(const Vec& p) { return p.x() * p.x() + p.y() * p.y(); }

std::vector<const char*> with(std::vector<const char*> keys, const std::vector<const char*>& extra) {
    keys.insert(keys.end(), extra.begin(), extra.end());
    return keys;
}

BodyShape sphere_shape(const Node& s, int dim, const std::vector<const char*>& extra) {
    s.allow_keys(with({"type", "radius"}, extra));
    const double r = s.at("radius").positive();
    BodyShape b;
    b.properties = dim == 2 ? cylinder_properties(r, 1.0) : sphere_properties(r);
    if (dim == 2) {
        b.surface.edges = true;
        circle_edges(b.surface, r, true);
    } else {
        b.surface = sphere_surface(r, kShapeSubdivisions);
    }
    b.inside = [r, dim](const Vec& p) { return (dim == 2 ? planar_radius2(p) : p.squaredNorm()) < r * r; };
    return b;
}

BodyShape box_shape(const Node& s, int dim, const std::vector<const char*>& extra) {
    s.allow_keys(with({"type", "size"}, extra));
    Vec half = 0.5 * s.at("size").vec(dim);
    if (dim == 2) half.z() = 0.5;
    for (int c = 0; c < 3; ++c)
        if (!(half[c] > 0)) s.at("size").fail("every edge of a box must be positive, got " + show(s.at("size").value()));
    BodyShape b;
    b.properties = box_properties(half);
    b.surface = box_surface(half, dim);
    b.inside = [half, dim](const Vec& p) {
        for (int c = 0; c < dim; ++c)
            if (!(std::fabs(p[c]) < half[c])) return false;
        return true;
    };
    return b;
}

// A cylinder (no inner radius) or a ring; 2D: a ring is an annulus.
BodyShape round_shape(const Node& s, const std::string& type, int dim, const std::vector<const char*>& extra) {
    const bool ring = type == "ring";
    s.allow_keys(with(ring ? std::vector<const char*>{"type", "outer_radius", "inner_radius", "height"}
                           : std::vector<const char*>{"type", "radius", "height"},
                      extra));
    const double outer = s.at(ring ? "outer_radius" : "radius").positive();
    const double inner = ring ? s.at("inner_radius").number(0, outer, false, true) : 0.0;
    const double h = dim == 2 ? 1.0 : s.at("height").positive();
    BodyShape b;
    b.properties = ring ? ring_properties(outer, inner, h) : cylinder_properties(outer, h);
    if (dim == 2) {
        b.surface.edges = true;
        circle_edges(b.surface, outer, true);
        if (inner > 0) circle_edges(b.surface, inner, false);
    } else {
        b.surface = prism_surface(outer, inner, h);
    }
    b.inside = [outer, inner, h, dim](const Vec& p) {
        const double r2 = planar_radius2(p);
        return r2 < outer * outer && r2 > inner * inner && (dim == 2 || std::fabs(p.z()) < h / 2);
    };
    return b;
}

BodyShape mesh_shape(const Node& s, const std::string& scene_dir) {
    s.allow_keys({"type", "file", "scale"});
    const std::string file = s.at("file").string();
    const MeshFile m = read_mesh(scene_path(scene_dir, file), file, s.at("file").path());
    const double scale = s.number_or("scale", 1.0, 0.0, kInf, true, true);
    BodyShape b;
    std::vector<Triangle> triangles = m.triangles;
    for (Triangle& t : triangles) {
        const std::int32_t k = std::int32_t(b.surface.vertices.size());
        for (Vec& v : t) b.surface.vertices.push_back(v *= scale);
        b.surface.faces.push_back({k, k + 1, k + 2});
    }
    b.properties = mesh_properties(triangles);
    if (!(b.properties.volume > 0))
        s.at("file").fail("\"" + file + "\" encloses no positive volume (" + std::to_string(b.properties.volume) +
                          " m3): a closed mesh with outward normals is needed for the body's mass");
    return b;
}

BodyShape analytic_shape(const Node& s, const std::string& type, int dim, const std::vector<const char*>& extra) {
    if (type == "sphere") return sphere_shape(s, dim, extra);
    if (type == "box") return box_shape(s, dim, extra);
    if (dim == 2 && type == "cylinder")
        s.at("type").fail("shape \"cylinder\" needs a 3D scene (a 2D scene's round shapes: sphere (a disc), ring)");
    return round_shape(s, type, dim, extra);
}

struct Placed {
    BodyShape shape;
    Eigen::Quaterniond turn;
    Vec shift;
    Vec lo, hi;  // its box in the union's frame
};

// Fails if two parts share volume: a grid of 24^d points over the overlap of
// their boxes, none inside both (touching faces are allowed).
void check_disjoint(const Node& parts, const std::vector<Placed>& p, int dim) {
    constexpr int n = 24;
    for (std::size_t i = 0; i < p.size(); ++i)
        for (std::size_t j = i + 1; j < p.size(); ++j) {
            const Vec lo = p[i].lo.cwiseMax(p[j].lo), hi = p[i].hi.cwiseMin(p[j].hi);
            if (!((hi - lo).head(dim).minCoeff() > 0)) continue;
            for (int a = 0; a < n; ++a)
                for (int b = 0; b < n; ++b)
                    for (int c = 0; c < (dim == 3 ? n : 1); ++c) {
                        const Vec f((a + 0.5) / n, (b + 0.5) / n, dim == 3 ? (c + 0.5) / n : 0.0);
                        const Vec x = lo + f.cwiseProduct(hi - lo);
                        const auto in = [&](const Placed& q) { return q.shape.inside(q.turn.conjugate() * (x - q.shift)); };
                        if (in(p[i]) && in(p[j]))
                            parts.at(j).fail("overlaps part " + std::to_string(i) +
                                             ": a union's parts must not share volume (its mass would count it twice); "
                                             "split them so that they only touch");
                    }
        }
}

// {"type": "union", "parts": [{"type": ..., "position", "orientation"}, ...]}:
// analytic parts placed in the body frame, touching but not overlapping.
BodyShape union_shape(const Node& s, int dim) {
    s.allow_keys({"type", "parts"});
    const Node parts = s.at("parts");
    parts.expect_array();
    if (parts.size() < 1 || parts.size() > 1000) parts.fail("a union has 1 to 1000 parts, got " + std::to_string(parts.size()));
    std::vector<Placed> placed;
    for (std::size_t k = 0; k < parts.size(); ++k) {
        const Node part = parts.at(k);
        const std::string type = part.at("type").choice({"sphere", "box", "cylinder", "ring"});
        Placed p{analytic_shape(part, type, dim, {"position", "orientation"}), Eigen::Quaterniond::Identity(),
                 part.vec_or("position", dim, Vec::Zero()), Vec::Constant(kInf), Vec::Constant(-kInf)};
        if (part.has("orientation")) p.turn = read_orientation(part.at("orientation"), dim);
        for (const Vec& v : p.shape.surface.vertices) {
            p.lo = p.lo.cwiseMin(p.turn * v + p.shift);
            p.hi = p.hi.cwiseMax(p.turn * v + p.shift);
        }
        const Vec pad = 0.01 * (p.hi - p.lo);  // a round part bulges past its polygon's vertices
        p.lo -= pad;
        p.hi += pad;
        placed.push_back(std::move(p));
    }
    check_disjoint(parts, placed, dim);
    BodyShape u;
    std::vector<MassProperties> props;
    for (const Placed& p : placed) {
        props.push_back(moved(p.shape.properties, p.turn, p.shift));
        append(u.surface, p.shape.surface, p.turn, p.shift);
    }
    u.properties = combined(props);
    u.inside = [placed](const Vec& x) {
        for (const Placed& p : placed)
            if (p.shape.inside(p.turn.conjugate() * (x - p.shift))) return true;
        return false;
    };
    return u;
}

} // namespace

Eigen::Quaterniond read_orientation(const Node& n, int dim) {
    if (dim == 2) return Eigen::Quaterniond(Eigen::AngleAxisd(n.number() * kPi / 180, Vec::UnitZ()));
    if (n.value().is_array()) {
        if (n.size() != 4) n.fail("expected a quaternion [w, x, y, z] or {\"axis\", \"angle\"}, got " + show(n.value()));
        Eigen::Quaterniond q(n.at(0).number(), n.at(1).number(), n.at(2).number(), n.at(3).number());
        if (!(std::fabs(q.norm() - 1) < 1e-6)) n.fail("a quaternion must have norm 1 (within 1e-6), got " + show(n.value()));
        return q.normalized();
    }
    n.allow_keys({"axis", "angle"});
    const Vec axis = n.at("axis").vec(3);
    if (!(axis.norm() > 0)) n.at("axis").fail("the axis must not be zero, got " + show(n.at("axis").value()));
    return Eigen::Quaterniond(Eigen::AngleAxisd(n.at("angle").number() * kPi / 180, axis.normalized()));
}

BodyShape read_shape(const Node& s, int dim, const std::string& scene_dir) {
    const std::string type = s.at("type").choice({"sphere", "box", "cylinder", "ring", "mesh", "union"});
    if (type == "union") return union_shape(s, dim);
    if (type == "mesh") {
        if (dim == 2) s.at("type").fail("shape \"mesh\" needs a 3D scene (a 2D scene's shapes: sphere (a disc), box, ring, union)");
        return mesh_shape(s, scene_dir);
    }
    return analytic_shape(s, type, dim, {});
}

BodySurface pebbles_surface(const std::vector<Pebble>& pebbles, int dim) {
    BodySurface s;
    for (const Pebble& p : pebbles) {
        BodySurface one;
        if (dim == 2) {
            one.edges = true;
            circle_edges(one, p.radius, true);
        } else {
            one = sphere_surface(p.radius, kPebbleSubdivisions);
        }
        append(s, one, Eigen::Quaterniond::Identity(), p.centre);
    }
    return s;
}

std::vector<Triangle> surface_triangles(const BodySurface& s) {
    std::vector<Triangle> t;
    t.reserve(s.faces.size());
    for (const auto& f : s.faces) t.push_back({s.vertices[f[0]], s.vertices[f[1]], s.vertices[f[2]]});
    return t;
}

} // namespace plab
