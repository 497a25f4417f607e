#include "passes/passes.hpp"

#include <plab_host/errors.hpp>

#include <algorithm>

namespace plab {

Passes::~Passes() {
    for (PassInstance& p : list_)
        if (p.desc->destroy && p.state) p.desc->destroy(p.state);
}

void Passes::add(PassInstance p) {
    const plab_pass_desc* d = p.desc;
    auto it = list_.begin();
    while (it != list_.end() && (it->desc->phase < d->phase || (it->desc->phase == d->phase && it->desc->stage <= d->stage)))
        ++it;
    list_.insert(it, std::move(p));
}

bool Passes::any_at(std::uint32_t phase) const {
    return std::any_of(list_.begin(), list_.end(), [phase](const PassInstance& p) { return p.desc->phase == phase; });
}

// The bodies, the pass's fields and the active contacts as the ABI shows them.
plab_pass_view Passes::view(const PassInstance& p, bool distances_current, std::vector<double*>& columns) const {
    const Bodies& b = in_.bodies;
    columns.clear();
    for (int f : p.fields) columns.push_back(in_.fields.column(f).data());
    plab_pass_view v{sizeof(plab_pass_view)};
    v.dim = uint32_t(in_.dim);
    v.body_count = uint32_t(b.size());
    v.dt = in_.last_dt;
    v.time = in_.time;
    v.position = b.position.empty() ? nullptr : b.position[0].data();
    v.velocity = b.velocity.empty() ? nullptr : b.velocity[0].data();
    v.force = b.force.empty() ? nullptr : b.force[0].data();
    v.radius = b.radius.data();
    v.mass = b.mass.data();
    v.group = b.group.data();
    v.fields = columns.data();
    const PassContacts& c = in_.contacts;
    v.contact_count = uint32_t(c.size());
    v.contact_end1 = c.end1();
    v.contact_end2 = c.end2();
    v.contact_end2_is_wall = c.end2_is_wall();
    for (int a = 0; a < 3; ++a) periodic_length_[a] = b.cell.periodic[a] ? b.cell.length(a) : 0.0;
    v.contact_distance = c.distance(distances_current);  // they hold while the range test's lists do
    v.periodic_length = b.cell.any() ? periodic_length_.data() : nullptr;
    return v;
}

void Passes::run(std::uint32_t phase, bool distances_current, std::uint64_t step, const Unstable& unstable) {
    std::vector<double*> columns;
    for (PassInstance& p : list_) {
        if (p.desc->phase != phase) continue;
        plab_pass_view v = view(p, distances_current, columns);
        char diagnostic[2048];  // room for a pass's advice (sph_eos: ~800 characters)
        diagnostic[0] = '\0';
        v.diagnostic = diagnostic;
        v.diagnostic_capacity = sizeof diagnostic;
        const int rc = p.desc->run(p.state, p.props.data(), &v);
        if (rc == PLAB_PASS_UNSTABLE) unstable(p.desc->name, diagnostic);
        if (rc != 0) throw RunError(std::string("pass '") + p.desc->name + "' failed at step " + std::to_string(step));
    }
}

} // namespace plab
