// Cycle set-up (groups, assignment table, fields, passes) and the cycle.
// Detection lives in detection/, the force pass in forces/.
#include "world/cycle.hpp"

#include <plab_host/errors.hpp>

#include "common/buffers.hpp"
#include "forces/geometry.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace plab {

const char* const phase_names[ph_count] = {"timestep", "law_of_motion", "contact_detection", "pre_force_passes",
                                           "force_displacement", "reduction", "post_force_passes", "integration",
                                           "stability_checks"};

namespace {
struct PhaseTimer {
    double& slot;
    std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
    ~PhaseTimer() { slot += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); }
};
} // namespace

Cycle::Cycle(World& w, std::shared_ptr<PluginHost> plugins)
    : world(w), host(std::move(plugins)),
      reduction({w.dim, w.bodies, w.walls, w.fields, w.gravity, instances, tables.sets, tables.owner, tables.body_contacts, w.energies,
                 w.last_dt, w.parallel_min}),
      passes({w.dim, w.bodies, w.fields, pass_contacts, w.time, w.last_dt}),
      forces({w.dim, w.bodies, w.walls, w.fields, assignment, instances, passes, tables.sets, tables.owner, tables.body_contacts,
              pass_contacts, w.bond_breaks, w.time, w.step_count, w.last_dt, w.parallel_min},
             reduction),
      monitor({w.dim, w.bodies, w.clumps, w.walls, assignment, instances, tables.sets, tables.owner, tables.body_contacts, forces.packed, w.energies,
               w.parallel_min},
              w.step_count, w.time, w.last_dt, w.stopped) {}

Cycle::~Cycle() {
    for (auto& inst : instances)
        if (inst->desc->destroy && inst->state) inst->desc->destroy(inst->state);
}




void Cycle::run_passes(std::uint32_t phase) {
    if (passes.empty()) return;
    passes.run(phase, forces.pass_distances_current(), world.step_count, [this](const std::string& pass, const char* diagnostic) {
        monitor.stop(monitor.pass_diagnostic(pass, diagnostic));
    });
}

void Cycle::prepare() {
    world.bodies.trim();  // the scene is built: no more room for bodies than bodies
    world.fields.resize(world.bodies.size());
    monitor.stiffness.clear(world.bodies.size());
    neighbours.invalidate();
    world.bodies.cell.slide_to(world.time);
    {
        PhaseTimer t{world.phase_seconds[ph_detection]};
        rebuild();
    }
    // dt = 0 in the batch: evaluate forces at this state without advancing
    // incremental history (a re-evaluation must not add a shear increment)
    const double dt = world.last_dt;
    world.last_dt = 0;
    forces.write_contact_forces(true);  // (also after a step that failed before its forces)
    force_pass();
    finish_clumps(0.0, 0.0);
    leapfrog_.cache_inverse_masses(world.bodies);
    leapfrog_.body_energies(world.bodies, 0.0);
    sum_energies(0.0);  // states (kinetic, strain) at this instant; no flow
    world.last_dt = dt;
    prepared = true;
    monitor.detector.measure_baseline(world.energies, world.bodies, world.walls, world.gravity);
    world.stopped = Diagnostic{};  // a run that goes on after a stop is running again
}

// Kick–drift–kick form of the leapfrog (thesis eqs. 32–36): the same
// positions as v(t+dt/2) = v(t-dt/2) + a dt, x += v dt, but velocities are
// kept at whole steps so outputs, energies and restarts are synchronised.
// Models see the half-step velocity, as in PFC.
void Cycle::step() {
    at_last_good_ = false;
    if (world.snapshot_interval > 0 && (world.step_count % world.snapshot_interval == 0 || !last_good_.valid())) take_snapshot();
    try {
        advance();
    } catch (const RunError& e) {
        if (!last_good_.valid()) throw;
        const std::uint64_t failed_at = world.step_count;
        restore_snapshot();
        at_last_good_ = true;
        throw RunError(std::string(e.what()) + "; the world is back at its last good state, step " +
                       std::to_string(world.step_count) + " (t = " + std::to_string(world.time) + " s), " +
                       std::to_string(failed_at - world.step_count) + " steps before the failure",
                       e.quantity());
    }
}

