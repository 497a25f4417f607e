#include "monitor/stiffness_sums.hpp"

#include "forces/geometry.hpp"

#include <utility>

namespace plab {

void StiffnessSums::clear(std::size_t n) {
    k_trans_.assign(n, 0.0);
    k_rot_.assign(n, 0.0);
}

void StiffnessSums::sum(const Bodies& bodies, const BodyContacts& contacts, const std::vector<ContactSet*>& tables,
                        std::size_t parallel_min) {
    if (valid_) return;
    const std::size_t n = bodies.size();
    clear(n);
    if (contacts.built_for(n)) {
#pragma omp parallel for schedule(static) if (n >= parallel_min)
        for (std::size_t i = 0; i < n; ++i) {
            double kt = 0, kr = 0;
            for (const BodyContact& en : contacts.of(i)) {
                const ContactSet& s = *tables[en.set];
                const std::uint32_t k = en.row();
                if (!s.active[k]) continue;
                double arm2;
                if (s.packed) {  // the contact point lies on the normal, its radius + half the gap from each centre
                    const double arm = row_end_radius(bodies, s, k, en.end2()) + 0.5 * row_gap(bodies, s, k);
                    arm2 = arm * arm;
                } else {
                    const Vec centre = en.end2() ? row_end2_centre(bodies, s, k) : bodies.position[i];  // (a minimum image)
                    arm2 = (Vec(&s.point[3 * k]) - centre).squaredNorm();
                }
                kt += k_t_at(s, k);
                kr += k_r_at(s, k) + k_t_at(s, k) * arm2;
            }
            k_trans_[i] = kt;
            k_rot_[i] = kr;
        }
    }
    valid_ = true;
}

void StiffnessSums::restore(std::vector<double> translational, std::vector<double> rotational) {
    k_trans_ = std::move(translational);
    k_rot_ = std::move(rotational);
    valid_ = true;
}

} // namespace plab
