// Clumps in a scene (clump_generator.hpp). A clump is written in its own
// body frame: its shape centred at the origin (cylinders and rings along z)
// and its pebbles where they sit on it; "position" and "orientation" place
// that frame in the world. The kernel keeps the clump in its principal
// frame about its centre of mass, worked out here.
#include "clump_generator.hpp"

#include "body_shapes.hpp"
#include "generators.hpp"
#include "pebble_fill.hpp"

#include <plab_host/mass_properties.hpp>

#include <spdlog/spdlog.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

namespace plab {

namespace {

constexpr double kUnionTolerance = 1e-4;  // relative, of a pebble union's volume and inertia

// A clump as its template: the clump at rest with its principal frame on
// the world's axes (pebbles about the centre of mass), and where the body
// frame's origin and axes are in that frame.
struct ClumpTemplate {
    ClumpSpec clump;
    Eigen::Quaterniond principal_to_body = Eigen::Quaterniond::Identity();
    Vec centroid = Vec::Zero();  // the centre of mass in the body frame
    double reach = 0;            // the farthest pebble surface from the centre of mass
};

std::vector<Pebble> read_pebbles(const Node& list, int dim) {
    list.expect_array();
    if (list.size() == 0) list.fail("a clump needs at least one pebble, got an empty list");
    if (list.size() > 100000) list.fail("value of " + std::to_string(list.size()) + " pebbles: at most 100000 per clump");
    std::vector<Pebble> pebbles;
    for (std::size_t k = 0; k < list.size(); ++k) {
        const Node p = list.at(k);
        p.allow_keys({"position", "radius"});
        pebbles.push_back({p.at("position").vec(dim), p.at("radius").positive()});
    }
    return pebbles;
}

// "pebbles": {"fill": {"tolerance", "radius": [min, max], "count"}}: the
// shape's surface covered to the tolerance (pebble_fill.hpp). Without a
// count, needing more than 1000 pebbles is an error; with one, stopping
// there is a warning giving the deviation reached.
std::vector<Pebble> fill_pebbles(const Node& fill, const BodySurface& surface, int dim) {
    fill.allow_keys({"tolerance", "radius", "count"});
    PebbleFillOptions o;
    o.dim = dim;
    o.tolerance = fill.at("tolerance").positive();
    if (fill.has("radius")) {
        const Node r = fill.at("radius");
        if (!r.value().is_array() || r.size() != 2) r.fail("expected [min, max] pebble radii in m, got " + show(r.value()));
        o.min_radius = r.at(0).number(0.0, kInf, false, true);
        o.max_radius = r.at(1).positive();
        if (!(o.max_radius >= o.min_radius)) r.fail("the largest radius must not be below the smallest, got " + show(r.value()));
    }
    const bool capped = fill.has("count");
    o.max_count = capped ? std::size_t(fill.at("count").integer(1, 100000)) : 1000;
    PebbleFill result;
    try {
        result = fill_with_pebbles(surface_triangles(surface), o);
    } catch (const std::invalid_argument& e) {
        fill.fail(e.what());
    }
    std::ostringstream s;
    s << fill.path() << ": " << result.pebbles.size() << " pebbles, the surface within " << result.deviation
      << " m of them (tolerance " << o.tolerance << " m)";
    if (result.reached) spdlog::info("{}", s.str());
    else if (capped) spdlog::warn("{}: the count stopped the fill first", s.str());
    else fill.at("tolerance").fail("needs more than 1000 pebbles (" + s.str() + "); give a \"count\" or a larger tolerance");
    return result.pebbles;
}

ClumpTemplate read_template(const Node& n, World& w, const std::string& scene_dir) {
    const int dim = w.dim;
    const Node pebble_node = n.at("pebbles");
    const bool fill = pebble_node.value().is_object();
    if (fill) pebble_node.allow_keys({"fill"});
    if (fill && !n.has("shape")) pebble_node.fail("a pebble fill covers the clump's \"shape\": give one");
    std::vector<Pebble> pebbles = fill ? std::vector<Pebble>{} : read_pebbles(pebble_node, dim);
    MassProperties props;
    BodySurface surface;
    if (n.has("shape")) {
        BodyShape shape = read_shape(n.at("shape"), dim, scene_dir);
        props = shape.properties;
        surface = std::move(shape.surface);
        if (fill) pebbles = fill_pebbles(pebble_node.at("fill"), surface, dim);
    } else {
        const UnionProperties u = pebble_union_properties(pebbles, dim, kUnionTolerance);
        if (!u.converged)
            spdlog::warn("{}: the pebbles' union integrated to a relative change of {:.2g}, above {:.0e}; give a \"shape\"",
                         n.path(), u.change, kUnionTolerance);
        props = u.properties;
        surface = pebbles_surface(pebbles, dim);
    }
    double density;
    if (n.has("mass")) {
        if (n.has("density")) n.at("mass").fail("give either \"density\" or \"mass\", not both");
        density = n.at("mass").positive() / props.volume;
    } else {
        density = n.at("density").positive();
    }
    ClumpTemplate t;
    t.clump.mass = density * props.volume;
    if (!(t.clump.mass >= 1e-30 && t.clump.mass <= 1e30)) {
        std::ostringstream s;
        s << "gives a clump mass of " << t.clump.mass << " kg (volume " << props.volume << " m3): outside [1e-30, 1e30] kg";
        n.at(n.has("mass") ? "mass" : "density").fail(s.str());
    }
    const Eigen::Matrix3d inertia = density * props.inertia;
    t.centroid = props.centroid;
    if (dim == 2) {
        t.clump.principal_moments = Vec(0, 0, inertia(2, 2));  // the plane's own axes: only the turn about z is a DOF
    } else {
        const PrincipalAxes axes = principal_axes(inertia);
        t.clump.principal_moments = axes.moments;
        t.principal_to_body = axes.orientation;
    }
    if (dim == 2) t.centroid.z() = 0;
    for (Vec& v : surface.vertices) v = t.principal_to_body.conjugate() * (v - t.centroid);
    t.clump.surface = std::int32_t(w.clumps.surfaces.size());
    w.clumps.surfaces.push_back(std::move(surface));
    for (const Pebble& p : pebbles) {
        const Vec offset = t.principal_to_body.conjugate() * (p.centre - t.centroid);
        t.clump.pebbles.push_back({offset, p.radius});
        t.reach = std::max(t.reach, offset.norm() + p.radius);
    }
    t.clump.group = w.group_index(n.string_or("group", "clumps"));
    t.clump.local_damping = n.number_or("local_damping", 0.0, 0.0, 1.0, false, true);
    if (n.has("fix")) t.clump.fixity = read_clump_fixity(n.at("fix"), dim);
    return t;
}

// The clump of template t with its body frame at `origin`, turned by `turn`.
ClumpSpec place(const ClumpTemplate& t, const Vec& origin, const Eigen::Quaterniond& turn, const Vec& velocity,
                const Vec& spin) {
    ClumpSpec s = t.clump;
    s.position = origin + turn * t.centroid;
    s.orientation = (turn * t.principal_to_body).normalized();
    s.velocity = velocity;
    s.angular_velocity = spin;
    return s;
}

} // namespace

std::uint8_t read_clump_fixity(const Node& fix, int dim) {
    std::uint8_t f = read_fixity(fix);
    const std::uint8_t rotations = rotation_dofs(dim);
    const std::uint8_t fixed = f & rotations;
    if (fixed && fixed != rotations)
        fix.fail("a clump's rotation is fixed whole or not at all (\"rotation\"" + std::string(dim == 2 ? " or \"rz\"" : "") +
                 "), got " + show(fix.value()));
    if (dim == 2) f &= std::uint8_t(~(dof_z | dof_rx | dof_ry));
    return f;
}

void generate_clump(const Node& n, World& w, const std::string& scene_dir) {
    n.allow_keys({"type", "group", "pebbles", "shape", "density", "mass", "position", "orientation", "velocity",
                  "angular_velocity", "fix", "local_damping"});
    const ClumpTemplate t = read_template(n, w, scene_dir);
    const Vec spin = read_angular_velocity(n, w.dim);
    const Eigen::Quaterniond turn = n.has("orientation") ? read_orientation(n.at("orientation"), w.dim)
                                                         : Eigen::Quaterniond::Identity();
    add_clump(w, place(t, n.at("position").vec(w.dim), turn, n.vec_or("velocity", w.dim, Vec::Zero()), spin));
}

namespace {

// The placed pebbles of a fill on a grid of cells one largest pebble
// diameter wide, for the overlap test of a new clump.
class PebbleGrid {
public:
    PebbleGrid(double cell, int dim) : cell_(cell), dim_(dim) {}
    bool free(const Vec& c, double r) const {
        const auto k = key_of(c);
        for (long dz = dim_ == 3 ? -1 : 0; dz <= (dim_ == 3 ? 1 : 0); ++dz)
            for (long dy = -1; dy <= 1; ++dy)
                for (long dx = -1; dx <= 1; ++dx) {
                    const auto it = cells_.find(hash(k[0] + dx, k[1] + dy, k[2] + dz));
                    if (it == cells_.end()) continue;
                    for (std::size_t i : it->second)
                        if ((centres_[i] - c).norm() < radii_[i] + r) return false;
                }
        return true;
    }
    void add(const Vec& c, double r) {
        const auto k = key_of(c);
        cells_[hash(k[0], k[1], k[2])].push_back(centres_.size());
        centres_.push_back(c);
        radii_.push_back(r);
    }

private:
    double cell_;
    int dim_;
    std::vector<Vec> centres_;
    std::vector<double> radii_;
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells_;
    std::array<long, 3> key_of(const Vec& c) const {
        return {long(std::floor(c.x() / cell_)), long(std::floor(c.y() / cell_)), dim_ == 3 ? long(std::floor(c.z() / cell_)) : 0};
    }
    static std::uint64_t hash(long x, long y, long z) {
        return (std::uint64_t(x) * 73856093ull) ^ (std::uint64_t(y) * 19349663ull) ^ (std::uint64_t(z) * 83492791ull);
    }
};

// A rotation drawn uniformly (Shoemake 1992: a uniform unit quaternion from
// three uniform numbers); 2D: a uniform angle about z.
Eigen::Quaterniond random_turn(Rng& rng, int dim) {
    if (dim == 2) return Eigen::Quaterniond(Eigen::AngleAxisd(rng.uniform(0, 2 * kPi), Vec::UnitZ()));
    const double u1 = rng.uniform(0, 1), u2 = rng.uniform(0, 2 * kPi), u3 = rng.uniform(0, 2 * kPi);
    const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
    return Eigen::Quaterniond(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3));
}

} // namespace