void Cycle::take_snapshot() {
    if (!prepared) prepare();
    last_good_.keep(world.bodies, world.clumps, world.walls, world.fields, world.energies, {world.time, world.last_dt, world.step_count}, world.bond_breaks.size(), instances);
    monitor.keep_snapshot_step();
    if (world.on_snapshot) world.on_snapshot();
}

// Contact rows come back with their history; the world re-detects and
// re-evaluates forces at this state (dt = 0), as after any change, so that
// what is written at the stop (VTK, the last-good checkpoint) and the next
// step see the forces of this state.
void Cycle::restore_snapshot() {
    Clock clock;
    std::size_t breaks = 0;
    last_good_.restore(world.bodies, world.clumps, world.walls, world.fields, world.energies, clock, breaks, instances);
    world.time = clock.time;
    world.last_dt = clock.last_dt;
    world.step_count = clock.step_count;
    world.bond_breaks.resize(breaks);
    const Diagnostic why = world.stopped;  // prepare() clears it: a run that goes on is running again
    prepare();
    world.stopped = why;
}

void Cycle::advance() {
    if (!prepared) prepare();
    double dt;
    {
        PhaseTimer t{world.phase_seconds[ph_timestep]};
        dt = world.fixed_dt > 0 ? world.fixed_dt : world.safety_factor * monitor.stable_timestep().critical;
        if (!std::isfinite(dt) || dt <= 0)
            throw RunError("no stable timestep: no contact model reports a stiffness or step limit; set a fixed "
                           "timestep (timestep.fixed)");
        world.last_dt = dt;
    }
    {
        PhaseTimer t{world.phase_seconds[ph_motion]};
        kick_and_drift(dt);
        world.bodies.cell.slide_to(world.time + dt);  // (the positions' time)
        neighbours.walls_moved(world.walls.move(dt, world.dim));
    }
    {
        PhaseTimer t{world.phase_seconds[ph_detection]};
        if (neighbours.stale(world.bodies)) rebuild();
    }
    world.time += dt;
    ++world.step_count;
    const bool post_force = passes.any_at(PLAB_PHASE_POST_FORCE);
    forces.write_contact_forces(!world.contact_forces_wanted || world.contact_forces_wanted());
    force_pass(post_force ? 0.0 : 0.5 * dt);  // the closing half kick inside reduce(), unless a pass comes between
    {
        PhaseTimer t{world.phase_seconds[ph_motion]};
        if (post_force) leapfrog_.kick(world.bodies, 0.5 * dt, true, world.parallel_min);
        finish_clumps(0.5 * dt, dt);
        sum_energies(dt);
    }
    {
        PhaseTimer t{world.phase_seconds[ph_integrate]};
        run_passes(PLAB_PHASE_INTEGRATE);
    }
    {
        PhaseTimer t{world.phase_seconds[ph_stability]};
        monitor.detect_instability();
    }
}

void Cycle::force_pass(double closing_kick) {
    {
        PhaseTimer t{world.phase_seconds[ph_pre_force]};
        run_passes(PLAB_PHASE_PRE_FORCE);
    }
    {
        PhaseTimer t{world.phase_seconds[ph_force]};
        // a pass added since the last rebuild may need a rates stage over
        // full columns that a packed set lacks (packs_balls)
        bool repacked = false;
        for (auto& inst : instances)
            if (inst->balls.packed != forces.packs_balls(*inst)) {
                lay_out_columns(*inst, inst->balls);
                fill_pair_constants(world.bodies, inst->balls);
                repacked = true;
            }
        if (repacked) build_entries();  // (which rows it lists depends on packing)
        forces.run([this](std::uint32_t phase) { run_passes(phase); });
    }
    {
        PhaseTimer t{world.phase_seconds[ph_reduction]};
        const bool non_finite = reduction.reduce(closing_kick, forces.rows_summed(), leapfrog_);
        monitor.stiffness.invalidate();
        if (non_finite) monitor.check_finite();
    }
    {
        PhaseTimer t{world.phase_seconds[ph_post_force]};
        run_passes(PLAB_PHASE_POST_FORCE);
    }
}

