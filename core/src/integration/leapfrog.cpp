// The leapfrog of leapfrog.hpp: kicks and drifts over blocks of bodies,
// each block's sums kept apart and added in block order.
#include "integration/leapfrog.hpp"

#include <algorithm>
#include <cmath>

namespace plab {

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
// (SPH particles), so only v is kicked; the energy sums are kick_fixed_block()'s.
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
void kick_fixed_block(Bodies& bodies, const double* inv_m, const double* inv_i, double h, std::size_t i0, std::size_t i1,
                bool energies, double& kinetic, double& boundary) {
    const std::uint8_t implicit = bodies.implicit_fixity();
    const std::uint8_t* fixity = bodies.fixity.data();
    const KickColumns B(bodies);
    for (std::size_t i = i0; i < i1; ++i) {
        const std::uint8_t fix = fixity[i];
        if (fix & dof_clumped) continue;  // its clump moves it (clump_motion.hpp)
        for (int c = 0; c < 3; ++c) {
            if (!(fix & (dof_x << c))) B.velocity[i][c] += h * B.force[i][c] * inv_m[i];
            if (!(fix & (dof_rx << c))) B.angular_velocity[i][c] += h * B.moment[i][c] * inv_i[i];
        }
        if (energies) add_body_energy(B, i, B.velocity[i], B.angular_velocity[i], 2 * h, fix & ~implicit, kinetic, boundary);
    }
}

} // namespace


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

void Leapfrog::cache_inverse_masses(const Bodies& bodies) {
    const std::size_t n = bodies.size();
    inv_mass_.resize(n);
    inv_inertia_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        inv_mass_[i] = 1.0 / bodies.mass[i];
        inv_inertia_[i] = 1.0 / bodies.inertia[i];
    }
}

void Leapfrog::prepare_blocks(const Bodies& bodies) {
    const std::size_t n = bodies.size(), n_blocks = body_blocks(n);
    if (inv_mass_.size() != n) cache_inverse_masses(bodies);  // e.g. a world just loaded from a checkpoint
    block_kinetic_.resize(n_blocks);
    block_boundary_.resize(n_blocks);
    block_body_work_.resize(n_blocks);
    block_max_drift2_.resize(n_blocks);
    block_out_.resize(n_blocks);
}

