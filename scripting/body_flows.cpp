#include "body_flows.hpp"

#include <plab_host/checkpoint.hpp>

#include <algorithm>
#include <cmath>

namespace plab {

namespace {

// Where a body is, against a box of the world's dimension.
bool inside(const Box& b, const Vec& p, int dim) {
    for (int c = 0; c < dim; ++c)
        if (p[c] < b.lo[c] || p[c] > b.hi[c]) return false;
    return true;
}

// A list entry's "name" (default <kind><index>), once in its list.
template <class T>
std::string read_name(const Node& e, std::size_t i, const char* kind, const std::vector<T>& before) {
    const std::string name = e.string_or("name", kind + std::to_string(i));
    for (const T& t : before)
        if (t.name == name) e.at("name").fail("the name \"" + name + "\" is taken by an earlier " + kind);
    return name;
}

// The inlet's rate: one of count_per_second (balls/s) and mass_per_second (kg/s).
void read_rate(const Node& r, Inlet& in) {
    r.allow_keys({"count_per_second", "mass_per_second"});
    if (r.has("count_per_second") == r.has("mass_per_second"))
        r.fail("give one of \"count_per_second\" (balls/s) and \"mass_per_second\" (kg/s)");
    in.by_mass = r.has("mass_per_second");
    in.rate = r.at(in.by_mass ? "mass_per_second" : "count_per_second").positive();
}

double ball_mass(const World& w, const Inlet& in, double r) { return Bodies::mass_of(w.dim, r, in.material.density); }

// The balls due at the world's time: those the rate has made since the
// start, up to the total; by mass, while the mass inserted is short of it.
bool more_due(const Inlet& in, const World& w) {
    if (in.inserted >= in.total) return false;
    if (in.by_mass) return in.mass < in.rate * w.time;
    return double(in.inserted) < std::floor(in.rate * w.time);
}

} // namespace

void BodyFlows::read_inlets(const Node& n, World& w, const std::string& scene_dir) {
    n.expect_array();
    for (std::size_t i = 0; i < n.size(); ++i) {
        const Node e = n.at(i);
        e.allow_keys({"name", "box", "radius", "density", "group", "velocity", "rate", "total", "every", "seed",
                      "max_attempts", "local_damping", "viscous_damping"});
        Inlet in;
        in.name = read_name(e, i, "inlet", inlets_);
        if (e.at("radius").value().is_object()) in.sizes.emplace(e.at("radius"), w.dim, scene_dir);
        in.material = read_material(e, w, true, false, in.sizes ? &*in.sizes : nullptr);
        in.box = read_box(e.at("box"), w.dim);
        for (int c = 0; c < w.dim; ++c)
            if (in.box.hi[c] - in.box.lo[c] < 2 * in.material.radius_hi)
                e.at("box").fail("the box is narrower than the largest ball's diameter " +
                                 std::to_string(2 * in.material.radius_hi) + " m in direction " + std::to_string(c));
        in.velocity = e.vec_or("velocity", w.dim, Vec::Zero());
        read_rate(e.at("rate"), in);
        in.total = e.at("total").integer(1, 100000000);
        in.every = e.has("every") ? e.at("every").integer(1, 1L << 40) : 100;
        in.rng = Rng(std::uint64_t(e.has("seed") ? e.at("seed").integer(0, 1L << 40) : 1));
        in.max_attempts = e.has("max_attempts") ? e.at("max_attempts").integer(1, 1L << 30) : 1000;
        inlets_.push_back(std::move(in));
    }
}

void BodyFlows::read_outlets(const Node& n, World& w) {
    n.expect_array();
    for (std::size_t i = 0; i < n.size(); ++i) {
        const Node e = n.at(i);
        e.allow_keys({"name", "box", "every"});
        Outlet out;
        out.name = read_name(e, i, "outlet", outlets_);
        out.box = read_box(e.at("box"), w.dim);
        out.every = e.has("every") ? e.at("every").integer(1, 1L << 40) : 100;
        outlets_.push_back(std::move(out));
    }
}

namespace {

// The free balls whose centre is in the outlet's box, removed and counted
// (a clump's pebbles stay: a clump leaves whole or not at all).
void remove_in(Outlet& out, World& w) {
    const Bodies& b = w.bodies;
    std::vector<std::uint8_t> gone(b.size(), 0);
    std::size_t n = 0;
    double mass = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
        if (!inside(out.box, b.position[i], w.dim) || (!b.clump.empty() && b.clump[i] >= 0)) continue;
        gone[i] = 1;
        ++n;
        mass += b.mass[i];
    }
    if (n == 0) return;
    remove_bodies(w, gone);
    out.removed += long(n);
    out.mass += mass;
}

// The balls due, each at a random place in the box that overlaps no ball
// of the world nor one just added; a ball that finds no place in
// max_attempts waits for the next time, with those after it.
void insert_due(Inlet& in, World& w) {
    if (!more_due(in, w)) return;
    const double r_hi = in.material.radius_hi;
    FillGrid grid(in.box, w.dim, r_hi, 64);
    Box reach = in.box;  // the balls a new one could touch
    for (int c = 0; c < w.dim; ++c) {
        reach.lo[c] -= 2 * r_hi;
        reach.hi[c] += 2 * r_hi;
    }
    const Bodies& b = w.bodies;
    for (std::size_t i = 0; i < b.size(); ++i)
        if (inside(reach, b.position[i], w.dim)) grid.occupy(b.position[i], b.radius[i]);
    bool added = false;
    while (more_due(in, w)) {
        const double r = in.sizes ? in.sizes->draw(in.rng) : in.rng.uniform(in.material.radius_lo, r_hi);
        Vec p;
        bool placed = false;
        for (long a = 0; a < in.max_attempts && !placed; ++a) placed = grid.draw_position(in.rng, r, p) && grid.place(p, r);
        if (!placed) break;
        add(w, in.material, p, r, in.velocity);
        ++in.inserted;
        in.mass += ball_mass(w, in, r);
        added = true;
    }
    if (added) w.mark_dirty();
}

} // namespace

