// World set-up (groups, assignment table, fields, passes) and the cycle.
// Detection lives in detection.cpp, the force pass in force_pass.cpp.
#include "world.hpp"

#include "buffers.hpp"
#include "error.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace plab {

int ModelInstance::history_slot(const std::string& name) const {
    for (uint32_t k = 0; k < desc->history_count; ++k)
        if (name == desc->history[k].name) return int(k);
    throw std::out_of_range("contact model " + model + " has no history slot " + name);
}

double ModelInstance::property(const std::string& name) const {
    for (uint32_t k = 0; k < desc->property_count; ++k)
        if (name == desc->properties[k].key) return props[k];
    throw std::out_of_range("contact model " + model + " has no property " + name);
}

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

World::World(int d, std::shared_ptr<PluginHost> host) : dim(d), host_(std::move(host)) { bodies.dim = d; }

World::~World() {
    for (auto& inst : instances_)
        if (inst->desc->destroy && inst->state) inst->desc->destroy(inst->state);
    for (auto& p : passes_)
        if (p.desc->destroy && p.state) p.desc->destroy(p.state);
}

int World::group_index(const std::string& name) {
    const int found = find_group(name);
    if (found >= 0) return found;
    groups_.push_back(name);
    const int n = int(groups_.size());
    std::vector<int> grown(std::size_t(n) * n, -1);
    for (int a = 0; a < n - 1; ++a)
        for (int b = 0; b < n - 1; ++b) grown[a * n + b] = cmat_[a * (n - 1) + b];
    cmat_ = std::move(grown);
    return n - 1;
}

int World::find_group(const std::string& name) const {
    for (std::size_t i = 0; i < groups_.size(); ++i)
        if (groups_[i] == name) return int(i);
    return -1;
}

