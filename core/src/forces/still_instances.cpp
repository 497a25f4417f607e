#include "forces/still_instances.hpp"

#include <algorithm>

namespace plab {

void StillInstances::find(const Bodies& bodies, const AssignmentTable& table, const Instances& instances) {
    instance_.assign(instances.size(), 0);
    bool at_centres = false;
    for (const auto& inst : instances) at_centres |= (inst->desc->flags & PLAB_MODEL_FORCE_AT_CENTRES) != 0;
    if (!at_centres) return;
    const std::size_t ng = std::size_t(table.group_count());
    group_.assign(ng, 1);
    const std::uint8_t* fixity = bodies.fixity.data();
    const int* group = bodies.group.data();
    // by runs of one group (bodies are made group by group): a flag in a
    // register, not a load and store of the group's per body
    for (std::size_t i = 0; i < bodies.size();) {
        const int g = group[i];
        bool still = true;
        for (; i < bodies.size() && group[i] == g; ++i) still &= fixity[i] == dof_all;
        group_[std::size_t(g)] &= still;
    }
    std::fill(instance_.begin(), instance_.end(), 1);
    for (std::size_t a = 0; a < ng; ++a)
        for (std::size_t b = 0; b < ng; ++b) {
            const int inst = table.assigned(int(a), int(b));
            if (inst >= 0 && !(group_[a] && group_[b])) instance_[std::size_t(inst)] = 0;
        }
}

bool StillInstances::centre_table_still(std::uint32_t si, const ContactSet& table, const Instances& instances) const {
    const std::uint32_t m = si / 2;
    return !table.with_wall && m < instance_.size() && instance_[m] &&
           (instances[m]->desc->flags & PLAB_MODEL_FORCE_AT_CENTRES);
}

void hold_still(ContactSet& s) {
    if (s.forces_zero) return;
    std::fill(s.force.begin(), s.force.end(), 0.0);
    std::fill(s.dt_limit.begin(), s.dt_limit.end(), kInf);  // (empty when the set keeps none)
    s.forces_zero = true;
}

} // namespace plab
