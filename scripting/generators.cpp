#include "generators.hpp"

#include "clump_generator.hpp"

#include "ball_fill.hpp"
#include "size_distribution.hpp"

#include <plab_host/plugins.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>

namespace plab {

namespace {

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

} // namespace

Material read_material(const Node& n, World& w, bool radius_range, bool allow_mass, const SizeDistribution* sizes) {
    Material m;
    const Node r = n.at("radius");
    if (sizes) {
        m.radius_lo = sizes->min();
        m.radius_hi = sizes->max();
    } else if (radius_range && r.value().is_array()) {
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

void add(World& w, const Material& m, const Vec& p, double radius, const Vec& v, const Vec& spin) {
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

namespace {

void single_ball(const Node& n, World& w) {
    n.allow_keys({"type", "group", "position", "radius", "density", "mass", "velocity", "angular_velocity", "fix",
                  "local_damping", "viscous_damping"});
    const Material m = read_material(n, w, false, true);
    add(w, m, n.at("position").vec(w.dim), m.radius_lo, n.vec_or("velocity", w.dim, Vec::Zero()),
        read_angular_velocity(n, w.dim));
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

// The pitches of a regular packing of spacing a: along x, between rows (2D)
// or in-layer rows (3D), between layers. 2D square / hexagonal (rows a√3/2
// apart, odd rows shifted by a/2); 3D cubic / hcp (layers a√(2/3) apart,
// ABAB stacking, B shifted by (a/2, a√3/6)). Each ball owns one Voronoi cell
// of a·dy (2D) or a·dy·dz (3D): hexagonal 2√3 R², hcp 4√2 R³ at a = 2R.
struct Packing {
    std::string name;
    double a = 0, dy = 0, dz = 0;
    bool hex = false, hcp = false;
    double shift_x(long j, long k) const { return (hex && (j % 2) ? a / 2 : 0.0) + (hcp && (k % 2) ? a / 2 : 0.0); }
    double shift_y(long k) const { return hcp && (k % 2) ? a * std::sqrt(3.0) / 6.0 : 0.0; }
};

Packing read_packing(const Node& n, int dim, double r) {
    Packing p;
    p.a = n.number_or("spacing", 2 * r, 2 * r, kInf, false, true);  // centre spacing
    p.name = n.has("packing") ? (dim == 2 ? n.at("packing").choice({"square", "hexagonal"}) : n.at("packing").choice({"cubic", "hcp"}))
                              : (dim == 2 ? "hexagonal" : "cubic");
    p.hex = p.name == "hexagonal" || p.name == "hcp";
    p.hcp = p.name == "hcp";
    p.dy = p.hex ? p.a * std::sqrt(3.0) / 2.0 : p.a;
    p.dz = p.hcp ? p.a * std::sqrt(2.0 / 3.0) : p.a;
    return p;
}

// Centres filling a box with every ball inside it (centres at least r from
// its faces).
std::vector<Vec> points_in_box(const Node& n, const Box& box, const Packing& pk, double r, int dim, const World& w,
                               const GeneratorLimits& limits) {
    const Vec lo = box.lo + Vec::Constant(r), hi = box.hi - Vec::Constant(r);
    // counts tolerate round-off: a box sized for exactly n rows holds n rows
    const double rows = std::floor((hi.y() - lo.y()) / pk.dy + 1e-6) + 1, columns = std::floor((hi.x() - lo.x()) / pk.a + 1e-6) + 1;
    const double layers = dim == 3 ? std::floor((hi.z() - lo.z()) / pk.dz + 1e-6) + 1 : 1;
    check_body_budget(n, std::max(0.0, rows) * std::max(0.0, columns) * std::max(0.0, layers), w, limits);
    std::vector<Vec> points;
    for (long k = 0; k < long(layers); ++k) {
        const long ny = long(std::floor((hi.y() - lo.y() - pk.shift_y(k)) / pk.dy + 1e-6)) + 1;
        for (long j = 0; j < ny; ++j)
            for (long i = 0;; ++i) {
                const Vec p(lo.x() + pk.shift_x(j, k) + i * pk.a, lo.y() + pk.shift_y(k) + j * pk.dy, dim == 3 ? lo.z() + k * pk.dz : 0.0);
                if (p.x() > hi.x() + 1e-6 * pk.a) break;
                points.push_back(p);
            }
    }
    return points;
}

// How many cells of `pitch` make `size` (solid.size[c]): the nearest whole
// number, refused when its cells miss the size by more than `tol` of it.
long cell_count(const Node& size_node, double size, double pitch, double tol, const char* cells) {
    const long count = std::max(1L, long(std::lround(size / pitch)));
    if (std::fabs(count * pitch - size) <= tol * size) return count;
    std::ostringstream s;
    s << "value " << size << " m is " << size / pitch << " " << cells << " of " << pitch
      << " m (the packing's pitch at this radius and spacing), not a whole number within solid.size_tolerance = " << tol
      << " of it; the valid range is [" << count * pitch / (1 + tol) << ", " << count * pitch / (1 - tol) << "] m for " << count
      << " " << cells;
    const long other = size / pitch > double(count) ? count + 1 : count - 1;
    if (other >= 1)
        s << " or [" << other * pitch / (1 + tol) << ", " << other * pitch / (1 - tol) << "] m for " << other << " " << cells;
    s << "; change the size, the radius, or solid.size_tolerance";
    size_node.fail(s.str());
}

// Centres whose cells make up the solid [min, min + size]: whole numbers of
// columns (pitch a), rows (dy) and layers (dz), every row with the same
// count, so that the cells' union (the equivalent continuum) has the size
// named (its cells from min to min + count pitch in each direction).
std::vector<Vec> points_for_solid(const Node& s, const Packing& pk, int dim, const World& w, const GeneratorLimits& limits,
                                  std::string& note) {
    s.allow_keys({"min", "size", "size_tolerance"});
    const Vec lo = s.at("min").vec(dim), size = s.at("size").vec(dim);
    for (int c = 0; c < dim; ++c)
        if (!(size[c] > 0)) s.at("size").at(c).fail("value " + show(s.at("size").at(c).value()) + " is not a size: the valid range is (0, inf) m");
    const double tol = s.number_or("size_tolerance", 0.01, 0.0, 0.5, false, true);
    const double pitch[3] = {pk.a, pk.dy, pk.dz};
    const char* names[3] = {"columns", "rows", "layers"};
    double estimate = 1;  // refused before a count can overflow
    for (int c = 0; c < dim; ++c) estimate *= std::max(1.0, std::round(size[c] / pitch[c]));
    check_body_budget(s.at("size"), estimate, w, limits);
    long count[3] = {1, 1, 1};
    for (int c = 0; c < dim; ++c) count[c] = cell_count(s.at("size").at(c), size[c], pitch[c], tol, names[c]);
    // each cell centred half a pitch in, less the rows' and layers' mean
    // shift (over their ABAB period), so that the cells fill [min, min + count pitch]
    const Vec start(lo.x() + pk.a / 2 - (pk.hex ? pk.a / 4 : 0.0) - (pk.hcp ? pk.a / 4 : 0.0),
                    lo.y() + pk.dy / 2 - (pk.hcp ? pk.a * std::sqrt(3.0) / 12 : 0.0), dim == 3 ? lo.z() + pk.dz / 2 : 0.0);
    std::vector<Vec> points;
    for (long k = 0; k < count[2]; ++k)
        for (long j = 0; j < count[1]; ++j)
            for (long i = 0; i < count[0]; ++i)
                points.push_back(start + Vec(pk.shift_x(j, k) + i * pk.a, pk.shift_y(k) + j * pk.dy, dim == 3 ? k * pk.dz : 0.0));
    std::ostringstream o;
    o << count[0] << " x " << count[1] << (dim == 3 ? " x " + std::to_string(count[2]) : "") << " " << pk.name
      << " cells, equivalent solid";
    for (int c = 0; c < dim; ++c) o << (c ? " x " : " ") << count[c] * pitch[c];
    o << " m (named";
    for (int c = 0; c < dim; ++c) o << (c ? " x " : " ") << size[c];
    o << " m)";
    note = o.str();
    return points;
}

// The balls' envelope: the region two generators must not share.
Box envelope(const std::vector<Vec>& points, double r) {
    Box b{Vec::Constant(kInf), Vec::Constant(-kInf)};
    for (const Vec& p : points) {
        b.lo = b.lo.cwiseMin(p - Vec::Constant(r));
        b.hi = b.hi.cwiseMax(p + Vec::Constant(r));
    }
    return b;
}

// A regular packing filling a box (every ball inside it) or making up a
// solid (its cells: `solid`, the size a calibrated structure stands for).
// Optional jitter for benchmarks.
Box lattice(const Node& n, World& w, const GeneratorLimits& limits, LatticeCells* cells) {
    n.allow_keys({"type", "group", "box", "solid", "radius", "density", "mass", "packing", "spacing", "fix", "local_damping",
                  "viscous_damping", "jitter", "velocity"});
    if (n.has("box") == n.has("solid"))
        n.fail("a lattice needs exactly one of \"box\" (the region its balls fill) or \"solid\" ({\"min\", \"size\"}: the "
               "solid its cells make up, as a calibrated structure is sized)");
    const Material m = read_material(n, w, false, true);
    const double r = m.radius_lo;
    const Packing pk = read_packing(n, w.dim, r);
    double jit_x = 0, jit_v = 0;
    std::uint64_t seed = 1;
    if (n.has("jitter")) {
        const Node j = n.at("jitter");
        j.allow_keys({"position", "velocity", "seed"});
        jit_x = j.number_or("position", 0.0, 0.0, r, false, false);
        jit_v = j.number_or("velocity", 0.0, 0.0, kInf, false, true);
        seed = std::uint64_t(j.has("seed") ? j.at("seed").integer(0, 1L << 40) : 1);
    }
    std::string note;
    const std::vector<Vec> points = n.has("box") ? points_in_box(n, read_box(n.at("box"), w.dim), pk, r, w.dim, w, limits)
                                                 : points_for_solid(n.at("solid"), pk, w.dim, w, limits, note);
    if (points.empty()) {
        const Box box = read_box(n.at("box"), w.dim);
        std::ostringstream s;
        s << "box [" << box.lo.head(w.dim).transpose() << "] .. [" << box.hi.head(w.dim).transpose()
          << "] is too small for one ball of radius " << r << " (needs at least " << 2 * r << " in every direction)";
        n.at("box").fail(s.str());
    }
    Rng rng(seed);
    const Vec v0 = n.vec_or("velocity", w.dim, Vec::Zero());
    for (Vec p : points) {
        Vec v = v0;
        for (int c = 0; c < w.dim; ++c) {
            if (jit_x > 0) p[c] += rng.uniform(-jit_x, jit_x);
            if (jit_v > 0) v[c] += rng.uniform(-jit_v, jit_v);
        }
        add(w, m, p, r, v);
    }
    if (cells) {
        cells->group = m.group;
        cells->packing = pk.name;
        cells->radius = r;
        cells->cell_volume = pk.a * pk.dy * (w.dim == 3 ? pk.dz : 1.0);
        cells->note = note;
    }
    return n.has("box") ? read_box(n.at("box"), w.dim) : envelope(points, r);
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

// A radius range [min, max]: each attempt draws its own radius, uniform in
// the range (so a dense fill keeps more small balls than the range holds).
long fill_drawing_per_attempt(FillGrid& grid, Rng& rng, const Material& m, long count, long max_attempts) {
    long attempts = 0;
    while (long(grid.placed.size()) < count && attempts < max_attempts) {
        ++attempts;
        const double r = rng.uniform(m.radius_lo, m.radius_hi);
        Vec p;
        if (grid.draw_position(rng, r, p)) grid.place(p, r);
    }
    return attempts;
}

// A size distribution: the count radii drawn first and placed largest
// first, so the fill holds exactly the radii drawn.
long fill_drawn_radii(FillGrid& grid, Rng& rng, const std::vector<double>& radii, long max_attempts) {
    long attempts = 0;
    for (double r : radii) {
        Vec p;
        bool placed = false;
        while (!placed && attempts < max_attempts) {
            ++attempts;
            placed = grid.draw_position(rng, r, p) && grid.place(p, r);
        }
        if (!placed) break;
    }
    return attempts;
}

// The drawn balls' total volume must fit the box (a necessary condition).
void check_drawn_fit(const Node& n, const std::vector<double>& radii, const Box& box, int dim) {
    double balls = 0, volume = 1;
    for (double r : radii) balls += dim == 2 ? M_PI * r * r : 4.0 / 3.0 * M_PI * r * r * r;
    for (int c = 0; c < dim; ++c) volume *= box.hi[c] - box.lo[c];
    if (balls > volume) {
        std::ostringstream s;
        s << "value " << radii.size() << " cannot fit: the radii drawn occupy " << balls << ", more than the box's "
          << volume;
        n.fail(s.str());
    }
}

double ball_volume(double r, int dim) { return dim == 2 ? M_PI * r * r : 4.0 / 3.0 * M_PI * r * r * r; }

double box_volume(const Box& box, int dim) {
    double v = 1;
    for (int c = 0; c < dim; ++c) v *= box.hi[c] - box.lo[c];
    return v;
}

// "solid_fraction": random placement without overlap jams near 0.55 of
// the area (2D) and 0.38 of the volume (3D); above 0.5 / 0.35 a fill would
// spend its attempts in vain.
double read_solid_fraction(const Node& n, int dim) {
    const double most = dim == 2 ? 0.5 : 0.35;
    const double phi = n.number(0.0, kInf, true, false);
    if (phi > most)
        n.fail("value " + std::to_string(phi) + " is outside the valid range (0, " + std::to_string(most).substr(0, 4) + "] in " +
               std::to_string(dim) + "D: random placement without overlap jams near " + (dim == 2 ? "0.55" : "0.38") +
               "; fill looser and compress (servo walls), or use a lattice");
    return phi;
}

// The number of balls of a radius range [lo, hi] (each drawn uniform) whose
// expected volume makes up `volume`: E[r^d] = (hi^(d+1) - lo^(d+1)) / ((d+1)(hi - lo)).
long count_for_volume(double volume, double lo, double hi, int dim) {
    const double mean_power = hi > lo ? (std::pow(hi, dim + 1) - std::pow(lo, dim + 1)) / ((dim + 1) * (hi - lo)) : std::pow(lo, dim);
    const double mean_ball = (dim == 2 ? M_PI : 4.0 / 3.0 * M_PI) * mean_power;
    return std::max(1L, std::lround(volume / mean_ball));
}

// Radii drawn one by one until their volume reaches `volume`, largest first
// (the order the fill places them in).
std::vector<double> draw_to_volume(const SizeDistribution& sizes, double volume, int dim, Rng& rng) {
    std::vector<double> radii;
    for (double sum = 0; sum < volume;) {
        radii.push_back(sizes.draw(rng));
        sum += ball_volume(radii.back(), dim);
    }
    std::sort(radii.begin(), radii.end(), std::greater<double>());
    return radii;
}

// Random non-overlapping fill by rejection on a background grid, to a count
// of balls or to a solid fraction of the box.
Box random_fill(const Node& n, World& w, const GeneratorLimits& limits, const std::string& scene_dir) {
    n.allow_keys({"type", "group", "box", "radius", "density", "count", "solid_fraction", "seed", "fix", "local_damping",
                  "viscous_damping", "max_attempts"});
    std::optional<SizeDistribution> sizes;
    if (n.at("radius").value().is_object()) sizes.emplace(n.at("radius"), w.dim, scene_dir);
    const Material m = read_material(n, w, true, false, sizes ? &*sizes : nullptr);
    const Box box = read_box(n.at("box"), w.dim);
    if (n.has("count") == n.has("solid_fraction")) n.fail("a random fill takes one of: count, solid_fraction");
    Rng rng(std::uint64_t(n.has("seed") ? n.at("seed").integer(0, 1L << 40) : 1));
    const Node amount = n.has("count") ? n.at("count") : n.at("solid_fraction");
    std::vector<double> radii;  // with a distribution: drawn before the fill
    long count = 0;
    if (n.has("count")) {
        count = n.at("count").integer(1, 100000000);
    } else {
        const double target = read_solid_fraction(amount, w.dim) * box_volume(box, w.dim);
        check_body_budget(amount, target / ball_volume(m.radius_lo, w.dim), w, limits);  // (the most it can draw)
        if (sizes) radii = draw_to_volume(*sizes, target, w.dim, rng);
        count = sizes ? long(radii.size()) : count_for_volume(target, m.radius_lo, m.radius_hi, w.dim);
    }
    check_body_budget(amount, double(count), w, limits);
    check_fill_possible(amount, count, m.radius_lo, box, w.dim);
    const long max_attempts = n.has("max_attempts") ? n.at("max_attempts").integer(1, 1L << 40) : 1000 * count;
    FillGrid grid(box, w.dim, m.radius_hi, count);
    long attempts = 0;
    if (sizes) {
        if (radii.empty()) radii = sizes->draw(count, rng);
        check_drawn_fit(amount, radii, box, w.dim);
        attempts = fill_drawn_radii(grid, rng, radii, max_attempts);
    } else {
        attempts = fill_drawing_per_attempt(grid, rng, m, count, max_attempts);
    }
    if (long(grid.placed.size()) < count) {
        std::ostringstream s;
        s << "could place only " << grid.placed.size() << " of " << count << " non-overlapping balls in " << attempts
          << " attempts; enlarge the box, lower the " << (n.has("count") ? "count" : "solid fraction") << " or the radius";
        amount.fail(s.str());
    }
    for (std::size_t i = 0; i < grid.placed.size(); ++i) add(w, m, grid.placed[i], grid.radii[i]);
    return box;
}

} // namespace

Vec read_angular_velocity(const Node& n, int dim) {
    Vec spin = Vec::Zero();
    if (!n.has("angular_velocity")) return spin;
    if (dim == 2) spin.z() = n.at("angular_velocity").number();
    else spin = n.at("angular_velocity").vec(3);
    return spin;
}

std::string scene_path(const std::string& scene_dir, const std::string& file) {
    const std::filesystem::path given(file);
    return given.is_absolute() ? file : (std::filesystem::path(scene_dir) / given).string();
}

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

std::optional<Box> generate_bodies(const Node& n, World& w, const GeneratorLimits& limits, LatticeCells* cells,
                                   const std::string& scene_dir) {
    const std::string type = n.at("type").choice({"ball", "lattice", "random_fill", "clump", "rigid", "clump_fill"});
    if (type == "ball") {
        single_ball(n, w);
        return std::nullopt;
    }
    if (type == "clump" || type == "rigid") {
        generate_clump(n, w, scene_dir);
        return std::nullopt;
    }
    if (type == "clump_fill") {
        generate_clump_fill(n, w, scene_dir);
        return std::nullopt;
    }
    w.mark_dirty();
    return type == "lattice" ? lattice(n, w, limits, cells) : random_fill(n, w, limits, scene_dir);
}

namespace {

std::string list_text(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s.empty() ? "none" : s;
}

std::vector<std::string> choice_names(const plab_property_desc& d) {
    std::vector<std::string> names;
    for (uint32_t c = 0; c < d.choice_count; ++c) names.push_back(d.choices[c]);
    return names;
}

// A JSON number that is a whole number, as a long (for old numeric codes).
bool whole_number(const json& j, long& out) {
    if (!j.is_number()) return false;
    const double x = j.get<double>();
    if (!std::isfinite(x) || std::floor(x) != x || std::fabs(x) > 1e15) return false;
    out = long(x);
    return true;
}

std::string groups_text(const std::vector<std::string>& groups) { return "groups in this scene: " + list_text(groups); }

} // namespace

double read_property(const Node& v, const plab_property_desc& d, const std::vector<std::string>& groups) {
    const json& j = v.value();
    long code = 0;
    switch (d.kind) {
    case PLAB_KIND_BOOL:
        if (j.is_boolean()) return j.get<bool>() ? 1.0 : 0.0;
        if (whole_number(j, code) && (code == 0 || code == 1))
            v.fail(show(j) + " is a numeric code; write " + (code ? "true" : "false") + " (" + d.name + ": true or false)");
        v.fail(show(j) + " is not true or false (" + d.name + "); use true or false");
    case PLAB_KIND_CHOICE: {
        const std::vector<std::string> names = choice_names(d);
        if (j.is_string()) {
            const std::string s = j.get<std::string>();
            for (std::size_t c = 0; c < names.size(); ++c)
                if (names[c] == s) return double(c);
            v.fail(show(j) + " is not one of " + list_text(names) + " (" + d.name + ")");
        }
        if (whole_number(j, code) && code >= 0 && code < long(names.size()))
            v.fail(show(j) + " is a numeric code; write \"" + names[std::size_t(code)] + "\" (" + d.name + ": one of " +
                   list_text(names) + ")");
        v.fail(show(j) + " is not one of " + list_text(names) + " (" + d.name + "; write the name, in quotes)");
    }
    case PLAB_KIND_GROUP: {
        const bool none_allowed = d.flags & PLAB_GROUP_NONE_ALLOWED;
        if (j.is_null() || (j.is_string() && j.get<std::string>() == "none")) {
            if (none_allowed) return -1.0;
            v.fail(show(j) + ": " + d.name + " must name a group; " + groups_text(groups));
        }
        if (j.is_string()) {
            const std::string s = j.get<std::string>();
            for (std::size_t g = 0; g < groups.size(); ++g)
                if (groups[g] == s) return double(g);
            v.fail(show(j) + " is not a group of this scene (" + d.name + "); " + groups_text(groups) +
                   (none_allowed ? ", or null for none" : ""));
        }
        if (whole_number(j, code) && code >= 0 && code < long(groups.size()))
            v.fail(show(j) + " is a numeric code (a group index); write \"" + groups[std::size_t(code)] + "\" (" +
                   d.name + ": a group name; " + groups_text(groups) + ")");
        if (whole_number(j, code) && code == -1 && none_allowed)
            v.fail(show(j) + " is a numeric code; write null for none (" + d.name + ")");
        v.fail(show(j) + " is not a group name (" + d.name + "); " + groups_text(groups) +
               (none_allowed ? ", or null for none" : ""));
    }
    default: {
        // dimensionless properties have the unit "1": leave it out of messages
        const std::string unit = std::string(d.unit) == "1" ? "" : " " + std::string(d.unit);
        if (!j.is_number()) v.fail("expected a number in " + range_text(d) + unit + ", got " + show(j));
        const double x = j.get<double>();
        std::ostringstream s;
        if (d.kind == PLAB_KIND_INTEGER && std::isfinite(x) && std::floor(x) != x) {
            s << "value " << x << " of " << d.name << " is not a whole number; valid: " << range_text(d) << unit;
            v.fail(s.str());
        }
        if (!in_range(d, x)) {
            s << "value " << x << " of " << d.name << " is outside the valid range " << range_text(d) << unit;
            v.fail(s.str());
        }
        return x;
    }
    }
}

std::string property_value_text(const plab_property_desc& d, double value, const std::vector<std::string>& groups) {
    switch (d.kind) {
    case PLAB_KIND_BOOL: return value != 0.0 ? "true" : "false";
    case PLAB_KIND_CHOICE:
        return value >= 0 && value < double(d.choice_count) ? d.choices[std::size_t(value)] : short_number(value);
    case PLAB_KIND_GROUP:
        if (value < 0) return "none";
        return value < double(groups.size()) ? groups[std::size_t(value)] : short_number(value);
    default: return short_number(value);
    }
}

std::vector<double> read_properties(const Node& owner, const plab_property_desc* props, uint32_t count,
                                    const std::string& what, const std::vector<std::string>& groups) {
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
        values[p] = read_property(v, props[p], groups);
    }
    return values;
}

void check_required_properties(const Node& owner, const plab_property_desc* props, uint32_t count,
                               const std::vector<double>& values, const std::string& what,
                               const std::vector<std::string>& groups) {
    for (uint32_t p = 0; p < count; ++p)
        if (props[p].kind == PLAB_KIND_GROUP && !(props[p].flags & PLAB_GROUP_NONE_ALLOWED) && values[p] < 0)
            throw InputError(owner.path() + ".properties." + props[p].key,
                             std::string("missing: ") + what + " needs " + props[p].name + " named; " +
                                 groups_text(groups));
}

} // namespace plab