int World::add_instance(const std::string& model, std::vector<double> props) {
    const plab_contact_model_desc* d = host_->model(model);
    if (!d) throw InputError("", "contact model '" + model + "' is not loaded");
    auto inst = std::make_unique<ModelInstance>();
    inst->model = model;
    inst->desc = d;
    inst->props = std::move(props);
    inst->state = d->create ? d->create(inst->props.data()) : nullptr;
    if (d->create && !inst->state)
        throw PluginError("contact model '" + model + "' (" + host_->library_of_model(model) +
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
    instances_.push_back(std::move(inst));
    mark_dirty();
    return int(instances_.size()) - 1;
}

void World::assign(int a, int b, int instance) {
    const int n = int(groups_.size());
    cmat_[a * n + b] = instance;
    cmat_[b * n + a] = instance;
    mark_dirty();
}

int World::assigned(int a, int b) const { return cmat_[a * int(groups_.size()) + b]; }

int World::field_index(const std::string& name) const {
    for (std::size_t i = 0; i < field_names_.size(); ++i)
        if (field_names_[i] == name) return int(i);
    return -1;
}

int World::register_field(const std::string& name, double default_value, const char* unit) {
    const int found = field_index(name);
    if (found >= 0) {
        if (field_units_[found].empty() && unit) field_units_[found] = unit;
        return found;
    }
    field_names_.push_back(name);
    field_defaults_.push_back(default_value);
    field_units_.push_back(unit ? unit : "");
    fields_.emplace_back(bodies.size(), default_value);
    return int(fields_.size()) - 1;
}

void World::resize_fields() {
    for (std::size_t f = 0; f < fields_.size(); ++f) fields_[f].resize(bodies.size(), field_defaults_[f]);
}

void World::add_pass(const std::string& name, std::vector<double> props) {
    const plab_pass_desc* d = host_->pass(name);
    if (!d) throw InputError("", "pass '" + name + "' is not loaded");
    PassInstance p;
    p.desc = d;
    p.props = std::move(props);
    p.state = d->create ? d->create(p.props.data()) : nullptr;
    if (d->create && !p.state) throw PluginError("pass '" + name + "' failed to create its state");
    for (uint32_t f = 0; f < d->field_count; ++f)
        p.fields.push_back(register_field(d->fields[f].name, d->fields[f].default_value, d->fields[f].unit));
    // stable order: by phase, then stage, then order of addition
    auto it = passes_.begin();
    while (it != passes_.end() &&
           (it->desc->phase < d->phase || (it->desc->phase == d->phase && it->desc->stage <= d->stage)))
        ++it;
    passes_.insert(it, std::move(p));
}

bool World::has_passes(std::uint32_t phase) const {
    return std::any_of(passes_.begin(), passes_.end(), [phase](const PassInstance& p) { return p.desc->phase == phase; });
}

void World::run_passes(std::uint32_t phase) {
    if (passes_.empty()) return;
    std::vector<double*> cols;
    for (auto& p : passes_) {
        if (p.desc->phase != phase) continue;
        cols.clear();
        for (int f : p.fields) cols.push_back(fields_[f].data());
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
        v.contact_count = uint32_t(pc_end1_.size());
        v.contact_end1 = pc_end1_.data();
        v.contact_end2 = pc_end2_.data();
        v.contact_end2_is_wall = pc_wall_.data();
        // the distances hold at these positions while the range test's lists do
        v.contact_distance = in_range_marked_ && pc_distance_.size() == pc_end1_.size() ? pc_distance_.data() : nullptr;
        char diagnostic[2048];  // room for a pass's advice (sph_eos: ~800 characters)
        diagnostic[0] = '\0';
        v.diagnostic = diagnostic;
        v.diagnostic_capacity = sizeof diagnostic;
        const int rc = p.desc->run(p.state, p.props.data(), &v);
        if (rc == PLAB_PASS_UNSTABLE) stop(pass_diagnostic(p.desc->name, diagnostic));
        if (rc != 0)
            throw RunError(std::string("pass '") + p.desc->name + "' failed at step " + std::to_string(step_count));
    }
}

double World::effective_skin() const {
    if (skin >= 0) return skin;
    double sum = 0;
    for (double r : bodies.radius) sum += r;
    return bodies.size() ? 0.25 * sum / double(bodies.size()) : 0.0;
}

void World::prepare() {
    bodies.trim();  // the scene is built: no more room for bodies than bodies
    resize_fields();
    k_trans_.assign(bodies.size(), 0.0);
    k_rot_.assign(bodies.size(), 0.0);
    need_rebuild_ = true;
    {
        PhaseTimer t{phase_seconds[ph_detection]};
        rebuild();
    }
    // dt = 0 in the batch: evaluate forces at this state without advancing
    // incremental history (a re-evaluation must not add a shear increment)
    const double dt = last_dt;
    last_dt = 0;
    contact_forces_kept_ = true;  // (also after a step that failed before its forces)
    force_pass();
    cache_inverse_masses();
    body_energies(0.0);
    sum_energies(0.0);  // states (kinetic, strain) at this instant; no flow
    last_dt = dt;
    prepared_ = true;
    set_stability_baseline();
    stopped = Diagnostic{};  // a run that goes on after a stop is running again
}

// Kick–drift–kick form of the leapfrog (thesis eqs. 32–36): the same
// positions as v(t+dt/2) = v(t-dt/2) + a dt, x += v dt, but velocities are
// kept at whole steps so outputs, energies and restarts are synchronised.
// Models see the half-step velocity, as in PFC.
void World::step() {
    at_last_good_ = false;
    if (snapshot_interval > 0 && (step_count % snapshot_interval == 0 || !snapshot_.valid)) take_snapshot();
    try {
        advance();
    } catch (const RunError& e) {
        if (!snapshot_.valid) throw;
        const std::uint64_t failed_at = step_count;
        restore_snapshot();
        at_last_good_ = true;
        throw RunError(std::string(e.what()) + "; the world is back at its last good state, step " +
                       std::to_string(step_count) + " (t = " + std::to_string(time) + " s), " +
                       std::to_string(failed_at - step_count) + " steps before the failure",
                       e.quantity());
    }
}

namespace {

// The rows of a set whose history differs from the model's defaults: a
// row at its defaults is what the rebuild makes of a new pair.
void keep_rows_with_history(const ModelInstance& inst, const ContactSet& c, std::vector<std::int32_t>& end1,
                            std::vector<std::int32_t>& end2, std::vector<double>& history) {
    const int stride = inst.stride;
    auto fresh = [&](std::size_t k) {
        const double* row = c.history.data() + k * stride;
        bool at_defaults = true;
        for (int h = 0; h < stride; ++h) at_defaults &= row[h] == inst.desc->history[h].default_value;
        return at_defaults;
    };
    std::size_t kept = 0;  // counted first: room for these rows, not up to twice as many (buffers.hpp)
    for (std::size_t k = 0; k < c.size(); ++k) kept += !fresh(k);
    clear_for(end1, kept);
    clear_for(end2, kept);
    clear_for(history, kept * stride);
    for (std::size_t k = 0; k < c.size(); ++k) {
        if (fresh(k)) continue;
        const double* row = c.history.data() + k * stride;
        end1.push_back(c.end1[k]);
        end2.push_back(c.end2[k]);
        history.insert(history.end(), row, row + stride);
    }
}

} // namespace

void World::take_snapshot() {
    if (!prepared_) prepare();
    Snapshot& s = snapshot_;
    // only the motion: everything else about a body changes with
    // mark_dirty() alone, which drops the snapshot (it never spans a change),
    // and the force and moment totals follow from the state
    s.position = bodies.position;
    s.velocity = bodies.velocity;
    s.angular_velocity = bodies.angular_velocity;
    s.walls = walls;
    s.fields = fields_;
    s.energies = energies;
    s.time = time;
    s.last_dt = last_dt;
    s.step_count = step_count;
    s.bond_breaks = bond_breaks.size();
    snapshot_stable_ = stable_timestep();
    s.sets.resize(2 * instances_.size());  // copied into the last snapshot's buffers: no allocation
    std::size_t k = 0;
    for (const auto& inst : instances_)
        for (const ContactSet* c : {&inst->balls, &inst->walls}) {
            SetState& st = s.sets[k++];
            keep_rows_with_history(*inst, *c, st.end1, st.end2, st.history);
        }
    s.valid = true;
    if (on_snapshot) on_snapshot();
}

// Contact rows come back with their history; the world re-detects and
// re-evaluates forces at this state (dt = 0), as after any change, so that
// what is written at the stop (VTK, the last-good checkpoint) and the next
// step see the forces of this state.
void World::restore_snapshot() {
    const Snapshot& s = snapshot_;
    bodies.position = s.position;
    bodies.velocity = s.velocity;
    bodies.angular_velocity = s.angular_velocity;
    walls = s.walls;
    fields_ = s.fields;
    energies = s.energies;
    time = s.time;
    last_dt = s.last_dt;
    step_count = s.step_count;
    bond_breaks.resize(s.bond_breaks);
    std::size_t k = 0;
    for (auto& inst : instances_)
        for (ContactSet* c : {&inst->balls, &inst->walls}) {
            const SetState& st = s.sets[k++];
            c->end1 = st.end1; c->end2 = st.end2; c->history = st.history;  // (prepare()'s rebuild lays the columns out)
            if (c->with_wall) {  // its side memory (facet_distance) is the rows' before the restore:
                c->normal.clear();  // the restored rows start without it (install_pairs)
                c->interior.clear();
            }
        }
    const Diagnostic why = stopped;  // prepare() clears it: a run that goes on is running again
    prepare();
    stopped = why;
}

void World::advance() {
    if (!prepared_) prepare();
    double dt;
    {
        PhaseTimer t{phase_seconds[ph_timestep]};
        dt = fixed_dt > 0 ? fixed_dt : safety_factor * stable_timestep().critical;
        if (!std::isfinite(dt) || dt <= 0)
            throw RunError("no stable timestep: no contact model reports a stiffness or step limit; set a fixed "
                           "timestep (timestep.fixed)");
        last_dt = dt;
    }
    {
        PhaseTimer t{phase_seconds[ph_motion]};
        kick_and_drift(dt);
        wall_motion_since_build_ += walls.move(dt, dim);
    }
    {
        PhaseTimer t{phase_seconds[ph_detection]};
        if (need_rebuild_ || displacement_exceeds_skin()) rebuild();
    }
    time += dt;
    ++step_count;
    const bool post_force = has_passes(PLAB_PHASE_POST_FORCE);
    contact_forces_kept_ = !contact_forces_wanted || contact_forces_wanted();
    force_pass(post_force ? 0.0 : 0.5 * dt);  // the closing half kick inside reduce(), unless a pass comes between
    {
        PhaseTimer t{phase_seconds[ph_motion]};
        if (post_force) kick(0.5 * dt, true);
        sum_energies(dt);
    }
    {
        PhaseTimer t{phase_seconds[ph_integrate]};
        run_passes(PLAB_PHASE_INTEGRATE);
    }
    {
        PhaseTimer t{phase_seconds[ph_stability]};
        detect_instability();
    }
}

void World::force_pass(double closing_kick) {
    {
        PhaseTimer t{phase_seconds[ph_pre_force]};
        run_passes(PLAB_PHASE_PRE_FORCE);
    }
    {
        PhaseTimer t{phase_seconds[ph_force]};
        find_fields_at_default();
        clear_batch_limits();  // force_sweep() keeps those of centre-force sets, the columns the others'
        // a pass added since the last rebuild may need a rates stage over
        // full columns that a packed set lacks (packs_balls)
        bool repacked = false;
        for (auto& inst : instances_)
            if (inst->balls.packed != packs_balls(*inst)) {
                lay_out_columns(*inst, inst->balls);
                fill_pair_constants(inst->balls);
                repacked = true;
            }
        if (repacked) build_entries();  // (which rows it lists depends on packing)
        // without a rates stage, each set is done in one sweep over batches
        // (geometry, model, scatter to slots); a rates stage needs all the
        // geometry before any force. A rates stage whose sums nothing reads
        // is skipped (rates_stage_needed).
        find_still_instances();
        bool rates_models = false;
        swept_ = true;
        for (auto& inst : instances_) {
            rates_models |= inst->desc->rates_stage != 0;
            swept_ &= !(inst->desc->rates_stage && rates_stage_needed(*inst));
        }
        for (std::uint32_t si = 0; si < sets_.size(); ++si) {
            ModelInstance& inst = *instances_[si / 2];
            ContactSet& s = *sets_[si];
            if (!s.with_wall && swept_) continue;  // geometry in the sweep
            geometry(inst, s);
            if (s.with_wall) resolve_wall_features(s);
        }
        if (swept_ && rates_models) {
            // the passes that turn rates into states (e.g. summation density,
            // the EOS) still run before the forces, on this cycle's contacts
            mark_ball_rows_in_range();  // (it lists the passes' contacts too)
            run_passes(PLAB_PHASE_RATES_DONE);
            for (std::uint32_t si = 0; si < sets_.size(); ++si) force_sweep(si, !sets_[si]->with_wall);
            in_range_marked_ = false;
        } else if (swept_) {
            for (std::uint32_t si = 0; si < sets_.size(); ++si) force_sweep(si, !sets_[si]->with_wall);
            build_pass_contacts();  // the sweeps set the active flags
        } else {
            build_pass_contacts();
            rates_stage();
            for (std::uint32_t m = 0; m < instances_.size(); ++m) {
                ModelInstance& inst = *instances_[m];
                if (still_centre_set(2 * m)) hold_still(inst.balls);  // (as force_sweep)
                else compute(inst, inst.balls, PLAB_STAGE_FORCES);
                compute(inst, inst.walls, PLAB_STAGE_FORCES);
            }
        }
    }
    {
        PhaseTimer t{phase_seconds[ph_reduction]};
        if (reduce(closing_kick)) check_finite();
    }
    {
        PhaseTimer t{phase_seconds[ph_post_force]};
        run_passes(PLAB_PHASE_POST_FORCE);
    }
}

namespace {

// The body columns a kick reads, their addresses in locals: Eigen's vector
// stores may alias anything, so GCC would otherwise reload every column's
// address per body.
struct KickColumns {
    Vec *velocity, *angular_velocity;
    const Vec *force, *moment, *applied_force, *applied_moment;
    const double *mass, *inertia;
    explicit KickColumns(Bodies& B)
        : velocity(B.velocity.data()), angular_velocity(B.angular_velocity.data()), force(B.force.data()),
          moment(B.moment.data()), applied_force(B.applied_force.data()), applied_moment(B.applied_moment.data()),
          mass(B.mass.data()), inertia(B.inertia.data()), loads(B.has_applied_loads()) {}
    bool loads;  // applied loads kept (Bodies: none until one is applied)
};

// What body i adds to the energy sums at its synchronised velocities (PFC's
// bookkeeping): kinetic energy, and the work over the step dt of its applied
// loads and, along explicitly fixed DOFs, of the reaction that keeps the
// velocity.
// (Dim 2: z of v and x, y of w are zero, so their squares are left out;
// the sums are the same bits.)
template <int Dim = 3>
inline void add_body_energy(const KickColumns& B, std::size_t i, const Vec& v, const Vec& w, double dt,
                            std::uint8_t explicit_fix, double& kinetic, double& boundary) {
    if (Dim == 2)
        kinetic += 0.5 * B.mass[i] * (v.x() * v.x() + v.y() * v.y()) + 0.5 * B.inertia[i] * (w.z() * w.z());
    else
        kinetic += 0.5 * B.mass[i] * v.squaredNorm() + 0.5 * B.inertia[i] * w.squaredNorm();
    if (B.loads) boundary += B.applied_force[i].dot(v) * dt + B.applied_moment[i].dot(w) * dt;
    if (explicit_fix)
        for (int c = 0; c < 3; ++c) {
            if (explicit_fix & (dof_x << c)) boundary -= B.force[i][c] * v[c] * dt;
            if (explicit_fix & (dof_rx << c)) boundary -= B.moment[i][c] * w[c] * dt;
        }
}

// Half a kick (thesis eq. 33: v += h F/m, w += h M/I) of bodies [i0, i1)
// with every DOF of their dimension free (2D: x, y and the spin about z),
// without a branch per component; with Energies, their energy sums too.
// SpinFixed: every body's rotations are fixed and its translations free
// (SPH particles), so only v is kicked; the energy sums are kick_block()'s.
template <int Dim, bool Energies, bool SpinFixed = false>
void kick_free_block(Bodies& bodies, const double* inv_m, const double* inv_i, double h, std::size_t i0, std::size_t i1,
                     double& kinetic, double& boundary) {
    const KickColumns B(bodies);
    const std::uint8_t spin_fixed = bodies.rotation_dofs();  // (explicitly: 2D's rx, ry are implicit)
    for (std::size_t i = i0; i < i1; ++i) {
        // on copies, stored whole: the energy sums read them back from
        // registers, not through a store of parts and a wider load
        Vec v = B.velocity[i], w = B.angular_velocity[i];
        const Vec& f = B.force[i];
        const Vec& m = B.moment[i];
        if (Dim == 3) {
            for (int c = 0; c < 3; ++c) {
                v[c] += h * f[c] * inv_m[i];
                if (!SpinFixed) w[c] += h * m[c] * inv_i[i];
            }
        } else {
            v[0] += h * f[0] * inv_m[i];
            v[1] += h * f[1] * inv_m[i];
            if (!SpinFixed) w[2] += h * m[2] * inv_i[i];
        }
        B.velocity[i] = v;
        if (!SpinFixed) B.angular_velocity[i] = w;
        if (Energies) add_body_energy<Dim>(B, i, v, w, 2 * h, SpinFixed ? spin_fixed : 0, kinetic, boundary);
    }
}

// The same for bodies that may have fixed DOFs: a fixed component keeps its velocity.
void kick_block(Bodies& bodies, const double* inv_m, const double* inv_i, double h, std::size_t i0, std::size_t i1,
                bool energies, double& kinetic, double& boundary) {
    const std::uint8_t implicit = bodies.implicit_fixity();
    const std::uint8_t* fixity = bodies.fixity.data();
    const KickColumns B(bodies);
    for (std::size_t i = i0; i < i1; ++i) {
        const std::uint8_t fix = fixity[i];
        for (int c = 0; c < 3; ++c) {
            if (!(fix & (dof_x << c))) B.velocity[i][c] += h * B.force[i][c] * inv_m[i];
            if (!(fix & (dof_rx << c))) B.angular_velocity[i][c] += h * B.moment[i][c] * inv_i[i];
        }
        if (energies) add_body_energy(B, i, B.velocity[i], B.angular_velocity[i], 2 * h, fix & ~implicit, kinetic, boundary);
    }
}

} // namespace

void World::cache_inverse_masses() {
    const std::size_t n = bodies.size();
    inv_mass_.resize(n);
    inv_inertia_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        inv_mass_[i] = 1.0 / bodies.mass[i];
        inv_inertia_[i] = 1.0 / bodies.inertia[i];
    }
}

