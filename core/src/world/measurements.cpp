// What a host measures of the world beside its own state: the ball stress,
// the unbalanced-force ratio, the contacts and bonds, the state hash; and
// the bonding of touching balls (PFC's `contact method bond`).
#include <plab_host/world.hpp>

#include "world/cycle.hpp"

#include "forces/geometry.hpp"

#include <cmath>

namespace plab {

std::vector<Eigen::Matrix3d> ball_stress(const World& w) {
    std::vector<Eigen::Matrix3d> sigma(w.bodies.size(), Eigen::Matrix3d::Zero());
    for (const auto& inst : w.cycle->instances)
        for (const ContactSet* s : {&inst->balls, &inst->walls})
            for (std::size_t k = 0; k < s->size(); ++k) {
                if (!s->active[k]) continue;
                const Vec f2(&s->force[3 * k]), p = row_point(w.bodies, *s, k);
                const int i = s->end1[k];
                sigma[i] += (p - w.bodies.position[i]) * (-f2).transpose();
                if (!s->with_wall) {
                    const int j = s->end2[k];
                    sigma[j] += (p - row_end2_centre(w.bodies, *s, k)) * f2.transpose();  // (a minimum image)
                }
            }
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        const double r = w.bodies.radius[i];
        const double volume = w.dim == 2 ? M_PI * r * r : 4.0 / 3.0 * M_PI * r * r * r;
        sigma[i] /= volume;
    }
    return sigma;
}

std::size_t World::bond(int a, int b, double gap_tolerance) {
    if (!cycle->prepared) prepare();
    std::size_t made = 0;
    for (auto& inst : cycle->instances) {
        const int slot = inst->desc->persist_slot;
        if (slot < 0) continue;
        ContactSet& s = inst->balls;
        for (std::size_t k = 0; k < s.size(); ++k) {
            const int g1 = bodies.group[s.end1[k]], g2 = bodies.group[s.end2[k]];
            if (!((g1 == a && g2 == b) || (g1 == b && g2 == a))) continue;
            if (row_gap(bodies, s, k) > gap_tolerance) continue;
            s.history[k * inst->stride + slot] = 1;
            ++made;
        }
    }
    cycle->prepared = false;  // re-evaluate forces with the bonds in place
    return made;
}

std::size_t intact_bonds(const World& w) {
    std::size_t n = 0;
    for (const auto& inst : w.cycle->instances) {
        const int slot = inst->desc->persist_slot;
        if (slot < 0) continue;
        for (const ContactSet* s : {&inst->balls, &inst->walls})
            for (std::size_t k = 0; k < s->size(); ++k) n += s->history[k * inst->stride + slot] > 0;
    }
    return n;
}

double unbalanced_force_ratio(const World& w) {
    double unbalanced = 0;
    std::size_t free_bodies = 0;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        const std::uint8_t fix = w.bodies.fixity[i];
        Vec f = w.bodies.force[i];
        for (int c = 0; c < 3; ++c)
            if (fix & (dof_x << c)) f[c] = 0;
        if ((fix & (dof_x | dof_y | dof_z)) == (dof_x | dof_y | dof_z)) continue;
        unbalanced += f.norm();
        ++free_bodies;
    }
    double contact = 0;
    std::size_t n = 0;
    for (auto& inst : w.cycle->instances)
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

std::size_t active_contacts(const World& w) {
    std::size_t n = 0;
    for (auto& inst : w.cycle->instances)
        for (const ContactSet* s : {&inst->balls, &inst->walls})
            for (std::uint8_t a : s->active) n += a;
    return n;
}

std::uint64_t state_hash(const World& w) {
    std::uint64_t h = 1469598103934665603ull;
    auto mix = [&h](const void* p, std::size_t bytes) {
        const auto* c = static_cast<const unsigned char*>(p);
        for (std::size_t i = 0; i < bytes; ++i) h = (h ^ c[i]) * 1099511628211ull;
    };
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        mix(w.bodies.position[i].data(), 3 * sizeof(double));
        mix(w.bodies.velocity[i].data(), 3 * sizeof(double));
        mix(w.bodies.angular_velocity[i].data(), 3 * sizeof(double));
    }
    // a clump's angular momentum and orientation are state its pebbles do not show
    for (std::size_t c = 0; c < w.clumps.size(); ++c) {
        mix(w.clumps.angular_momentum[c].data(), 3 * sizeof(double));
        mix(w.clumps.orientation[c].coeffs().data(), 4 * sizeof(double));
    }
    return h;
}

} // namespace plab
