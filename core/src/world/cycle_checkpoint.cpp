#include "world/cycle_checkpoint.hpp"

#include "bodies/bodies_checkpoint.hpp"
#include "contacts/contacts_checkpoint.hpp"
#include "detection/detection_checkpoint.hpp"
#include "host/passes_checkpoint.hpp"
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
        {[&](CheckpointWriter& out) { save_passes(c.passes, *c.host, out); }, [&](CheckpointReader& in) { load_passes(c.passes, *c.host, in); }},
        {[&](CheckpointWriter& out) { save_bond_breaks(w.bond_breaks, out); }, [&](CheckpointReader& in) { load_bond_breaks(w.bond_breaks, in); }},
        {[](CheckpointWriter& out) { save_rng(out); }, [](CheckpointReader& in) { load_rng(in); }},
        {[&](CheckpointWriter& out) { save_stability(c.monitor.detector.baseline, out); },
         [&](CheckpointReader& in) {
             if (in.format() >= 2) load_stability(c.monitor.detector.baseline, in);
             else c.monitor.detector.measure_baseline(w.energies, w.bodies, w.walls, w.gravity);  // format 1: none saved
         }},
    };
}

} // namespace plab
