// The host API (plab_host/world.hpp, contacts.hpp): the world's functions
// and the contact views, each handed to the cycle (world/cycle.hpp).
#include "world/cycle.hpp"

#include <plab_host/errors.hpp>
#include <plab_host/world.hpp>

#include "contacts/contact_keys.hpp"
#include "forces/geometry.hpp"

#include <cmath>
#include <stdexcept>

namespace plab {

World::World(int d, std::shared_ptr<PluginHost> host)
    : dim(d), cycle(std::make_unique<Cycle>(*this, std::move(host))) {
    bodies.dim = d;
}

World::~World() = default;

int World::group_index(const std::string& name) { return cycle->assignment.group_index(name); }
int World::find_group(const std::string& name) const { return cycle->assignment.find_group(name); }
const std::vector<std::string>& World::group_names() const { return cycle->assignment.group_names(); }
int World::assigned(int group_a, int group_b) const { return cycle->assignment.assigned(group_a, group_b); }
std::size_t World::model_count() const { return cycle->instances.size(); }
ModelView World::model(std::size_t instance) const { return {*cycle, *cycle->instances.at(instance)}; }
void World::set_max_overlap(std::size_t instance, double fraction_of_radius) {
    cycle->instances.at(instance)->max_overlap = fraction_of_radius;
}
int World::register_field(const std::string& name, double default_value, const char* unit) {
    return fields.add(name, default_value, unit, bodies.size());
}
std::size_t add_clump(World& w, const ClumpSpec& spec) {
    const std::size_t c = w.clumps.add(spec, w.bodies);
    w.mark_dirty();
    return c;
}
std::size_t remove_bodies(World& w, const std::vector<std::uint8_t>& gone) {
    if (gone.size() != w.bodies.size()) throw std::invalid_argument("remove_bodies: one flag per body");
    std::size_t n = 0;
    for (std::size_t i = 0; i < gone.size(); ++i) {
        if (!gone[i]) continue;
        if (!w.bodies.clump.empty() && w.bodies.clump[i] >= 0)
            throw std::invalid_argument("remove_bodies: ball " + std::to_string(w.bodies.id[i]) +
                                        " is a pebble of a clump; a clump leaves whole or not at all");
        ++n;
    }
    if (n == 0) return 0;
    const std::vector<std::int32_t> new_index = w.bodies.remove(gone);
    w.fields.keep_rows(new_index);
    for (auto& inst : w.cycle->instances)
        for (ContactSet* s : {&inst->balls, &inst->walls}) renumber_ends(*s, new_index, std::size_t(inst->stride));
    for (auto& p : w.clumps.pebble_body) p = new_index[std::size_t(p)];
    w.mark_dirty();
    return n;
}
void World::set_skin(double skin) { cycle->neighbours.skin = skin; }
void World::step() { cycle->step(); }
void World::prepare() { cycle->prepare(); }
void World::mark_dirty() { cycle->mark_dirty(); }

int World::add_instance(const std::string& model, std::vector<double> props) {
    const plab_contact_model_desc* d = cycle->host->model(model);
    if (!d) throw InputError("", "contact model '" + model + "' is not loaded");
    auto inst = std::make_unique<ModelInstance>();
    inst->model = model;
    inst->desc = d;
    inst->props = std::move(props);
    inst->state = d->create ? d->create(inst->props.data()) : nullptr;
    if (d->create && !inst->state)
        throw PluginError("contact model '" + model + "' (" + cycle->host->library_of_model(model) +
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
    if (d->fields_accumulated_count > ReadFields::kMax)
        throw PluginError("contact model '" + model + "' accumulates " + std::to_string(d->fields_accumulated_count) +
                          " body fields; plab takes at most " + std::to_string(ReadFields::kMax));
    for (uint32_t f = 0; f < d->fields_read_count; ++f)
        inst->fields_read.push_back(register_field(d->fields_read[f].name, d->fields_read[f].default_value, d->fields_read[f].unit));
    for (uint32_t f = 0; f < d->fields_accumulated_count; ++f)
        inst->fields_accumulated.push_back(
            register_field(d->fields_accumulated[f].name, d->fields_accumulated[f].default_value,
                           d->fields_accumulated[f].unit));
    inst->walls.with_wall = true;
    for (ContactSet* s : {&inst->balls, &inst->walls}) {
        s->model = d;
    }
    cycle->instances.push_back(std::move(inst));
    mark_dirty();
    return int(cycle->instances.size()) - 1;
}

void World::assign(int a, int b, int instance) {
    cycle->assignment.assign(a, b, instance);
    mark_dirty();
}

void World::add_pass(const std::string& name, std::vector<double> props) {
    const plab_pass_desc* d = cycle->host->pass(name);
    if (!d) throw InputError("", "pass '" + name + "' is not loaded");
    PassInstance p;
    p.desc = d;
    p.props = std::move(props);
    p.state = d->create ? d->create(p.props.data()) : nullptr;
    if (d->create && !p.state) throw PluginError("pass '" + name + "' failed to create its state");
    for (uint32_t f = 0; f < d->field_count; ++f)
        p.fields.push_back(register_field(d->fields[f].name, d->fields[f].default_value, d->fields[f].unit));
    cycle->passes.add(std::move(p));
}

StabilityLimits& World::stability_limits() { return cycle->monitor.detector.limits; }

StableStep stable_timestep(const World& w) { return w.cycle->monitor.stable_timestep(); }
StableStep nominal_timestep(const World& w) { return w.cycle->monitor.nominal_timestep(); }
std::uint64_t rebuilds(const World& w) { return w.cycle->neighbours.rebuilds; }
bool field_computed(const World& w, int field) { return w.cycle->forces.field_computed(field); }
bool contact_forces_current(const World& w) { return w.cycle->forces.contact_forces_kept(); }
bool at_last_good(const World& w) { return w.cycle->at_last_good(); }

// ---- contact views ----

std::size_t ContactTable::size() const { return set_->size(); }
bool ContactTable::with_wall() const { return set_->with_wall; }
bool ContactTable::active(std::size_t k) const { return set_->active[k] != 0; }
std::size_t ContactTable::end1(std::size_t k) const { return std::size_t(set_->end1[k]); }
std::size_t ContactTable::end2(std::size_t k) const { return std::size_t(set_->end2[k]); }
ContactKey ContactTable::key(std::size_t k) const { return row_key(cycle_->world.bodies, cycle_->world.walls, *set_, k); }
const double* ContactTable::history(std::size_t k) const {
    return set_->history.data() + k * std::size_t(instance_->stride);
}
bool ContactTable::bonded(std::size_t k) const {
    const int slot = instance_->desc->persist_slot;
    return slot >= 0 && history(k)[slot] > 0;
}
Vec ContactTable::force(std::size_t k) const { return Vec(&set_->force[3 * k]); }
Vec ContactTable::normal(std::size_t k) const { return row_normal(cycle_->world.bodies, *set_, k); }
Vec ContactTable::point(std::size_t k) const { return row_point(cycle_->world.bodies, *set_, k); }
double ContactTable::gap(std::size_t k) const { return row_gap(cycle_->world.bodies, *set_, k); }
double ContactTable::end_radius(std::size_t k, bool end2) const { return row_end_radius(cycle_->world.bodies, *set_, k, end2); }
double ContactTable::stiffness(std::size_t k) const { return k_t_at(*set_, k); }
double ContactTable::dt_limit(std::size_t k) const { return dt_limit_at(*set_, k); }

const std::string& ModelView::model() const { return instance_->model; }
const plab_contact_model_desc& ModelView::desc() const { return *instance_->desc; }
const std::vector<double>& ModelView::properties() const { return instance_->props; }
double ModelView::range() const { return instance_->range; }
int ModelView::history_slot(const std::string& name) const { return instance_->history_slot(name); }
double ModelView::property(const std::string& name) const { return instance_->property(name); }
ContactTable ModelView::balls() const { return {*cycle_, *instance_, instance_->balls}; }
ContactTable ModelView::walls() const { return {*cycle_, *instance_, instance_->walls}; }

} // namespace plab