void BodyFlows::before_step(World& w) {
    for (Outlet& out : outlets_)
        if (w.step_count % std::uint64_t(out.every) == 0) remove_in(out, w);
    for (Inlet& in : inlets_)
        if (w.step_count % std::uint64_t(in.every) == 0) insert_due(in, w);
}

std::function<double(const World&)> BodyFlows::quantity(const Node& column) const {
    const std::string q = column.at("quantity").string();
    const bool of_inlet = q == "inlet.count" || q == "inlet.mass", of_outlet = q == "outlet.count" || q == "outlet.mass";
    if (!of_inlet && !of_outlet) return nullptr;
    const bool count = q == "inlet.count" || q == "outlet.count";
    const Node named = column.at(of_inlet ? "inlet" : "outlet");
    const std::string name = named.string();
    std::string names;
    if (of_inlet) {
        for (const Inlet& in : inlets_) {
            if (in.name == name)
                return [p = &in, count](const World&) { return count ? double(p->inserted) : p->mass; };
            names += (names.empty() ? "" : ", ") + in.name;
        }
    } else {
        for (const Outlet& out : outlets_) {
            if (out.name == name)
                return [p = &out, count](const World&) { return count ? double(p->removed) : p->mass; };
            names += (names.empty() ? "" : ", ") + out.name;
        }
    }
    named.fail("unknown " + std::string(of_inlet ? "inlet" : "outlet") + " \"" + name + "\"; the scene has: " +
               (names.empty() ? "none" : names));
}

void BodyFlows::save(CheckpointWriter& out) const {
    out.section("flows");
    out.u64(inlets_.size());
    for (const Inlet& in : inlets_) {
        out.str(in.name);
        out.u64(std::uint64_t(in.inserted));
        out.f64(in.mass);
        out.u64(in.rng.state());
    }
    out.u64(outlets_.size());
    for (const Outlet& o : outlets_) {
        out.str(o.name);
        out.u64(std::uint64_t(o.removed));
        out.f64(o.mass);
    }
}

void BodyFlows::load(CheckpointReader& in) {
    in.section("flows");
    if (in.u64() != inlets_.size()) in.fail("the scene now has " + std::to_string(inlets_.size()) + " inlets, the run had another number");
    for (Inlet& i : inlets_) {
        if (in.str() != i.name) in.fail("the inlets differ from the run's (names)");
        i.inserted = long(in.u64());
        i.mass = in.f64();
        i.rng.set_state(in.u64());
    }
    if (in.u64() != outlets_.size()) in.fail("the scene now has " + std::to_string(outlets_.size()) + " outlets, the run had another number");
    for (Outlet& o : outlets_) {
        if (in.str() != o.name) in.fail("the outlets differ from the run's (names)");
        o.removed = long(in.u64());
        o.mass = in.f64();
    }
}

} // namespace plab