// Half a kick of block b; the closing kick of a step (`closing`) also
// takes the block's energy sums while the velocities are at hand, for
// sum_energies().
void World::kick_block_of_bodies(std::size_t b, double h, bool closing) {
    const std::size_t i0 = b * kBodyBlock, i1 = std::min(bodies.size(), i0 + kBodyBlock);
    const double* inv_m = inv_mass_.data();
    const double* inv_i = inv_inertia_.data();
    std::uint8_t fixed = 0, every = 0xff;  // explicitly fixed DOFs: of any body in the block, of every one
    for (std::size_t i = i0; i < i1; ++i) {
        fixed |= bodies.fixity[i];
        every &= bodies.fixity[i];
    }
    fixed &= ~bodies.implicit_fixity();
    every &= ~bodies.implicit_fixity();
    const std::uint8_t spin = bodies.rotation_dofs();
    double kinetic = 0, boundary = 0;
    if (fixed == spin && every == spin) {  // rotations fixed, translations free, in every body
        if (dim == 3)
            closing ? kick_free_block<3, true, true>(bodies, inv_m, inv_i, h, i0, i1, kinetic, boundary)
                    : kick_free_block<3, false, true>(bodies, inv_m, inv_i, h, i0, i1, kinetic, boundary);
        else
            closing ? kick_free_block<2, true, true>(bodies, inv_m, inv_i, h, i0, i1, kinetic, boundary)
                    : kick_free_block<2, false, true>(bodies, inv_m, inv_i, h, i0, i1, kinetic, boundary);
    } else if (fixed)
        kick_block(bodies, inv_m, inv_i, h, i0, i1, closing, kinetic, boundary);
    else if (dim == 3)
        closing ? kick_free_block<3, true>(bodies, inv_m, inv_i, h, i0, i1, kinetic, boundary)
                : kick_free_block<3, false>(bodies, inv_m, inv_i, h, i0, i1, kinetic, boundary);
    else
        closing ? kick_free_block<2, true>(bodies, inv_m, inv_i, h, i0, i1, kinetic, boundary)
                : kick_free_block<2, false>(bodies, inv_m, inv_i, h, i0, i1, kinetic, boundary);
    if (closing) {
        block_kinetic_[b] = kinetic;
        block_boundary_[b] = boundary;
    }
}

