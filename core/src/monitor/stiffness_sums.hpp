// Per-body sums of the contact stiffnesses of the last force pass, for PFC's
// stable step sqrt(m / Σk) and sqrt(I / Σk_r): translational Σk_t, and
// rotational Σ(k_r + k_t r²) with r the arm from the centre to the contact
// point. Only the automatic timestep, snapshots and reports need them, so
// they are summed on demand, at most once per force pass, each body over its
// contacts in their fixed order (contacts/body_contacts.hpp).
#pragma once

#include <plab_host/bodies.hpp>

#include "contacts/body_contacts.hpp"
#include "contacts/contact_set.hpp"

#include <vector>

namespace plab {

class StiffnessSums {
public:
    void invalidate() { valid_ = false; }  // a force pass ran
    void clear(std::size_t bodies);        // zero at every body (a new scene)
    void sum(const Bodies& bodies, const BodyContacts& contacts, const std::vector<ContactSet*>& tables,
             std::size_t parallel_min);
    const std::vector<double>& translational() const { return k_trans_; }
    const std::vector<double>& rotational() const { return k_rot_; }
    // From a checkpoint: the sums of the pass that made the saved forces.
    void restore(std::vector<double> translational, std::vector<double> rotational);

private:
    std::vector<double> k_trans_, k_rot_;
    bool valid_ = false;
};

} // namespace plab
