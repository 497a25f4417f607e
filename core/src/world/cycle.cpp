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
    : dim(w.dim), bodies(w.bodies), walls(w.walls), fields(w.fields), gravity(w.gravity), parallel_min(w.parallel_min),
      fixed_dt(w.fixed_dt), safety_factor(w.safety_factor), time(w.time), step_count(w.step_count), last_dt(w.last_dt),
      contact_forces_wanted(w.contact_forces_wanted), bond_breaks(w.bond_breaks), snapshot_interval(w.snapshot_interval),
      lean_rebuild_rows(w.lean_rebuild_rows), on_snapshot(w.on_snapshot), stopped(w.stopped), energies(w.energies),
      phase_seconds(w.phase_seconds), host(std::move(plugins)),
      reduction({dim, bodies, walls, fields, gravity, instances, sets_, set_owner_, body_contacts_, energies, last_dt,
                 parallel_min}),
      forces({dim, bodies, walls, fields, assignment, instances, passes, sets_, set_owner_, body_contacts_, pass_contacts,
              bond_breaks, time, step_count, last_dt, parallel_min},
             reduction),
      monitor({dim, bodies, walls, assignment, instances, sets_, set_owner_, body_contacts_, forces.packed, energies,
               parallel_min},
              step_count, time, last_dt, stopped) {}

Cycle::~Cycle() {
    for (auto& inst : instances)
        if (inst->desc->destroy && inst->state) inst->desc->destroy(inst->state);
    for (auto& p : passes)
        if (p.desc->destroy && p.state) p.desc->destroy(p.state);
}

int Cycle::add_instance(const std::string& model, std::vector<double> props) {
    const plab_contact_model_desc* d = host->model(model);
    if (!d) throw InputError("", "contact model '" + model + "' is not loaded");
    auto inst = std::make_unique<ModelInstance>();
    inst->model = model;
    inst->desc = d;
    inst->props = std::move(props);
    inst->state = d->create ? d->create(inst->props.data()) : nullptr;
    if (d->create && !inst->state)
        throw PluginError("contact model '" + model + "' (" + host->library_of_model(model) +
                          ") failed to create an instance from its properties");
    inst->range = d->activity_range(inst->props.data());
    if (!std::isfinite(inst->range))
        throw PluginError("contact model '" + model + "' reports a non-finite activity range");
    inst->stride = int(d->history_count);
    // overlap means something for mechanical contacts only (SPH pairs are
    // "in contact" at a distance)
    inst->max_overlap = d->range_kind == PLAB_RANGE_GAP ? 1.0 : kInf;
    if (d->fields_read_count > ReadFields::kMax)
        throw PluginError("contact model '" + model + "' reads " + std::to_string(d->fields_read_count) +
                          " body fields; plab passes at most " + std::to_string(ReadFields::kMax));
    for (uint32_t f = 0; f < d->fields_read_count; ++f)
        inst->fields_read.push_back(register_field(d->fields_read[f].name, d->fields_read[f].default_value, d->fields_read[f].unit));
    for (uint32_t f = 0; f < d->fields_accumulated_count; ++f)
        inst->fields_accumulated.push_back(
            register_field(d->fields_accumulated[f].name, d->fields_accumulated[f].default_value,
                           d->fields_accumulated[f].unit));
    inst->walls.with_wall = true;
    for (ContactSet* s : {&inst->balls, &inst->walls}) {
        s->model_io = d->io;
        s->model_flags = d->flags;
    }
    instances.push_back(std::move(inst));
    mark_dirty();
    return int(instances.size()) - 1;
}

void Cycle::assign(int a, int b, int instance) {
    assignment.assign(a, b, instance);
    mark_dirty();
}

void Cycle::add_pass(const std::string& name, std::vector<double> props) {
    const plab_pass_desc* d = host->pass(name);
    if (!d) throw InputError("", "pass '" + name + "' is not loaded");
    PassInstance p;
    p.desc = d;
    p.props = std::move(props);
    p.state = d->create ? d->create(p.props.data()) : nullptr;
    if (d->create && !p.state) throw PluginError("pass '" + name + "' failed to create its state");
    for (uint32_t f = 0; f < d->field_count; ++f)
        p.fields.push_back(register_field(d->fields[f].name, d->fields[f].default_value, d->fields[f].unit));
    // stable order: by phase, then stage, then order of addition
    auto it = passes.begin();
    while (it != passes.end() &&
           (it->desc->phase < d->phase || (it->desc->phase == d->phase && it->desc->stage <= d->stage)))
        ++it;
    passes.insert(it, std::move(p));
}

bool Cycle::has_passes(std::uint32_t phase) const {
    return std::any_of(passes.begin(), passes.end(), [phase](const PassInstance& p) { return p.desc->phase == phase; });
}