// The first half of a step's law of motion: half a kick, the PRE_DRIFT
// passes (e.g. XSPH: a drift velocity correction from v(t + dt/2)), the
// drift. Without such a pass or correction the drift of a block follows its
// kick in the same loop, while v is in cache.
void World::kick_and_drift(double dt) {
    const std::size_t n = bodies.size(), n_blocks = body_blocks();
    prepare_body_blocks();
    const DriftCorrection corr = drift_correction();
    if (has_passes(PLAB_PHASE_PRE_DRIFT) || corr.on) {
        kick(0.5 * dt);
        run_passes(PLAB_PHASE_PRE_DRIFT);
        drift(dt);
        return;
    }
#pragma omp parallel for schedule(static) if (n >= parallel_min)
    for (std::size_t b = 0; b < n_blocks; ++b) {
        kick_block_of_bodies(b, 0.5 * dt, false);
        drift_block(b, dt, corr);
    }
    finish_drift();
}

// Half a kick for every body (see kick_block_of_bodies()).
void World::kick(double h, bool closing) {
    const std::size_t n = bodies.size(), n_blocks = body_blocks();
    prepare_body_blocks();
#pragma omp parallel for schedule(static) if (n >= parallel_min)
    for (std::size_t b = 0; b < n_blocks; ++b) kick_block_of_bodies(b, h, closing);
}

