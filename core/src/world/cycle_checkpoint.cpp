#include "world/cycle_checkpoint.hpp"

#include "bodies/bodies_checkpoint.hpp"
#include "contacts/contacts_checkpoint.hpp"
#include "detection/detection_checkpoint.hpp"
#include "passes/passes_checkpoint.hpp"
#include "monitor/monitor_checkpoint.hpp"
#include "world/cycle.hpp"

namespace plab {

namespace {

void save_clock(const World& w, std::uint64_t rebuilds, CheckpointWriter& out) {
    out.section("world");
    out.u32(std::uint32_t(w.dim));
    out.f64(w.time);
    out.u64(w.step_count);
    out.f64(w.last_dt);
    out.vec(w.gravity);
    out.u64(rebuilds);
    const Energies& e = w.energies;
    for (double v : {e.kinetic, e.strain, e.body, e.boundary, e.slip, e.dashpot, e.local_damping, e.bond_break}) out.f64(v);
}

void load_clock(World& w, std::uint64_t& rebuilds, CheckpointReader& in) {
    in.section("world");
    const std::uint32_t dim = in.u32();
    if (int(dim) != w.dim) in.fail("a " + std::to_string(dim) + "D state for a " + std::to_string(w.dim) + "D scene");
    w.time = in.f64();
    w.step_count = in.u64();
    w.last_dt = in.f64();
    w.gravity = in.vec();
    rebuilds = in.u64();
    Energies& e = w.energies;
    for (double* v : {&e.kinetic, &e.strain, &e.body, &e.boundary, &e.slip, &e.dashpot, &e.local_damping, &e.bond_break})
        *v = in.f64();
}

void save_bond_breaks(const std::vector<BondBreak>& breaks, CheckpointWriter& out) {
    out.section("bond_breaks");
    out.u64(breaks.size());
    for (const BondBreak& b : breaks) {
        out.u64(b.step);
        out.f64(b.time);
        out.u64(b.id1);
        out.u64(b.id2);
        out.vec(b.point);
        out.u32(std::uint32_t(b.mode));
        out.str(b.model);
    }
}

void load_bond_breaks(std::vector<BondBreak>& breaks, CheckpointReader& in) {
    in.section("bond_breaks");
    breaks.resize(in.u64());
    for (BondBreak& b : breaks) {
        b.step = in.u64();
        b.time = in.f64();
        b.id1 = in.u64();
        b.id2 = in.u64();
        b.point = in.vec();
        b.mode = int(in.u32());
        b.model = in.str();
    }
}

// The kernel draws no random numbers while it runs (generators draw theirs,
// seeded, when the scene loads): no generator state to carry.
void save_rng(CheckpointWriter& out) {
    out.section("rng");
    out.u64(0);
}

void load_rng(CheckpointReader& in) {
    in.section("rng");
    if (in.u64() != 0) in.fail("it holds random-number generator states this build has no use for");
}

// The clumps (format 4): every column, and which clump each ball is a pebble of.
void save_clumps(const World& w, CheckpointWriter& out) {
    const Clumps& C = w.clumps;
    out.section("clumps");
    out.column(w.bodies.clump);
    out.column(C.id);
    for (const auto* v : {&C.position, &C.velocity, &C.angular_velocity, &C.angular_momentum, &C.principal_moments,
                          &C.force, &C.moment, &C.pebble_offset})
        out.vecs(*v);
    out.u64(C.orientation.size());
    for (const Eigen::Quaterniond& q : C.orientation)
        for (double x : {q.w(), q.x(), q.y(), q.z()}) out.f64(x);
    out.column(C.mass);
    out.column(C.local_damping);
    out.column(C.fixity);
    out.column(C.group);
    out.column(C.first_pebble);
    out.column(C.pebble_body);
}

void load_clumps(World& w, int groups, CheckpointReader& in) {
    Clumps& C = w.clumps;
    in.section("clumps");
    w.bodies.clump = in.column<std::int32_t>();
    C.dim = w.dim;
    C.id = in.column<BodyId>();
    for (auto* v : {&C.position, &C.velocity, &C.angular_velocity, &C.angular_momentum, &C.principal_moments,
                    &C.force, &C.moment, &C.pebble_offset})
        *v = in.vecs();
    C.orientation.resize(in.u64());
    for (Eigen::Quaterniond& q : C.orientation) {
        const double qw = in.f64(), qx = in.f64(), qy = in.f64(), qz = in.f64();
        q = Eigen::Quaterniond(qw, qx, qy, qz);
    }
    C.mass = in.column<double>();
    C.local_damping = in.column<double>();
    C.fixity = in.column<std::uint8_t>();
    C.group = in.column<int>();
    C.first_pebble = in.column<std::size_t>();
    C.pebble_body = in.column<std::int32_t>();
    const std::size_t n = C.id.size();
    bool whole = !w.bodies.clump.empty() ? w.bodies.clump.size() == w.bodies.size() : n == 0;
    for (const auto* v : {&C.position, &C.velocity, &C.angular_velocity, &C.angular_momentum, &C.principal_moments,
                          &C.force, &C.moment})
        whole &= v->size() == n;
    whole &= C.orientation.size() == n && C.mass.size() == n && C.local_damping.size() == n && C.fixity.size() == n &&
             C.group.size() == n && C.first_pebble.size() == n + 1 && C.pebble_offset.size() == C.pebble_body.size() &&
             !C.first_pebble.empty() && C.first_pebble.back() == C.pebble_body.size();
    for (int g : C.group) whole &= g >= 0 && g < groups;
    for (std::int32_t i : C.pebble_body) whole &= i >= 0 && std::size_t(i) < w.bodies.size();
    if (!whole) in.fail("its clumps do not match its bodies (column sizes, pebble indices or groups)");
    if (C.surface.size() != n) C.surface.assign(n, -1);  // the scene's surfaces, kept when the scene built the same clumps
}

// The periodic cell (format 6): which axes are periodic and the cell's
// bounds, and (format 7) its shear and its offset when the lists were last
// built; a restart continues in the cell the run was in.
void save_periodic_cell(const PeriodicCell& cell, double offset_at_build, CheckpointWriter& out) {
    out.section("periodic_cell");
    for (bool p : cell.periodic) out.u32(p ? 1 : 0);
    out.vec(cell.lo);
    out.vec(cell.hi);
    out.u32(cell.sheared ? 1 : 0);  // (format 7: Lees–Edwards)
    out.f64(cell.shear_rate);
    out.f64(cell.shear_offset);
    out.f64(offset_at_build);
}

void load_periodic_cell(PeriodicCell& cell, NeighbourLists& lists, CheckpointReader& in) {
    in.section("periodic_cell");
    for (bool& p : cell.periodic) p = in.u32() != 0;
    cell.lo = in.vec();
    cell.hi = in.vec();
    if (in.format() >= 7) {
        cell.sheared = in.u32() != 0;
        cell.shear_rate = in.f64();
        cell.shear_offset = in.f64();
        lists.restore_offset_at_build(in.f64());
    }
    for (int c = 0; c < 3; ++c)
        if (cell.periodic[c] && !(cell.hi[c] > cell.lo[c])) in.fail("its periodic cell has no extent along a periodic axis");
}

} // namespace

std::vector<CheckpointSection> checkpoint_sections(Cycle& c) {
    World& w = c.world;
    const DetectionState detection{c.neighbours, c.pass_contacts, c.prepared};
    const int groups = c.assignment.group_count();
    return {
        {[&](CheckpointWriter& out) { save_clock(w, c.neighbours.rebuilds, out); },
         [&](CheckpointReader& in) { load_clock(w, c.neighbours.rebuilds, in); }},
        {[&](CheckpointWriter& out) { save_assignment(c.assignment, out); },
         [&](CheckpointReader& in) { load_assignment(c.assignment, c.instances.size(), in); }},
        {[&](CheckpointWriter& out) { save_bodies(w.bodies, out); }, [&, groups](CheckpointReader& in) { load_bodies(w.bodies, groups, in); }},
        {[&](CheckpointWriter& out) { save_walls(w.walls, out); }, [&, groups](CheckpointReader& in) { load_walls(w.walls, groups, in); }},
        {[&](CheckpointWriter& out) { save_fields(w.fields, out); }, [&](CheckpointReader& in) { load_fields(w.fields, w.bodies.size(), in); }},
        {[&](CheckpointWriter& out) { save_contacts(c.instances, w.bodies, w.walls, out); },
         [&](CheckpointReader& in) {
             load_contacts(c.instances, w.bodies, w.walls, *c.host,
                           [&](const ModelInstance& inst) { return c.forces.packs_balls(inst); }, in);
         }},
        {[&, detection](CheckpointWriter& out) { save_detection(detection, c.monitor.summed_stiffness(), out); },
         [&, detection](CheckpointReader& in) { load_detection(detection, c.monitor.stiffness, w.bodies.size(), in); }},
        {[&](CheckpointWriter& out) { save_passes(c.passes.instances(), *c.host, out); }, [&](CheckpointReader& in) { load_passes(c.passes.instances(), *c.host, in); }},
        {[&](CheckpointWriter& out) { save_bond_breaks(w.bond_breaks, out); }, [&](CheckpointReader& in) { load_bond_breaks(w.bond_breaks, in); }},
        {[](CheckpointWriter& out) { save_rng(out); }, [](CheckpointReader& in) { load_rng(in); }},
        {[&](CheckpointWriter& out) { save_stability(c.monitor.detector.baseline, out); },
         [&](CheckpointReader& in) {
             if (in.format() >= 2) load_stability(c.monitor.detector.baseline, in);
             else c.monitor.detector.measure_baseline(w.energies, w.bodies, w.walls, w.gravity);  // format 1: none saved
         }},
        {[&](CheckpointWriter& out) { save_clumps(w, out); },
         [&, groups](CheckpointReader& in) {
             if (in.format() >= 4) load_clumps(w, groups, in);
             else w.clumps = Clumps{};  // before format 4: no clumps
         }},
        {[&](CheckpointWriter& out) { save_periodic_cell(w.bodies.cell, c.neighbours.offset_at_build(), out); },
         [&](CheckpointReader& in) {
             if (in.format() >= 6) load_periodic_cell(w.bodies.cell, c.neighbours, in);
             else w.bodies.cell = PeriodicCell{};  // before format 6: no periodic axis
         }},
    };
}

} // namespace plab
