#include <plab_host/bodies.hpp>

#include <cmath>

namespace plab {

double Bodies::mass_of(int dim, double r, double rho) {
    return dim == 2 ? rho * M_PI * r * r : rho * 4.0 / 3.0 * M_PI * r * r * r;
}

double Bodies::inertia_of(int dim, double r, double m) {
    return dim == 2 ? 0.5 * m * r * r : 0.4 * m * r * r;
}

void Bodies::enable_applied_loads() {
    applied_force.resize(size(), Vec::Zero());
    applied_moment.resize(size(), Vec::Zero());
}

void Bodies::trim() {
    for (auto* v : {&position, &velocity, &angular_velocity, &force, &moment, &applied_force, &applied_moment})
        v->shrink_to_fit();
    for (auto* v : {&radius, &mass, &inertia, &local_damping, &viscous_damping}) v->shrink_to_fit();
    id.shrink_to_fit();
    group.shrink_to_fit();
    fixity.shrink_to_fit();
    clump.shrink_to_fit();
}

BodyId Bodies::add(const BallSpec& s) {
    const BodyId new_id = next_id++;
    id.push_back(new_id);
    Vec p = s.position, v = s.velocity, w = s.angular_velocity;
    if (dim == 2) { p.z() = 0; v.z() = 0; w.x() = 0; w.y() = 0; }
    position.push_back(p);
    velocity.push_back(v);
    angular_velocity.push_back(w);
    force.push_back(Vec::Zero());
    moment.push_back(Vec::Zero());
    if (has_applied_loads()) {
        applied_force.push_back(Vec::Zero());
        applied_moment.push_back(Vec::Zero());
    }
    radius.push_back(s.radius);
    const double m = mass_of(dim, s.radius, s.density);
    mass.push_back(m);
    inertia.push_back(inertia_of(dim, s.radius, m));
    local_damping.push_back(s.local_damping);
    viscous_damping.push_back(s.viscous_damping);
    group.push_back(s.group);
    fixity.push_back(s.fixity | implicit_fixity());
    if (!clump.empty()) clump.push_back(-1);
    return new_id;
}

namespace {
// Column c down to the rows whose new index is not -1, in order.
template <class T> void keep_rows(std::vector<T>& c, const std::vector<std::int32_t>& new_index) {
    if (c.empty()) return;  // (a column not kept: applied loads, clump)
    for (std::size_t i = 0; i < new_index.size(); ++i)
        if (new_index[i] >= 0) c[std::size_t(new_index[i])] = c[i];
    std::size_t kept = 0;
    for (std::int32_t n : new_index) kept += n >= 0;
    c.resize(kept);
}
} // namespace

std::vector<std::int32_t> Bodies::remove(const std::vector<std::uint8_t>& gone) {
    std::vector<std::int32_t> new_index(size(), -1);
    std::int32_t next = 0;
    for (std::size_t i = 0; i < size(); ++i)
        if (!gone[i]) new_index[i] = next++;
    for (auto* v : {&position, &velocity, &angular_velocity, &force, &moment, &applied_force, &applied_moment})
        keep_rows(*v, new_index);
    for (auto* v : {&radius, &mass, &inertia, &local_damping, &viscous_damping}) keep_rows(*v, new_index);
    keep_rows(id, new_index);
    keep_rows(group, new_index);
    keep_rows(fixity, new_index);
    keep_rows(clump, new_index);
    return new_index;
}

} // namespace plab