void World::prepare_body_blocks() {
    const std::size_t n = bodies.size(), n_blocks = body_blocks();
    if (inv_mass_.size() != n) cache_inverse_masses();  // e.g. a world just loaded from a checkpoint
    block_kinetic_.resize(n_blocks);
    block_boundary_.resize(n_blocks);
    block_body_work_.resize(n_blocks);
    block_max_drift2_.resize(n_blocks);
    block_out_.resize(n_blocks);
}

// The closing kick's energy sums without a kick (prepare(): forces at a state).
void World::body_energies(double dt) {
    const std::size_t n = bodies.size(), n_blocks = body_blocks();
    block_kinetic_.assign(n_blocks, 0.0);
    block_boundary_.assign(n_blocks, 0.0);
    const std::uint8_t implicit = bodies.implicit_fixity();
    const KickColumns cols(bodies);
    for (std::size_t b = 0; b < n_blocks; ++b)
        for (std::size_t i = b * kBodyBlock; i < std::min(n, (b + 1) * kBodyBlock); ++i)
            add_body_energy(cols, i, cols.velocity[i], cols.angular_velocity[i], dt, bodies.fixity[i] & ~implicit,
                            block_kinetic_[b], block_boundary_[b]);
}

World::DriftCorrection World::drift_correction() {
    DriftCorrection c;
    const int cx = field_index(PLAB_DRIFT_CORRECTION_X), cy = field_index(PLAB_DRIFT_CORRECTION_Y),
              cz = field_index(PLAB_DRIFT_CORRECTION_Z);
    c.on = cx >= 0 && cy >= 0 && cz >= 0;
    if (c.on) c.field = {fields_[cx].data(), fields_[cy].data(), fields_[cz].data()};
    return c;
}

