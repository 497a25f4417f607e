// Walls from a scene: segment / polyline / box (2D and 3D), plane,
// rectangle, triangle lists and mesh files (3D). Each wall moves rigidly.
#include "generators.hpp"
#include "mesh_reader.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

namespace plab {

namespace {

void add_segment(World& w, int wall, const Vec& a, const Vec& b) {
    Facet f;
    f.kind = FacetKind::segment;
    f.a = a;
    f.b = b;
    w.walls.add_facet(wall, f);
}

void add_triangle(World& w, int wall, const Vec& a, const Vec& b, const Vec& c) {
    Facet f;
    f.kind = FacetKind::triangle;
    f.a = a;
    f.b = b;
    f.c = c;
    w.walls.add_facet(wall, f);
}

void add_rectangle(World& w, int wall, const Vec& a, const Vec& b, const Vec& c, const Vec& d) {
    add_triangle(w, wall, a, b, c);
    add_triangle(w, wall, a, c, d);
}

void require_dim(const Node& n, const World& w, int dim, const std::string& type) {
    if (w.dim != dim) n.at("type").fail("wall type \"" + type + "\" needs a " + std::to_string(dim) + "D scene");
}

// A box of walls; `open` names faces left out ("top" = +y in 2D, +z in 3D).
void box(const Node& n, World& w, int wall) {
    const Vec lo = n.at("min").vec(w.dim), hi = n.at("max").vec(w.dim);
    for (int c = 0; c < w.dim; ++c)
        if (!(lo[c] < hi[c])) n.at("max").fail("box max must exceed min in every direction");
    std::vector<std::string> open;
    if (n.has("open")) {
        const Node o = n.at("open");
        o.expect_array();
        for (std::size_t i = 0; i < o.size(); ++i)
            open.push_back(o.at(i).choice({"left", "right", "bottom", "top", "front", "back"}));
    }
    auto is_open = [&](const char* face) { return std::find(open.begin(), open.end(), face) != open.end(); };
    if (w.dim == 2) {
        const Vec p00(lo.x(), lo.y(), 0), p10(hi.x(), lo.y(), 0), p11(hi.x(), hi.y(), 0), p01(lo.x(), hi.y(), 0);
        if (!is_open("bottom")) add_segment(w, wall, p00, p10);
        if (!is_open("right")) add_segment(w, wall, p10, p11);
        if (!is_open("top")) add_segment(w, wall, p11, p01);
        if (!is_open("left")) add_segment(w, wall, p01, p00);
        return;
    }
    auto corner = [&](int i, int j, int k) { return Vec(i ? hi.x() : lo.x(), j ? hi.y() : lo.y(), k ? hi.z() : lo.z()); };
    if (!is_open("left")) add_rectangle(w, wall, corner(0, 0, 0), corner(0, 1, 0), corner(0, 1, 1), corner(0, 0, 1));
    if (!is_open("right")) add_rectangle(w, wall, corner(1, 0, 0), corner(1, 1, 0), corner(1, 1, 1), corner(1, 0, 1));
    if (!is_open("front")) add_rectangle(w, wall, corner(0, 0, 0), corner(1, 0, 0), corner(1, 0, 1), corner(0, 0, 1));
    if (!is_open("back")) add_rectangle(w, wall, corner(0, 1, 0), corner(1, 1, 0), corner(1, 1, 1), corner(0, 1, 1));
    if (!is_open("bottom")) add_rectangle(w, wall, corner(0, 0, 0), corner(1, 0, 0), corner(1, 1, 0), corner(0, 1, 0));
    if (!is_open("top")) add_rectangle(w, wall, corner(0, 0, 1), corner(1, 0, 1), corner(1, 1, 1), corner(0, 1, 1));
}

// A mesh's placement in the scene: x' = R (S x) + t, the file's
// coordinates scaled per axis (e.g. 0.001 for a CAD file in mm), rotated
// about the origin (e.g. an OBJ's y-up to the scene's z-up), then moved.
struct Placement {
    Vec scale = Vec::Ones(), translate = Vec::Zero();
    Eigen::Matrix3d rotate = Eigen::Matrix3d::Identity();
    Vec operator()(const Vec& x) const { return rotate * scale.cwiseProduct(x) + translate; }
};

Placement mesh_placement(const Node& n) {
    Placement p;
    if (n.has("scale")) {
        const Node s = n.at("scale");
        if (s.value().is_number()) p.scale = Vec::Constant(s.positive());
        else if (s.value().is_array() && s.size() == 3) for (int c = 0; c < 3; ++c) p.scale[c] = s.at(std::size_t(c)).positive();
        else s.fail("expected a number or 3 numbers (per axis), each > 0, got " + show(s.value()));
    }
    p.translate = n.vec_or("translate", 3, Vec::Zero());
    if (n.has("rotate")) {
        const Node r = n.at("rotate");
        r.allow_keys({"axis", "angle"});
        const Vec axis = r.at("axis").vec(3);
        if (axis.norm() == 0) r.at("axis").fail("the rotation axis must not be zero");
        const double degrees = r.at("angle").number(-360, 360);
        p.rotate = Eigen::AngleAxisd(degrees * M_PI / 180, axis.normalized()).toRotationMatrix();
    }
    return p;
}

std::string text(const Vec& v) {
    std::ostringstream s;
    s << "[" << short_number(v.x()) << ", " << short_number(v.y()) << ", " << short_number(v.z()) << "]";
    return s.str();
}

// A mesh file's triangles, each a triangle facet of the one wall (so the
// wall's force and moment sum over them, and a ball on a shared edge is
// pushed once: resolve_wall_features works within a wall).
void mesh(const Node& n, World& w, int wall, const std::string& scene_dir) {
    if (w.dim != 3)
        n.at("type").fail("wall type \"mesh\" needs a 3D scene (a 2D scene's walls are segments: use \"polyline\")");
    const std::string file = n.at("file").string();
    const MeshFile m = read_mesh(scene_path(scene_dir, file), file, n.at("file").path());
    const Placement place = mesh_placement(n);
    Vec lo = Vec::Constant(kInf), hi = Vec::Constant(-kInf);
    for (const Triangle& t : m.triangles) {
        const Vec a = place(t[0]), b = place(t[1]), c = place(t[2]);
        for (const Vec& p : {a, b, c}) {
            if (!p.allFinite())
                n.at(n.has("scale") ? "scale" : "translate").fail("the placed mesh has a vertex beyond the range of doubles");
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
        }
        add_triangle(w, wall, a, b, c);
    }
    if (m.degenerate)
        spdlog::warn("{}: \"{}\": left out {} zero-area triangle{} ({}): no face a ball could touch", n.at("file").path(), file,
                     m.degenerate, m.degenerate > 1 ? "s" : "", m.degenerate_where);
    if (!m.ignored.empty())
        spdlog::warn("{}: \"{}\": OBJ statements other than v and f left out, the first {}", n.at("file").path(), file, m.ignored);
    spdlog::info("{}: {} triangles from \"{}\" ({}), in the scene from {} to {} m", n.path(), m.triangles.size(), file,
                 m.format, text(lo), text(hi));
}

} // namespace

void generate_wall(const Node& n, World& w, const std::string& scene_dir) {
    const std::string type =
        n.at("type").choice({"segment", "polyline", "box", "plane", "rectangle", "triangles", "mesh"});
    std::vector<const char*> keys = {"type", "name", "group", "velocity", "angular_velocity", "centre"};
    if (type == "segment") keys.insert(keys.end(), {"from", "to"});
    if (type == "polyline") keys.insert(keys.end(), {"points", "closed"});
    if (type == "box") keys.insert(keys.end(), {"min", "max", "open"});
    if (type == "plane") keys.insert(keys.end(), {"point", "normal"});
    if (type == "rectangle") keys.insert(keys.end(), {"corners"});
    if (type == "triangles") keys.insert(keys.end(), {"vertices", "triangles"});
    if (type == "mesh") keys.insert(keys.end(), {"file", "scale", "translate", "rotate"});
    // allow_keys takes an initializer list; check by hand for this variable set
    n.expect_object();
    for (auto it = n.value().begin(); it != n.value().end(); ++it) {
        if (std::find_if(keys.begin(), keys.end(), [&](const char* k) { return it.key() == k; }) != keys.end()) continue;
        std::string list;
        for (const char* k : keys) list += (list.empty() ? "" : ", ") + std::string(k);
        throw InputError(n.path() + "." + it.key(), "unknown key '" + it.key() + "' for a " + type + " wall; allowed: " + list);
    }
    Wall wall;
    wall.name = n.string_or("name", "wall" + std::to_string(w.walls.walls.size()));
    if (w.walls.find(wall.name) >= 0) n.at("name").fail("a wall named \"" + wall.name + "\" already exists");
    wall.group = w.group_index(n.string_or("group", "walls"));
    wall.velocity = n.vec_or("velocity", w.dim, Vec::Zero());
    if (n.has("angular_velocity")) {
        if (w.dim == 2) wall.angular_velocity.z() = n.at("angular_velocity").number();
        else wall.angular_velocity = n.at("angular_velocity").vec(3);
    }
    wall.centre = n.vec_or("centre", w.dim, Vec::Zero());
    const int id = w.walls.add_wall(wall);
    if (type == "segment") {
        require_dim(n, w, 2, type);
        const Vec from = n.at("from").vec(2), to = n.at("to").vec(2);
        if (from == to) n.at("to").fail("the segment has zero length: \"to\" equals \"from\"");
        add_segment(w, id, from, to);
    } else if (type == "polyline") {
        require_dim(n, w, 2, type);
        const Node pts = n.at("points");
        pts.expect_array();
        if (pts.size() < 2) pts.fail("a polyline needs at least 2 points");
        for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
            if (pts.at(i).vec(2) == pts.at(i + 1).vec(2)) pts.at(i + 1).fail("repeats the point before: a segment of zero length");
            add_segment(w, id, pts.at(i).vec(2), pts.at(i + 1).vec(2));
        }
        if (n.has("closed") && n.at("closed").boolean()) add_segment(w, id, pts.at(pts.size() - 1).vec(2), pts.at(0).vec(2));
    } else if (type == "box") {
        box(n, w, id);
    } else if (type == "plane") {
        Facet f;
        f.kind = FacetKind::plane;
        f.a = n.at("point").vec(w.dim);
        const Vec normal = n.at("normal").vec(w.dim);
        if (normal.norm() == 0) n.at("normal").fail("normal must not be zero");
        f.b = normal.normalized();
        w.walls.add_facet(id, f);
    } else if (type == "mesh") {
        mesh(n, w, id, scene_dir);
    } else if (type == "rectangle") {
        require_dim(n, w, 3, type);
        const Node c = n.at("corners");
        if (!c.value().is_array() || c.size() != 4) c.fail("expected 4 corners, in order around the rectangle");
        add_rectangle(w, id, c.at(0).vec(3), c.at(1).vec(3), c.at(2).vec(3), c.at(3).vec(3));
    } else {
        require_dim(n, w, 3, type);
        const Node v = n.at("vertices"), t = n.at("triangles");
        v.expect_array();
        t.expect_array();
        for (std::size_t i = 0; i < t.size(); ++i) {
            const Node tri = t.at(i);
            if (!tri.value().is_array() || tri.size() != 3) tri.fail("expected 3 vertex indices");
            Vec p[3];
            for (int k = 0; k < 3; ++k) p[k] = v.at(std::size_t(tri.at(k).integer(0, long(v.size()) - 1))).vec(3);
            if ((p[1] - p[0]).cross(p[2] - p[0]).norm() == 0) tri.fail("the triangle has zero area (its vertices are on a line)");
            add_triangle(w, id, p[0], p[1], p[2]);
        }
    }
    w.mark_dirty();
}

