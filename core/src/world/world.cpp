// The host API (plab_host/world.hpp, contacts.hpp): the world's functions
// and the contact views, each handed to the cycle (world/cycle.hpp).
#include "world/cycle.hpp"

#include <plab_host/world.hpp>

#include "contacts/contact_keys.hpp"
#include "forces/geometry.hpp"

namespace plab {

World::World(int d, std::shared_ptr<PluginHost> host)
    : dim(d), cycle(std::make_unique<Cycle>(*this, std::move(host))) {
    bodies.dim = d;
}

World::~World() = default;

int World::group_index(const std::string& name) { return cycle->assignment.group_index(name); }
int World::find_group(const std::string& name) const { return cycle->assignment.find_group(name); }
const std::vector<std::string>& World::group_names() const { return cycle->assignment.group_names(); }
int World::add_instance(const std::string& model, std::vector<double> props) {
    return cycle->add_instance(model, std::move(props));
}
void World::assign(int group_a, int group_b, int instance) { cycle->assign(group_a, group_b, instance); }
int World::assigned(int group_a, int group_b) const { return cycle->assignment.assigned(group_a, group_b); }
std::size_t World::model_count() const { return cycle->instances.size(); }
ModelView World::model(std::size_t instance) const { return {*cycle, *cycle->instances.at(instance)}; }
void World::set_max_overlap(std::size_t instance, double fraction_of_radius) {
    cycle->instances.at(instance)->max_overlap = fraction_of_radius;
}
int World::register_field(const std::string& name, double default_value, const char* unit) {
    return cycle->register_field(name, default_value, unit);
}
void World::add_pass(const std::string& name, std::vector<double> props) { cycle->add_pass(name, std::move(props)); }
void World::set_skin(double skin) { cycle->set_skin(skin); }
void World::step() { cycle->step(); }
void World::prepare() { cycle->prepare(); }
void World::mark_dirty() { cycle->mark_dirty(); }
std::size_t World::bond(int group_a, int group_b, double gap_tolerance) {
    return cycle->bond(group_a, group_b, gap_tolerance);
}
StabilityLimits& World::stability_limits() { return cycle->stability_limits(); }

StableStep stable_timestep(const World& w) { return w.cycle->stable_timestep(); }
StableStep nominal_timestep(const World& w) { return w.cycle->nominal_timestep(); }
std::uint64_t state_hash(const World& w) { return w.cycle->state_hash(); }
std::vector<Eigen::Matrix3d> ball_stress(const World& w) { return w.cycle->ball_stress(); }
double unbalanced_force_ratio(const World& w) { return w.cycle->unbalanced_force_ratio(); }
std::size_t active_contacts(const World& w) { return w.cycle->active_contacts(); }
std::size_t intact_bonds(const World& w) { return w.cycle->intact_bonds(); }
std::uint64_t rebuilds(const World& w) { return w.cycle->rebuilds(); }
bool field_computed(const World& w, int field) { return w.cycle->field_computed(field); }
bool contact_forces_current(const World& w) { return w.cycle->contact_forces_current(); }
bool at_last_good(const World& w) { return w.cycle->at_last_good(); }

// ---- contact views ----

std::size_t ContactTable::size() const { return set_->size(); }
bool ContactTable::with_wall() const { return set_->with_wall; }
bool ContactTable::active(std::size_t k) const { return set_->active[k] != 0; }
std::size_t ContactTable::end1(std::size_t k) const { return std::size_t(set_->end1[k]); }
std::size_t ContactTable::end2(std::size_t k) const { return std::size_t(set_->end2[k]); }
ContactKey ContactTable::key(std::size_t k) const { return row_key(cycle_->bodies, cycle_->walls, *set_, k); }
const double* ContactTable::history(std::size_t k) const {
    return set_->history.data() + k * std::size_t(instance_->stride);
}
bool ContactTable::bonded(std::size_t k) const {
    const int slot = instance_->desc->persist_slot;
    return slot >= 0 && history(k)[slot] > 0;
}
Vec ContactTable::force(std::size_t k) const { return Vec(&set_->force[3 * k]); }
Vec ContactTable::normal(std::size_t k) const { return row_normal(cycle_->bodies, *set_, k); }
Vec ContactTable::point(std::size_t k) const { return row_point(cycle_->bodies, *set_, k); }
double ContactTable::gap(std::size_t k) const { return row_gap(cycle_->bodies, *set_, k); }
double ContactTable::end_radius(std::size_t k, bool end2) const { return row_end_radius(cycle_->bodies, *set_, k, end2); }
double ContactTable::stiffness(std::size_t k) const { return set_->k_t_at(k); }
double ContactTable::dt_limit(std::size_t k) const { return set_->dt_limit_at(k); }

const std::string& ModelView::model() const { return instance_->model; }
const plab_contact_model_desc& ModelView::desc() const { return *instance_->desc; }
const std::vector<double>& ModelView::properties() const { return instance_->props; }
double ModelView::range() const { return instance_->range; }
int ModelView::history_slot(const std::string& name) const { return instance_->history_slot(name); }
double ModelView::property(const std::string& name) const { return instance_->property(name); }
ContactTable ModelView::balls() const { return {*cycle_, *instance_, instance_->balls}; }
ContactTable ModelView::walls() const { return {*cycle_, *instance_, instance_->walls}; }

} // namespace plab