// x += (v + correction) dt; the correction (abi.h, PLAB_PHASE_PRE_DRIFT) only
// where a pass registered its fields, and only along free translational DOFs.
void World::drift(double dt) {
    const std::size_t n = bodies.size(), n_blocks = body_blocks();
    prepare_body_blocks();
    const DriftCorrection corr = drift_correction();
#pragma omp parallel for schedule(static) if (n >= parallel_min)
    for (std::size_t b = 0; b < n_blocks; ++b) drift_block(b, dt, corr);
    finish_drift();
}

namespace {
// What drift_block() sums over a block while x is at hand.
struct DriftSums {
    double body_work = 0, max2 = 0;
    bool out = false;
};

// The body columns and constants a drift reads; column addresses in
// locals: Eigen's vector stores may alias anything.
struct DriftColumns {
    Vec* position;
    const Vec *velocity, *built;
    const double* mass;
    const std::uint8_t* fixity;
    Vec lo, hi, g;  // copies: no reload after each store
};

// x += (v + correction) dt for bodies [i0, i1), any dimension; the
// correction (the drift correction fields, null: none) only along free
// translational DOFs.
DriftSums drift_rows(const DriftColumns& c, const double* const* correction, double dt, std::size_t i0,
                     std::size_t i1) {
    DriftSums sums;
    for (std::size_t i = i0; i < i1; ++i) {
        Vec dx = c.velocity[i] * dt;
        if (correction) {
            const std::uint8_t fix = c.fixity[i];
            for (int k = 0; k < 3; ++k)
                if (!(fix & (dof_x << k))) dx[k] += correction[k][i] * dt;
        }
        Vec& x = c.position[i];
        x += dx;
        sums.body_work += c.mass[i] * c.g.dot(dx);  // exact for a constant force
        sums.max2 = std::max(sums.max2, (x - c.built[i]).squaredNorm());
        // a NaN fails every comparison (& rather than &&: no branch per comparison)
        sums.out |= !((x.x() >= c.lo.x()) & (x.x() <= c.hi.x()) & (x.y() >= c.lo.y()) & (x.y() <= c.hi.y()) &
                      (x.z() >= c.lo.z()) & (x.z() <= c.hi.z()) & (std::fabs(x.x() + x.y() + x.z()) < kInf));
    }
    return sums;
}

// drift_rows() for a 2D world without a drift correction: z, vz and the
// domain's z bounds (infinite) never change, so only x and y are worked out
// (the general loop spends a third of its arithmetic on those zeros). The
// positions come out the same bits.
DriftSums drift_plane_rows(const DriftColumns& c, double dt, std::size_t i0, std::size_t i1) {
    double body_work = 0, max2 = 0;
    bool out = false;
    const double gx = c.g.x(), gy = c.g.y(), lox = c.lo.x(), loy = c.lo.y(), hix = c.hi.x(), hiy = c.hi.y();
    for (std::size_t i = i0; i < i1; ++i) {
        const double dx = c.velocity[i].x() * dt, dy = c.velocity[i].y() * dt;
        const double x = c.position[i].x() + dx, y = c.position[i].y() + dy;
        c.position[i].x() = x;
        c.position[i].y() = y;
        body_work += c.mass[i] * (gx * dx + gy * dy);
        const double ex = x - c.built[i].x(), ey = y - c.built[i].y();
        max2 = std::max(max2, ex * ex + ey * ey);
        out |= !((x >= lox) & (x <= hix) & (y >= loy) & (y <= hiy) & (std::fabs(x + y) < kInf));
    }
    return {body_work, max2, out};
}
} // namespace