void generate_clump_fill(const Node& n, World& w, const std::string& scene_dir) {
    n.allow_keys({"type", "clump", "box", "count", "seed", "max_attempts"});
    const Node tn = n.at("clump");
    tn.allow_keys({"group", "pebbles", "shape", "density", "mass", "fix", "local_damping"});
    const ClumpTemplate t = read_template(tn, w, scene_dir);
    const Node bn = n.at("box");
    bn.allow_keys({"min", "max"});
    const Vec lo = bn.at("min").vec(w.dim), hi = bn.at("max").vec(w.dim);
    // the body frame's origin stays far enough inside that no pebble leaves the box
    const double margin = t.reach + t.centroid.norm();
    for (int c = 0; c < w.dim; ++c)
        if (!(hi[c] - lo[c] > 2 * margin))
            bn.at("max").fail("the box must be wider than a clump (" + std::to_string(2 * margin) + " m) in every direction");
    const long count = n.at("count").integer(1, 10000000);
    Rng rng(std::uint64_t(n.has("seed") ? n.at("seed").integer(0, 1L << 40) : 1));
    const long max_attempts = n.has("max_attempts") ? n.at("max_attempts").integer(1, 1L << 40) : 1000 * count;
    double largest = 0;
    for (const PebbleSpec& p : t.clump.pebbles) largest = std::max(largest, p.radius);
    PebbleGrid grid(2 * largest, w.dim);
    long placed = 0, attempts = 0;
    std::vector<Vec> centres(t.clump.pebbles.size());
    while (placed < count && attempts < max_attempts) {
        ++attempts;
        Vec origin = Vec::Zero();
        for (int c = 0; c < w.dim; ++c) origin[c] = rng.uniform(lo[c] + margin, hi[c] - margin);
        const ClumpSpec s = place(t, origin, random_turn(rng, w.dim), Vec::Zero(), Vec::Zero());
        bool fits = true;
        for (std::size_t p = 0; p < s.pebbles.size() && fits; ++p) {
            centres[p] = s.position + s.orientation * s.pebbles[p].offset;
            fits = grid.free(centres[p], s.pebbles[p].radius);
        }
        if (!fits) continue;
        for (std::size_t p = 0; p < s.pebbles.size(); ++p) grid.add(centres[p], s.pebbles[p].radius);
        add_clump(w, s);
        ++placed;
    }
    if (placed < count) {
        std::ostringstream s;
        s << "could place only " << placed << " of " << count << " non-overlapping clumps in " << attempts
          << " attempts; enlarge the box or lower the count";
        n.at("count").fail(s.str());
    }
}

} // namespace plab
