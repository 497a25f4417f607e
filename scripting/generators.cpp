#include "generators.hpp"

#include <plab_core/plugin_host.hpp>

#include <cmath>
#include <sstream>

namespace plab {

namespace {

struct Material {
    double radius_lo = 0, radius_hi = 0, density = 0, damping = 0, viscous = 0;
    int group = 0;
    std::uint8_t fixity = 0;
};

// `mass` (ball, lattice) gives each ball's mass directly, e.g. an SPH
// particle's rho0 dp^2 (2D, per unit thickness) or rho0 dp^3 (3D); it is
// stored as the equivalent material density of the disc / sphere, so the
// kernel's mass and inertia (from that mass) follow.
double density_from_mass(const Node& n, int dim, double radius) {
    if (n.has("density")) n.at("mass").fail("give either \"density\" or \"mass\", not both");
    const double mass = n.at("mass").positive();
    return mass / Bodies::mass_of(dim, radius, 1.0);
}

// A mass no body in a simulation has (below an atom's, above a mountain's)
// is a unit slip; caught here rather than as NaN forces in the first step.
void check_mass(const Node& n, int dim, double radius, double density) {
    const double mass = Bodies::mass_of(dim, radius, density);
    if (mass >= 1e-30 && mass <= 1e30) return;
    std::ostringstream s;
    s << "radius " << radius << " m and density " << density << " kg/m" << (dim == 2 ? "2 (a disc 1 m thick)" : "3")
      << " give a ball mass of " << mass << " kg: outside [1e-30, 1e30] kg";
    // blame the radius when no material would make a sensible ball of it
    const double water_ball = Bodies::mass_of(dim, radius, 1000.0);
    const bool radius_at_fault = !(water_ball >= 1e-30 && water_ball <= 1e30);
    n.at(n.has("mass") ? "mass" : radius_at_fault ? "radius" : "density").fail(s.str());
}

Material read_material(const Node& n, World& w, bool radius_range, bool allow_mass = false) {
    Material m;
    const Node r = n.at("radius");
    if (radius_range && r.value().is_array()) {
        if (r.size() != 2) r.fail("expected a radius or a range [min, max], got " + show(r.value()));
        m.radius_lo = r.at(0).positive();
        m.radius_hi = r.at(1).positive();
        if (m.radius_hi < m.radius_lo) r.fail("radius range [min, max] has max < min, got " + show(r.value()));
    } else {
        m.radius_lo = m.radius_hi = r.positive();
    }
    m.density = allow_mass && n.has("mass") ? density_from_mass(n, w.dim, m.radius_lo) : n.at("density").positive();
    check_mass(n, w.dim, m.radius_lo, m.density);
    check_mass(n, w.dim, m.radius_hi, m.density);
    m.damping = n.number_or("local_damping", 0.0, 0.0, 1.0, false, true);
    m.viscous = n.number_or("viscous_damping", 0.0, 0.0, kInf, false, true);
    m.group = w.group_index(n.string_or("group", "balls"));
    m.fixity = n.has("fix") ? read_fixity(n.at("fix")) : 0;
    return m;
}

Box read_box(const Node& n, int dim) {
    n.allow_keys({"min", "max"});
    Box b{n.at("min").vec(dim), n.at("max").vec(dim)};
    for (int c = 0; c < dim; ++c)
        if (!(b.lo[c] < b.hi[c])) n.at("max").fail("box max must exceed min in every direction");
    return b;
}

void add(World& w, const Material& m, const Vec& p, double radius, const Vec& v = Vec::Zero(),
         const Vec& spin = Vec::Zero()) {
    BallSpec s;
    s.position = p;
    s.velocity = v;
    s.angular_velocity = spin;
    s.radius = radius;
    s.density = m.density;
    s.group = m.group;
    s.fixity = m.fixity;
    s.local_damping = m.damping;
    s.viscous_damping = m.viscous;
    w.bodies.add(s);
}

void single_ball(const Node& n, World& w) {
    n.allow_keys({"type", "group", "position", "radius", "density", "mass", "velocity", "angular_velocity", "fix",
                  "local_damping", "viscous_damping"});
    const Material m = read_material(n, w, false, true);
    Vec spin = Vec::Zero();
    if (n.has("angular_velocity")) {
        if (w.dim == 2) spin.z() = n.at("angular_velocity").number();
        else spin = n.at("angular_velocity").vec(3);
    }
    add(w, m, n.at("position").vec(w.dim), m.radius_lo, n.vec_or("velocity", w.dim, Vec::Zero()), spin);
}

// About what a ball costs in a run (its columns, contacts, neighbour
// lists: bench/peers/memory.py measured 1004 B at 1e5 balls).
constexpr double kBytesPerBall = 1000;

// Refused before anything is allocated: a generator asking for more balls
// than the scene's limit, with the count and the memory it would take.
void check_body_budget(const Node& n, double count, const World& w, const GeneratorLimits& limits) {
    const double total = double(w.bodies.size()) + count;
    if (total <= double(limits.max_bodies)) return;
    std::ostringstream s;
    s << "would make " << count << " balls (" << total << " in the scene so far), about " << total * kBytesPerBall
      << " bytes of memory; above limits.max_bodies = " << limits.max_bodies
      << ": raise it in the scene's \"limits\" if the machine has the memory";
    n.fail(s.str());
}

// Regular packings filling a box with ball centres at least r from its faces:
// 2D square / hexagonal (rows r√3 apart, odd rows shifted by r); 3D cubic /
// hcp (layers 2r√(2/3) apart, ABAB stacking). Optional jitter for benchmarks.
Box lattice(const Node& n, World& w, const GeneratorLimits& limits) {
    n.allow_keys({"type", "group", "box", "radius", "density", "mass", "packing", "spacing", "fix", "local_damping",
                  "viscous_damping", "jitter", "velocity"});
    const Material m = read_material(n, w, false, true);
    const Box box = read_box(n.at("box"), w.dim);
    const double r = m.radius_lo;
    const double a = n.number_or("spacing", 2 * r, 2 * r, kInf, false, true);  // centre spacing
    const std::string packing = n.has("packing") ? (w.dim == 2 ? n.at("packing").choice({"square", "hexagonal"})
                                                                : n.at("packing").choice({"cubic", "hcp"}))
                                                 : (w.dim == 2 ? "hexagonal" : "cubic");
    double jit_x = 0, jit_v = 0;
    std::uint64_t seed = 1;
    if (n.has("jitter")) {
        const Node j = n.at("jitter");
        j.allow_keys({"position", "velocity", "seed"});
        jit_x = j.number_or("position", 0.0, 0.0, r, false, false);
        jit_v = j.number_or("velocity", 0.0, 0.0, kInf, false, true);
        seed = std::uint64_t(j.has("seed") ? j.at("seed").integer(0, 1L << 40) : 1);
    }
    Rng rng(seed);
    const Vec v0 = n.vec_or("velocity", w.dim, Vec::Zero());
    const bool hex = packing == "hexagonal" || packing == "hcp";
    const double dy = hex ? a * std::sqrt(3.0) / 2.0 : a;   // row pitch (2D) / in-layer row pitch (3D)
    const double dz = packing == "hcp" ? a * std::sqrt(2.0 / 3.0) : a;
    const Vec lo = box.lo + Vec::Constant(r), hi = box.hi - Vec::Constant(r);
    // counts tolerate round-off: a box sized for exactly n rows holds n rows
    const double rows = std::floor((hi.y() - lo.y()) / dy + 1e-6) + 1, columns = std::floor((hi.x() - lo.x()) / a + 1e-6) + 1;
    const double layers = w.dim == 3 ? std::floor((hi.z() - lo.z()) / dz + 1e-6) + 1 : 1;
    check_body_budget(n, std::max(0.0, rows) * std::max(0.0, columns) * std::max(0.0, layers), w, limits);
    const long nz = long(layers);
    std::size_t count = 0;
    for (long k = 0; k < nz; ++k) {
        const double layer_x = packing == "hcp" && (k % 2) ? a / 2 : 0.0;
        const double layer_y = packing == "hcp" && (k % 2) ? a * std::sqrt(3.0) / 6.0 : 0.0;
        const long ny = long(std::floor((hi.y() - lo.y() - layer_y) / dy + 1e-6)) + 1;
        for (long j = 0; j < ny; ++j) {
            const double shift = hex && (j % 2) ? a / 2 : 0.0;
            for (long i = 0;; ++i) {
                Vec p(lo.x() + layer_x + shift + i * a, lo.y() + layer_y + j * dy, w.dim == 3 ? lo.z() + k * dz : 0.0);
                if (p.x() > hi.x() + 1e-6 * a) break;
                Vec v = v0;
                for (int c = 0; c < w.dim; ++c) {
                    if (jit_x > 0) p[c] += rng.uniform(-jit_x, jit_x);
                    if (jit_v > 0) v[c] += rng.uniform(-jit_v, jit_v);
                }
                add(w, m, p, r, v);
                ++count;
            }
        }
    }
    if (count == 0) {
        std::ostringstream s;
        s << "box [" << box.lo.head(w.dim).transpose() << "] .. [" << box.hi.head(w.dim).transpose()
          << "] is too small for one ball of radius " << r << " (needs at least " << 2 * r << " in every direction)";
        n.at("box").fail(s.str());
    }
    return box;
}

// Balls cannot fill more than the box: refuse at once instead of spending
// 1000 x count rejected attempts on an impossible fill.
void check_fill_possible(const Node& count_node, long count, double radius, const Box& box, int dim) {
    const double ball_volume = dim == 2 ? M_PI * radius * radius : 4.0 / 3.0 * M_PI * std::pow(radius, 3);
    double box_volume = 1;
    for (int c = 0; c < dim; ++c) box_volume *= box.hi[c] - box.lo[c];
    if (double(count) * ball_volume <= box_volume) return;
    std::ostringstream s;
    s << "value " << count << " cannot fit: " << count << " balls of radius at least " << radius << " occupy "
      << double(count) * ball_volume << ", more than the box's " << box_volume << "; the valid range is at most [1, "
      << long(box_volume / ball_volume) << "]";
    count_node.fail(s.str());
}

// Random non-overlapping fill by rejection on a background grid.
Box random_fill(const Node& n, World& w, const GeneratorLimits& limits) {
    n.allow_keys({"type", "group", "box", "radius", "density", "count", "seed", "fix", "local_damping", "viscous_damping", "max_attempts"});
    const Material m = read_material(n, w, true);
    const Box box = read_box(n.at("box"), w.dim);
    const long count = n.at("count").integer(1, 100000000);
    check_body_budget(n.at("count"), double(count), w, limits);
    check_fill_possible(n.at("count"), count, m.radius_lo, box, w.dim);
    Rng rng(std::uint64_t(n.has("seed") ? n.at("seed").integer(0, 1L << 40) : 1));
    const long max_attempts = n.has("max_attempts") ? n.at("max_attempts").integer(1, 1L << 40) : 1000 * count;
    std::vector<Vec> placed;
    std::vector<double> radii;
    // cells at least a diameter (neighbours are then within one cell) and
    // not more cells than balls: tiny balls in a big box need no fine grid
    double box_volume = 1;
    for (int c = 0; c < w.dim; ++c) box_volume *= box.hi[c] - box.lo[c];
    const double cell = std::max(2 * m.radius_hi, std::pow(box_volume / double(count), 1.0 / w.dim));
    std::array<long, 3> dims{1, 1, 1};
    for (int c = 0; c < w.dim; ++c) dims[c] = std::max(1L, long((box.hi[c] - box.lo[c]) / cell) + 1);
    std::vector<std::vector<int>> grid(std::size_t(dims[0] * dims[1] * dims[2]));
    auto cell_of = [&](const Vec& p, int c) { return std::clamp(long((p[c] - box.lo[c]) / cell), 0L, dims[c] - 1); };
    long attempts = 0;
    while (long(placed.size()) < count && attempts < max_attempts) {
        ++attempts;
        const double r = rng.uniform(m.radius_lo, m.radius_hi);
        Vec p = Vec::Zero();
        bool fits = true;
        for (int c = 0; c < w.dim; ++c) {
            if (box.hi[c] - box.lo[c] < 2 * r) fits = false;
            p[c] = rng.uniform(box.lo[c] + r, box.hi[c] - r);
        }
        if (!fits) continue;
        const long cx = cell_of(p, 0), cy = cell_of(p, 1), cz = w.dim == 3 ? cell_of(p, 2) : 0;
        for (long z = std::max(0L, cz - 1); fits && z <= std::min(dims[2] - 1, cz + 1); ++z)
            for (long y = std::max(0L, cy - 1); fits && y <= std::min(dims[1] - 1, cy + 1); ++y)
                for (long x = std::max(0L, cx - 1); fits && x <= std::min(dims[0] - 1, cx + 1); ++x)
                    for (int q : grid[(z * dims[1] + y) * dims[0] + x])
                        if ((placed[q] - p).norm() < radii[q] + r) { fits = false; break; }
        if (!fits) continue;
        grid[(cz * dims[1] + cy) * dims[0] + cx].push_back(int(placed.size()));
        placed.push_back(p);
        radii.push_back(r);
    }
    if (long(placed.size()) < count) {
        std::ostringstream s;
        s << "could place only " << placed.size() << " of " << count << " non-overlapping balls in " << attempts
          << " attempts; enlarge the box, lower the count or the radius";
        n.at("count").fail(s.str());
    }
    for (std::size_t i = 0; i < placed.size(); ++i) add(w, m, placed[i], radii[i]);
    return box;
}

} // namespace

std::uint8_t read_fixity(const Node& n) {
    n.expect_array();
    std::uint8_t f = 0;
    for (std::size_t i = 0; i < n.size(); ++i) {
        const std::string d = n.at(i).choice({"x", "y", "z", "rx", "ry", "rz", "translation", "rotation", "all"});
        if (d == "x") f |= dof_x;
        else if (d == "y") f |= dof_y;
        else if (d == "z") f |= dof_z;
        else if (d == "rx") f |= dof_rx;
        else if (d == "ry") f |= dof_ry;
        else if (d == "rz") f |= dof_rz;
        else if (d == "translation") f |= dof_x | dof_y | dof_z;
        else if (d == "rotation") f |= dof_rx | dof_ry | dof_rz;
        else f = 63;
    }
    return f;
}

std::optional<Box> generate_bodies(const Node& n, World& w, const GeneratorLimits& limits) {
    const std::string type = n.at("type").choice({"ball", "lattice", "random_fill"});
    if (type == "ball") {
        single_ball(n, w);
        return std::nullopt;
    }
    w.mark_dirty();
    return type == "lattice" ? lattice(n, w, limits) : random_fill(n, w, limits);
}

double read_property(const Node& v, const plab_property_desc& d) {
    // dimensionless properties have the unit "1": leave it out of messages
    const std::string unit = std::string(d.unit) == "1" ? "" : " " + std::string(d.unit);
    if (!v.value().is_number()) v.fail("expected a number in " + range_text(d) + unit + ", got " + show(v.value()));
    const double x = v.value().get<double>();
    if (!in_range(d, x)) {
        std::ostringstream s;
        s << "value " << x << " of " << d.name << " is outside the valid range " << range_text(d) << unit;
        v.fail(s.str());
    }
    return x;
}

std::vector<double> read_properties(const Node& owner, const plab_property_desc* props, uint32_t count,
                                    const std::string& what) {
    std::vector<double> values(count);
    for (uint32_t p = 0; p < count; ++p) values[p] = props[p].default_value;
    if (!owner.has("properties")) return values;
    const Node given = owner.at("properties");
    given.expect_object();
    for (auto it = given.value().begin(); it != given.value().end(); ++it) {
        const Node v(*it, given.path() + "." + it.key());
        uint32_t p = 0;
        while (p < count && it.key() != props[p].key) ++p;
        if (p == count) {
            std::string known;
            for (uint32_t q = 0; q < count; ++q) known += (known.empty() ? "" : ", ") + std::string(props[q].key);
            v.fail("unknown property '" + it.key() + "' of " + what + "; its properties: " + (known.empty() ? "none" : known));
        }
        values[p] = read_property(v, props[p]);
    }
    return values;
}

} // namespace plab