void Cycle::run_passes(std::uint32_t phase) {
    if (passes.empty()) return;
    std::vector<double*> cols;
    for (auto& p : passes) {
        if (p.desc->phase != phase) continue;
        cols.clear();
        for (int f : p.fields) cols.push_back(fields.column(f).data());
        plab_pass_view v{sizeof(plab_pass_view)};
        v.dim = uint32_t(dim);
        v.body_count = uint32_t(bodies.size());
        v.dt = last_dt;
        v.time = time;
        v.position = bodies.position.empty() ? nullptr : bodies.position[0].data();
        v.velocity = bodies.velocity.empty() ? nullptr : bodies.velocity[0].data();
        v.force = bodies.force.empty() ? nullptr : bodies.force[0].data();
        v.radius = bodies.radius.data();
        v.mass = bodies.mass.data();
        v.group = bodies.group.data();
        v.fields = cols.data();
        v.contact_count = uint32_t(pass_contacts.size());
        v.contact_end1 = pass_contacts.end1();
        v.contact_end2 = pass_contacts.end2();
        v.contact_end2_is_wall = pass_contacts.end2_is_wall();
        // the distances hold at these positions while the range test's lists do
        v.contact_distance = pass_contacts.distance(forces.pass_distances_current());
        char diagnostic[2048];  // room for a pass's advice (sph_eos: ~800 characters)
        diagnostic[0] = '\0';
        v.diagnostic = diagnostic;
        v.diagnostic_capacity = sizeof diagnostic;
        const int rc = p.desc->run(p.state, p.props.data(), &v);
        if (rc == PLAB_PASS_UNSTABLE) monitor.stop(monitor.pass_diagnostic(p.desc->name, diagnostic));
        if (rc != 0)
            throw RunError(std::string("pass '") + p.desc->name + "' failed at step " + std::to_string(step_count));
    }
}

void Cycle::prepare() {
    bodies.trim();  // the scene is built: no more room for bodies than bodies
    fields.resize(bodies.size());
    monitor.stiffness.clear(bodies.size());
    neighbours.invalidate();
    {
        PhaseTimer t{phase_seconds[ph_detection]};
        rebuild();
    }
    // dt = 0 in the batch: evaluate forces at this state without advancing
    // incremental history (a re-evaluation must not add a shear increment)
    const double dt = last_dt;
    last_dt = 0;
    forces.write_contact_forces(true);  // (also after a step that failed before its forces)
    force_pass();
    leapfrog_.cache_inverse_masses(bodies);
    leapfrog_.body_energies(bodies, 0.0);
    sum_energies(0.0);  // states (kinetic, strain) at this instant; no flow
    last_dt = dt;
    prepared = true;
    monitor.detector.measure_baseline(energies, bodies, walls, gravity);
    stopped = Diagnostic{};  // a run that goes on after a stop is running again
}

// Kick–drift–kick form of the leapfrog (thesis eqs. 32–36): the same
// positions as v(t+dt/2) = v(t-dt/2) + a dt, x += v dt, but velocities are
// kept at whole steps so outputs, energies and restarts are synchronised.
// Models see the half-step velocity, as in PFC.
void Cycle::step() {
    at_last_good_ = false;
    if (snapshot_interval > 0 && (step_count % snapshot_interval == 0 || !last_good_.valid())) take_snapshot();
    try {
        advance();
    } catch (const RunError& e) {
        if (!last_good_.valid()) throw;
        const std::uint64_t failed_at = step_count;
        restore_snapshot();
        at_last_good_ = true;
        throw RunError(std::string(e.what()) + "; the world is back at its last good state, step " +
                       std::to_string(step_count) + " (t = " + std::to_string(time) + " s), " +
                       std::to_string(failed_at - step_count) + " steps before the failure",
                       e.quantity());
    }
}

void Cycle::take_snapshot() {
    if (!prepared) prepare();
    last_good_.keep(bodies, walls, fields, energies, {time, last_dt, step_count}, bond_breaks.size(), instances);
    monitor.keep_snapshot_step();
    if (on_snapshot) on_snapshot();
}

// Contact rows come back with their history; the world re-detects and
// re-evaluates forces at this state (dt = 0), as after any change, so that
// what is written at the stop (VTK, the last-good checkpoint) and the next
// step see the forces of this state.
void Cycle::restore_snapshot() {
    Clock clock;
    std::size_t breaks = 0;
    last_good_.restore(bodies, walls, fields, energies, clock, breaks, instances);
    time = clock.time;
    last_dt = clock.last_dt;
    step_count = clock.step_count;
    bond_breaks.resize(breaks);
    const Diagnostic why = stopped;  // prepare() clears it: a run that goes on is running again
    prepare();
    stopped = why;
}