namespace {

// A facet's vertices in a canonical order, so coincident facets compare equal.
std::vector<double> facet_key(const Facet& f) {
    std::vector<std::array<double, 3>> v{{f.a.x(), f.a.y(), f.a.z()}, {f.b.x(), f.b.y(), f.b.z()}};
    if (f.kind == FacetKind::triangle) v.push_back({f.c.x(), f.c.y(), f.c.z()});
    std::sort(v.begin(), v.end());
    std::vector<double> key{double(int(f.kind))};
    for (const auto& p : v) key.insert(key.end(), p.begin(), p.end());
    return key;
}

bool same_plane(const Facet& p, const Facet& q) {
    return p.b == q.b && std::fabs((q.a - p.a).dot(p.b)) <= 1e-12 * std::max(1.0, (q.a - p.a).norm());
}

} // namespace

void check_coincident_facets(const Node& walls, const World& w) {
    const std::vector<Facet>& facets = w.walls.facets;
    std::vector<std::pair<std::vector<double>, int>> keys;
    std::vector<const Facet*> planes;
    const auto refuse = [&](int first, int second) {
        walls.at(std::size_t(second)).fail("a facet coincides with one of " + walls.at(std::size_t(first)).path() +
                                           (first == second ? " (itself)" : "") +
                                           ": a ball touching it would feel the wall twice; remove one");
    };
    for (const Facet& f : facets) {
        if (f.kind != FacetKind::plane) { keys.emplace_back(facet_key(f), f.wall); continue; }
        for (const Facet* p : planes)
            if (same_plane(*p, f)) refuse(p->wall, f.wall);
        planes.push_back(&f);
    }
    std::sort(keys.begin(), keys.end());
    for (std::size_t i = 1; i < keys.size(); ++i)
        if (keys[i].first == keys[i - 1].first) refuse(std::min(keys[i].second, keys[i - 1].second), std::max(keys[i].second, keys[i - 1].second));
}

} // namespace plab