// The drift of block b. While x is at hand: the work of gravity, the
// detector's domain check and the largest displacement since the last
// build (displacement_exceeds_skin()).
void World::drift_block(std::size_t b, double dt, const DriftCorrection& corr) {
    const std::size_t i0 = b * kBodyBlock, i1 = std::min(bodies.size(), i0 + kBodyBlock);
    // (no reference positions yet: measured against x itself; finish_drift() knows)
    const bool tracked = position_at_build_.size() == bodies.size();
    const DriftColumns c{bodies.position.data(), bodies.velocity.data(),
                         tracked ? position_at_build_.data() : bodies.position.data(), bodies.mass.data(),
                         bodies.fixity.data(), baseline_.lo, baseline_.hi, gravity};
    const DriftSums sums = dim == 2 && !corr.on ? drift_plane_rows(c, dt, i0, i1)
                                                : drift_rows(c, corr.on ? corr.field.data() : nullptr, dt, i0, i1);
    block_body_work_[b] = sums.body_work;
    block_max_drift2_[b] = sums.max2;
    block_out_[b] = sums.out;
}

// The blocks' drift results, in block order.
void World::finish_drift() {
    double body_work = 0, max2 = 0;
    bool out = false;
    for (std::size_t b = 0; b < body_blocks(); ++b) {
        body_work += block_body_work_[b];
        max2 = std::max(max2, block_max_drift2_[b]);
        out |= block_out_[b] != 0;
    }
    energies.body += body_work;
    left_domain_ = out;
    max_drift2_ = position_at_build_.size() == bodies.size() ? max2 : -1;  // -1: no reference, rebuild
}