void Cycle::advance() {
    if (!prepared) prepare();
    double dt;
    {
        PhaseTimer t{phase_seconds[ph_timestep]};
        dt = fixed_dt > 0 ? fixed_dt : safety_factor * monitor.stable_timestep().critical;
        if (!std::isfinite(dt) || dt <= 0)
            throw RunError("no stable timestep: no contact model reports a stiffness or step limit; set a fixed "
                           "timestep (timestep.fixed)");
        last_dt = dt;
    }
    {
        PhaseTimer t{phase_seconds[ph_motion]};
        kick_and_drift(dt);
        neighbours.walls_moved(walls.move(dt, dim));
    }
    {
        PhaseTimer t{phase_seconds[ph_detection]};
        if (neighbours.stale(bodies)) rebuild();
    }
    time += dt;
    ++step_count;
    const bool post_force = has_passes(PLAB_PHASE_POST_FORCE);
    forces.write_contact_forces(!contact_forces_wanted || contact_forces_wanted());
    force_pass(post_force ? 0.0 : 0.5 * dt);  // the closing half kick inside reduce(), unless a pass comes between
    {
        PhaseTimer t{phase_seconds[ph_motion]};
        if (post_force) leapfrog_.kick(bodies, 0.5 * dt, true, parallel_min);
        sum_energies(dt);
    }
    {
        PhaseTimer t{phase_seconds[ph_integrate]};
        run_passes(PLAB_PHASE_INTEGRATE);
    }
    {
        PhaseTimer t{phase_seconds[ph_stability]};
        monitor.detect_instability();
    }
}

void Cycle::force_pass(double closing_kick) {
    {
        PhaseTimer t{phase_seconds[ph_pre_force]};
        run_passes(PLAB_PHASE_PRE_FORCE);
    }
    {
        PhaseTimer t{phase_seconds[ph_force]};
        // a pass added since the last rebuild may need a rates stage over
        // full columns that a packed set lacks (packs_balls)
        bool repacked = false;
        for (auto& inst : instances)
            if (inst->balls.packed != forces.packs_balls(*inst)) {
                lay_out_columns(*inst, inst->balls);
                fill_pair_constants(inst->balls);
                repacked = true;
            }
        if (repacked) build_entries();  // (which rows it lists depends on packing)
        forces.run([this](std::uint32_t phase) { run_passes(phase); });
    }
    {
        PhaseTimer t{phase_seconds[ph_reduction]};
        const bool non_finite = reduction.reduce(closing_kick, forces.rows_summed(), leapfrog_);
        monitor.stiffness.invalidate();
        if (non_finite) monitor.check_finite();
    }
    {
        PhaseTimer t{phase_seconds[ph_post_force]};
        run_passes(PLAB_PHASE_POST_FORCE);
    }
}

// What the drift reads besides the bodies: gravity, the detector's domain,
// the positions at the last build and the drift correction fields.
DriftInputs Cycle::drift_inputs() const {
    DriftInputs in;
    in.gravity = gravity;
    in.lo = monitor.detector.baseline.lo;
    in.hi = monitor.detector.baseline.hi;
    in.position_at_build = &neighbours.position_at_build();
    const int cx = fields.index(PLAB_DRIFT_CORRECTION_X), cy = fields.index(PLAB_DRIFT_CORRECTION_Y),
              cz = fields.index(PLAB_DRIFT_CORRECTION_Z);
    if (cx >= 0 && cy >= 0 && cz >= 0) in.correction = {fields.column(cx).data(), fields.column(cy).data(), fields.column(cz).data()};
    return in;
}

void Cycle::take_drift(const DriftResult& r) {
    energies.body += r.body_work;
    monitor.set_left_domain(r.left_domain);
    neighbours.bodies_moved(r.max_drift2);
}

// The first half of a step's law of motion: half a kick, the PRE_DRIFT
// passes (e.g. XSPH: a drift velocity correction from v(t + dt/2)), the
// drift; without such a pass or correction, in one loop.
void Cycle::kick_and_drift(double dt) {
    const DriftInputs in = drift_inputs();
    if (has_passes(PLAB_PHASE_PRE_DRIFT) || in.corrected()) {
        leapfrog_.kick(bodies, 0.5 * dt, false, parallel_min);
        run_passes(PLAB_PHASE_PRE_DRIFT);
        take_drift(leapfrog_.drift(bodies, drift_inputs(), dt, parallel_min));
        return;
    }
    take_drift(leapfrog_.kick_and_drift(bodies, in, dt, parallel_min));
}



// Energy flows over the step just taken; states (kinetic, strain) are
// recomputed at the synchronised velocities.
void Cycle::sum_energies(double dt) {
    // the bodies' part, summed per block by the closing kick or body_energies()
    const double kinetic = leapfrog_.kinetic();
    double boundary = leapfrog_.boundary_work();
    // contact energies, summed per batch of rows by scatter_rows()
    double strain = 0;
    for (const ContactSet* s : sets_)
        for (std::size_t b = 0; b < s->batch_energy.size(); b += kBatchEnergies) {
            const double* e = &s->batch_energy[b];
            strain += e[0];
            if (dt == 0) continue;  // a re-evaluation, not a step: no dissipation
            energies.slip += e[1];
            energies.dashpot += e[2];
            energies.bond_break += e[3];
            boundary += e[4] * dt;  // work of the walls on the balls
        }
    energies.kinetic = kinetic;
    energies.strain = strain;
    energies.boundary += boundary;
}




} // namespace plab
