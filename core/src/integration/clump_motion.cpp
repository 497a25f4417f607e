// The clumps' leapfrog of clump_motion.hpp. Each clump's sums are taken
// serially over its pebbles in their order, and the clumps' energy sums are
// added in clump order, so the answer does not depend on the thread count.
#include "integration/clump_motion.hpp"

#include "integration/rigid_rotation.hpp"

#include <algorithm>
#include <cmath>

namespace plab {

namespace {

// Half a kick of clump c: v += h F/M along free translations (thesis eq. 33),
// L += h T when its rotation is free; a fixed DOF keeps its velocity. ω is
// left for the caller to renew: the opening kick's turn renews it anyway.
void kick_clump(Clumps& C, std::size_t c, double h) {
    for (int k = 0; k < 3; ++k)
        if (!(C.fixity[c] & (dof_x << k))) C.velocity[c][k] += h * C.force[c][k] / C.mass[c];
    if (!C.rotation_fixed(c)) C.angular_momentum[c] += h * C.moment[c];
}

// L of a clump whose spin is prescribed: L = R I Rᵀ ω.
Vec prescribed_momentum(const Clumps& C, std::size_t c) {
    const Eigen::Matrix3d R = C.orientation[c].toRotationMatrix();
    return R * C.principal_moments[c].asDiagonal() * (R.transpose() * C.angular_velocity[c]);
}

// The orientation over dt: the free rotation of Euler's equations (Joubert
// eq. 35, rigid_rotation.hpp), or a turn at the prescribed spin.
void turn_clump(Clumps& C, std::size_t c, double dt) {
    if (!C.rotation_fixed(c)) {
        RigidRotation r{C.orientation[c], C.angular_momentum[c]};
        rotate_freely(r, C.principal_moments[c], dt);
        C.orientation[c] = r.orientation;
        C.update_angular_velocity(c);
        return;
    }
    const Vec& w = C.angular_velocity[c];
    const double rate = w.norm();
    if (rate > 0) C.orientation[c] = (Eigen::Quaterniond(Eigen::AngleAxisd(rate * dt, w / rate)) * C.orientation[c]).normalized();
    C.angular_momentum[c] = prescribed_momentum(C, c);
}

// F = M g + Σ (f_p − m_p g), T = Σ (M_p + arm_p × (f_p − m_p g)) over clump
// c's pebbles in order: the reduction gave each pebble the clump's weight
// (its mass is the clump's), taken back here and counted once.
void sum_onto_clump(Clumps& C, const Bodies& B, const Vec& gravity, std::size_t c) {
    Vec f = C.mass[c] * gravity, m = Vec::Zero();
    for (std::size_t p = C.first_pebble[c]; p < C.first_pebble[c + 1]; ++p) {
        const std::size_t i = std::size_t(C.pebble_body[p]);
        const Vec contact = B.force[i] - B.mass[i] * gravity;
        f += contact;
        m += B.moment[i] + (B.position[i] - C.position[c]).cross(contact);
    }
    C.force[c] = f;
    C.moment[c] = m;
}

// PFC local damping of the clump's sums, −α |F| sign(v) per component and
// likewise for the moment (at the half-step velocities); returns its work over dt.
double damp_clump(Clumps& C, std::size_t c, double dt) {
    const double alpha = C.local_damping[c];
    if (!(alpha > 0)) return 0;
    double work = 0;
    for (int k = 0; k < 3; ++k) {
        const double v = C.velocity[c][k], w = C.angular_velocity[c][k];
        const double fd = -alpha * std::fabs(C.force[c][k]) * ((v > 0) - (v < 0));
        const double md = -alpha * std::fabs(C.moment[c][k]) * ((w > 0) - (w < 0));
        C.force[c][k] += fd;
        C.moment[c][k] += md;
        work -= (fd * v + md * w) * dt;
    }
    return work;
}

// The work over dt of the reactions that hold clump c's fixed DOFs.
double reaction_work(const Clumps& C, std::size_t c, double dt) {
    double work = 0;
    for (int k = 0; k < 3; ++k)
        if (C.fixity[c] & (dof_x << k)) work -= C.force[c][k] * C.velocity[c][k] * dt;
    if (C.rotation_fixed(c)) work -= C.moment[c].dot(C.angular_velocity[c]) * dt;
    return work;
}

} // namespace

void ClumpMotion::hold_pebbles(const Clumps& C, Bodies& B) const {
    for (std::int32_t i : C.pebble_body) B.velocity[std::size_t(i)].setZero();
}

DriftResult ClumpMotion::kick_and_drift(Clumps& C, Bodies& B, const DriftInputs& in, double dt, DriftResult balls,
                                        std::size_t parallel_min) {
    const std::size_t n = C.size();
    drift_.assign(n, {});
    const bool tracked = in.position_at_build && in.position_at_build->size() == B.size();
#pragma omp parallel for schedule(static) if (n >= parallel_min / 4)
    for (std::size_t c = 0; c < n; ++c) {
        kick_clump(C, c, 0.5 * dt);
        const Vec dx = C.velocity[c] * dt;
        C.position[c] += dx;
        turn_clump(C, c, dt);
        C.place_pebbles(B, c);
        DriftResult& d = drift_[c];
        d.body_work = C.mass[c] * in.gravity.dot(dx);
        d.max_drift2 = 0;
        for (std::size_t p = C.first_pebble[c]; p < C.first_pebble[c + 1]; ++p) {
            const std::size_t i = std::size_t(C.pebble_body[p]);
            const Vec& x = B.position[i];
            if (tracked) d.max_drift2 = std::max(d.max_drift2, (x - (*in.position_at_build)[i]).squaredNorm());
            d.left_domain |= !((x.array() >= in.lo.array()).all() && (x.array() <= in.hi.array()).all() && x.allFinite());
        }
    }
    for (const DriftResult& d : drift_) {
        balls.body_work += d.body_work;
        if (balls.max_drift2 >= 0) balls.max_drift2 = std::max(balls.max_drift2, d.max_drift2);
        balls.left_domain |= d.left_domain;
    }
    return balls;
}

ClumpEnergies ClumpMotion::finish(Clumps& C, Bodies& B, const Vec& gravity, double half_dt, double dt,
                                  std::size_t parallel_min) {
    const std::size_t n = C.size();
    energies_.assign(n, {});
#pragma omp parallel for schedule(static) if (n >= parallel_min / 4)
    for (std::size_t c = 0; c < n; ++c) {
        sum_onto_clump(C, B, gravity, c);
        ClumpEnergies& e = energies_[c];
        e.local_damping = damp_clump(C, c, dt);
        if (half_dt > 0) {
            kick_clump(C, c, half_dt);
            C.update_angular_velocity(c);  // (a fixed spin keeps its ω)
        }
        if (C.rotation_fixed(c)) C.angular_momentum[c] = prescribed_momentum(C, c);
        C.place_pebbles(B, c);  // (the positions are unchanged: the velocities are synchronised)
        e.kinetic = C.kinetic_energy(c);
        e.boundary = reaction_work(C, c, dt);
    }
    ClumpEnergies sum;
    for (const ClumpEnergies& e : energies_) {
        sum.kinetic += e.kinetic;
        sum.boundary += e.boundary;
        sum.local_damping += e.local_damping;
    }
    return sum;
}

} // namespace plab