// For a plug-in author: the model and contact whose output went non-finite.
std::string World::non_finite_contact(std::size_t body) const {
    for (const auto& inst : instances_)
        for (const ContactSet* set : {&inst->balls, &inst->walls})
            for (std::size_t k = 0; k < set->size(); ++k) {
                if (!set->active[k] || (std::size_t(set->end1[k]) != body && (set->with_wall || std::size_t(set->end2[k]) != body)))
                    continue;
                const Vec f(&set->force[3 * k]), m1 = set->moment1_at(k), m2 = set->moment2_at(k);
                if (f.allFinite() && m1.allFinite() && m2.allFinite()) continue;
                std::ostringstream s;
                s << "contact model '" << inst->model << "' returned a non-finite force or moment (a contact model returned NaN) for the contact of ball id "
                  << bodies.id[set->end1[k]] << (set->with_wall ? " with a wall" : " and ball id " + std::to_string(bodies.id[set->end2[k]]))
                  << " at gap " << contact_gap(*set, k) << " m: check its law for division by zero, sqrt or log of a negative "
                  << "number, or use of history before it is set";
                return s.str();
            }
    return "";
}

void World::check_finite() {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (bodies.position[i].allFinite() && bodies.force[i].allFinite() && bodies.moment[i].allFinite() &&
            bodies.velocity[i].allFinite())
            continue;
        std::ostringstream s;
        s << "position " << bodies.position[i].transpose() << ", force " << bodies.force[i].transpose();
        Diagnostic d;
        d.quantity = "non-finite state";
        d.subject = "ball id " + std::to_string(bodies.id[i]) + " (group " + groups_[bodies.group[i]] + ")";
        d.detail = s.str();
        // for a plug-in author: the model and contact whose output went non-finite
        const std::string culprit = non_finite_contact(i);
        d.cause = culprit.empty() ? "a contact model returned NaN or Inf (or a pass did), or the state overflowed" : culprit;
        stop(d);
    }
}

// Energy flows over the step just taken; states (kinetic, strain) are
// recomputed at the synchronised velocities.
void World::sum_energies(double dt) {
    double kinetic = 0, boundary = 0;  // the bodies' part, per block (kick(), body_energies())
    for (std::size_t b = 0; b < block_kinetic_.size(); ++b) {
        kinetic += block_kinetic_[b];
        boundary += block_boundary_[b];
    }
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

double World::unbalanced_force_ratio() const {
    double unbalanced = 0;
    std::size_t free_bodies = 0;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const std::uint8_t fix = bodies.fixity[i];
        Vec f = bodies.force[i];
        for (int c = 0; c < 3; ++c)
            if (fix & (dof_x << c)) f[c] = 0;
        if ((fix & (dof_x | dof_y | dof_z)) == (dof_x | dof_y | dof_z)) continue;
        unbalanced += f.norm();
        ++free_bodies;
    }
    double contact = 0;
    std::size_t n = 0;
    for (auto& inst : instances_)
        for (const ContactSet* s : {&inst->balls, &inst->walls})
            for (std::size_t k = 0; k < s->size(); ++k)
                if (s->active[k]) {
                    contact += Vec(&s->force[3 * k]).norm();
                    ++n;
                }
    if (free_bodies == 0) return 0;
    if (n == 0 || contact == 0) return kInf;
    return (unbalanced / double(free_bodies)) / (contact / double(n));
}

std::size_t World::active_contacts() const {
    std::size_t n = 0;
    for (auto& inst : instances_)
        for (const ContactSet* s : {&inst->balls, &inst->walls})
            for (std::uint8_t a : s->active) n += a;
    return n;
}

std::uint64_t World::state_hash() const {
    std::uint64_t h = 1469598103934665603ull;
    auto mix = [&h](const void* p, std::size_t bytes) {
        const auto* c = static_cast<const unsigned char*>(p);
        for (std::size_t i = 0; i < bytes; ++i) h = (h ^ c[i]) * 1099511628211ull;
    };
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        mix(bodies.position[i].data(), 3 * sizeof(double));
        mix(bodies.velocity[i].data(), 3 * sizeof(double));
        mix(bodies.angular_velocity[i].data(), 3 * sizeof(double));
    }
    return h;
}

} // namespace plab