// Half a kick of block b; the closing kick of a step (`closing`) also
// takes the block's energy sums while the velocities are at hand.
void Leapfrog::kick_block(Bodies& bodies, std::size_t b, double h, bool closing) {
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
    const int dim = bodies.dim;
    double kinetic = 0, boundary = 0;
    if (fixed == spin && every == spin) {  // rotations fixed, translations free, in every body
        if (dim == 3)
            closing ? kick_free_block<3, true, true>(bodies, inv_m, inv_i, h, i0, i1, kinetic, boundary)
                    : kick_free_block<3, false, true>(bodies, inv_m, inv_i, h, i0, i1, kinetic, boundary);
        else
            closing ? kick_free_block<2, true, true>(bodies, inv_m, inv_i, h, i0, i1, kinetic, boundary)
                    : kick_free_block<2, false, true>(bodies, inv_m, inv_i, h, i0, i1, kinetic, boundary);
    } else if (fixed)
        kick_fixed_block(bodies, inv_m, inv_i, h, i0, i1, closing, kinetic, boundary);
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

void Leapfrog::kick(Bodies& bodies, double h, bool closing, std::size_t parallel_min) {
    const std::size_t n = bodies.size(), n_blocks = body_blocks(n);
    prepare_blocks(bodies);
#pragma omp parallel for schedule(static) if (n >= parallel_min)
    for (std::size_t b = 0; b < n_blocks; ++b) kick_block(bodies, b, h, closing);
}

// Without a pass between them, the drift of a block follows its kick in the
// same loop, while v is in cache.
DriftResult Leapfrog::kick_and_drift(Bodies& bodies, const DriftInputs& in, double dt, std::size_t parallel_min) {
    const std::size_t n = bodies.size(), n_blocks = body_blocks(n);
    prepare_blocks(bodies);
#pragma omp parallel for schedule(static) if (n >= parallel_min)
    for (std::size_t b = 0; b < n_blocks; ++b) {
        kick_block(bodies, b, 0.5 * dt, false);
        drift_block(bodies, b, dt, in);
    }
    return finish_drift(bodies, in);
}

// x += (v + correction) dt; the correction (abi.h, PLAB_PHASE_PRE_DRIFT) only
// where a pass registered its fields, and only along free translational DOFs.
DriftResult Leapfrog::drift(Bodies& bodies, const DriftInputs& in, double dt, std::size_t parallel_min) {
    const std::size_t n = bodies.size(), n_blocks = body_blocks(n);
    prepare_blocks(bodies);
#pragma omp parallel for schedule(static) if (n >= parallel_min)
    for (std::size_t b = 0; b < n_blocks; ++b) drift_block(bodies, b, dt, in);
    return finish_drift(bodies, in);
}

void Leapfrog::body_energies(Bodies& bodies, double dt) {
    const std::size_t n = bodies.size(), n_blocks = body_blocks(n);
    block_kinetic_.assign(n_blocks, 0.0);
    block_boundary_.assign(n_blocks, 0.0);
    const std::uint8_t implicit = bodies.implicit_fixity();
    const KickColumns cols(bodies);
    for (std::size_t b = 0; b < n_blocks; ++b)
        for (std::size_t i = b * kBodyBlock; i < std::min(n, (b + 1) * kBodyBlock); ++i)
            if (!(bodies.fixity[i] & dof_clumped))
                add_body_energy(cols, i, cols.velocity[i], cols.angular_velocity[i], dt, bodies.fixity[i] & ~implicit,
                            block_kinetic_[b], block_boundary_[b]);
}

double Leapfrog::kinetic() const {
    double sum = 0;
    for (double e : block_kinetic_) sum += e;
    return sum;
}

double Leapfrog::boundary_work() const {
    double sum = 0;
    for (double e : block_boundary_) sum += e;
    return sum;
}

// The drift of block b. While x is at hand: the work of gravity, the
// detector's domain check and the largest displacement since the last
// build (the Verlet skin test).
void Leapfrog::drift_block(Bodies& bodies, std::size_t b, double dt, const DriftInputs& in) {
    const std::size_t i0 = b * kBodyBlock, i1 = std::min(bodies.size(), i0 + kBodyBlock);
    // (no reference positions yet: measured against x itself; finish_drift() knows)
    const bool tracked = in.position_at_build && in.position_at_build->size() == bodies.size();
    const DriftColumns c{bodies.position.data(), bodies.velocity.data(),
                         tracked ? in.position_at_build->data() : bodies.position.data(), bodies.mass.data(),
                         bodies.fixity.data(), in.lo, in.hi, in.gravity};
    const DriftSums sums = bodies.dim == 2 && !in.corrected()
                               ? drift_plane_rows(c, dt, i0, i1)
                               : drift_rows(c, in.corrected() ? in.correction.data() : nullptr, dt, i0, i1);
    block_body_work_[b] = sums.body_work;
    block_max_drift2_[b] = sums.max2;
    block_out_[b] = sums.out;
}

DriftResult Leapfrog::finish_drift(const Bodies& bodies, const DriftInputs& in) const {
    DriftResult r;
    double max2 = 0;
    for (std::size_t b = 0; b < body_blocks(bodies.size()); ++b) {
        r.body_work += block_body_work_[b];
        max2 = std::max(max2, block_max_drift2_[b]);
        r.left_domain |= block_out_[b] != 0;
    }
    const bool tracked = in.position_at_build && in.position_at_build->size() == bodies.size();
    r.max_drift2 = tracked ? max2 : -1;  // -1: no reference, rebuild
    return r;
}

} // namespace plab