// What the drift reads besides the bodies: gravity, the detector's domain,
// the positions at the last build and the drift correction fields.
DriftInputs Cycle::drift_inputs() const {
    DriftInputs in;
    in.gravity = world.gravity;
    in.lo = monitor.detector.baseline.lo;
    in.hi = monitor.detector.baseline.hi;
    in.position_at_build = &neighbours.position_at_build();
    const int cx = world.fields.index(PLAB_DRIFT_CORRECTION_X), cy = world.fields.index(PLAB_DRIFT_CORRECTION_Y),
              cz = world.fields.index(PLAB_DRIFT_CORRECTION_Z);
    if (cx >= 0 && cy >= 0 && cz >= 0) in.correction = {world.fields.column(cx).data(), world.fields.column(cy).data(), world.fields.column(cz).data()};
    return in;
}

void Cycle::take_drift(const DriftResult& r) {
    world.energies.body += r.body_work;
    monitor.set_left_domain(r.left_domain);
    neighbours.bodies_moved(r.max_drift2);
}

// The first half of a step's law of motion: half a kick, the PRE_DRIFT
// passes (e.g. XSPH: a drift velocity correction from v(t + dt/2)), the
// drift; without such a pass or correction, in one loop.
void Cycle::kick_and_drift(double dt) {
    const DriftInputs in = drift_inputs();
    Clumps& clumps = world.clumps;
    if (clumps.size()) clump_motion_.hold_pebbles(clumps, world.bodies);
    DriftResult balls;
    if (passes.any_at(PLAB_PHASE_PRE_DRIFT) || in.corrected()) {
        leapfrog_.kick(world.bodies, 0.5 * dt, false, world.parallel_min);
        run_passes(PLAB_PHASE_PRE_DRIFT);
        balls = leapfrog_.drift(world.bodies, drift_inputs(), dt, world.parallel_min);
    } else {
        balls = leapfrog_.kick_and_drift(world.bodies, in, dt, world.parallel_min);
    }
    if (clumps.size()) balls = clump_motion_.kick_and_drift(clumps, world.bodies, in, dt, balls, world.parallel_min);
    take_drift(balls);
}

void Cycle::finish_clumps(double half_dt, double dt) {
    if (!world.clumps.size()) { clump_energies_ = {}; return; }
    clump_energies_ = clump_motion_.finish(world.clumps, world.bodies, world.gravity, half_dt, dt, world.parallel_min);
    world.energies.local_damping += clump_energies_.local_damping;
}



// Energy flows over the step just taken; states (kinetic, strain) are
// recomputed at the synchronised velocities.
void Cycle::sum_energies(double dt) {
    // the bodies' part, summed per block by the closing kick or body_energies()
    const double kinetic = leapfrog_.kinetic() + clump_energies_.kinetic;
    double boundary = leapfrog_.boundary_work() + clump_energies_.boundary;
    // contact energies, summed per batch of rows by scatter_rows()
    double strain = 0;
    for (const ContactSet* s : tables.sets)
        for (std::size_t b = 0; b < s->batch_energy.size(); b += kBatchEnergies) {
            const double* e = &s->batch_energy[b];
            strain += e[0];
            if (dt == 0) continue;  // a re-evaluation, not a step: no dissipation
            world.energies.slip += e[1];
            world.energies.dashpot += e[2];
            world.energies.bond_break += e[3];
            boundary += e[4] * dt;  // work of the walls on the balls
        }
    world.energies.kinetic = kinetic;
    world.energies.strain = strain;
    world.energies.boundary += boundary;
}




} // namespace plab
