// The instability detector (DESIGN.md "Errors"; issue 7), run at the end of
// every cycle. A separate pass over bodies or contacts streams memory the
// cycle has already streamed (measured 3 % of a settled granular step at
// N = 1e4), so the bounds are compared where the data is at hand and only
// flags are read here (measured < 0.5 %, docs/stability.md):
//   * non-finite positions and particles leaving the domain — in the drift (integration/);
//   * energy appearing from nowhere — the energy balance the cycle already
//     keeps (Energies::balance), O(1);
//   * overlap beyond a fraction of the smaller radius — in geometry().
// Passes report what only they know (SPH density) through the pass view's
// diagnostic (abi.h, plab_pass_view::diagnostic; Cycle::run_passes). When a check fires, the run
// stops with a Diagnostic; Cycle::step() restores the last good state.
#include "monitor/stability.hpp"

#include <plab_host/errors.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace plab {

namespace {
// The first `dim` components of v, separated by spaces (as Eigen prints a
// row), without Eigen's printing of a dynamic-size block: GCC 12 warns of a
// 64-byte AVX-512 store into it (-march=native), on a path for longer rows.
std::string first_components(const Vec& v, int dim) {
    std::ostringstream s;
    for (int c = 0; c < dim; ++c) s << (c ? " " : "") << v[c];
    return s.str();
}
} // namespace

// After every change of the scene (and at the start) the balance, the energy
// turned over so far and the domain are measured afresh: a `set velocity`
// adds kinetic energy that no force did work for, and is not an instability.
void InstabilityDetector::measure_baseline(const Energies& e, const Bodies& bodies, const Walls& walls, const Vec& gravity) {
    StabilityBaseline& b = baseline;
    const int dim = bodies.dim;
    b.balance = e.balance();
    b.body = e.body;
    b.boundary = e.boundary;
    b.dissipated = e.slip + e.dashpot + e.local_damping + e.bond_break;
    b.stored = e.kinetic + e.strain;
    b.max_work = 0;
    // potential energy the particles hold over their own extent along g
    b.potential = 0;
    const double g = gravity.norm();
    if (g > 0 && bodies.size()) {
        const Vec up = -gravity / g;
        double lo = kInf, hi = -kInf, mass = 0;
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            lo = std::min(lo, up.dot(bodies.position[i]) - bodies.radius[i]);
            hi = std::max(hi, up.dot(bodies.position[i]) + bodies.radius[i]);
            mass += bodies.mass[i];
        }
        b.potential = mass * g * (hi - lo);
    }
    // the domain: the scene's, else the walls' bounding box (with the
    // bodies, which may start outside it) grown by the margin
    b.lo = limits.domain_min;
    b.hi = limits.domain_max;
    if (b.lo.array().isInf().all() && b.hi.array().isInf().all()) {
        Vec lo = Vec::Constant(kInf), hi = Vec::Constant(-kInf);
        bool any = false;
        for (const Facet& f : walls.facets) {
            if (f.kind == FacetKind::plane) continue;  // unbounded
            for (const Vec* p : {&f.a, &f.b, &f.c}) {
                if (f.kind == FacetKind::segment && p == &f.c) continue;
                lo = lo.cwiseMin(*p);
                hi = hi.cwiseMax(*p);
            }
            any = true;
        }
        if (any) {
            for (std::size_t i = 0; i < bodies.size(); ++i) {
                lo = lo.cwiseMin(bodies.position[i] - Vec::Constant(bodies.radius[i]));
                hi = hi.cwiseMax(bodies.position[i] + Vec::Constant(bodies.radius[i]));
            }
            const double margin = limits.domain_margin * (hi - lo).head(dim).maxCoeff();
            b.lo = lo - Vec::Constant(margin);
            b.hi = hi + Vec::Constant(margin);
        }
    }
    if (dim == 2) { b.lo.z() = -kInf; b.hi.z() = kInf; }
    // a ball leaves a periodic cell only to come back on the other side
    for (int c = 0; c < 3; ++c)
        if (bodies.cell.periodic[c]) { b.lo[c] = -kInf; b.hi[c] = kInf; }
}

// The drift flags a position outside the domain or not finite while it moves
// the balls (a second pass over positions would cost more than the check);
// the slow path here names the ball.
Diagnostic InstabilityDetector::domain_check(const Bodies& bodies, const AssignmentTable& groups) const {
    const StabilityBaseline& b = baseline;
    const int dim = bodies.dim;
    const std::size_t n = bodies.size();
    for (std::size_t i = 0; i < n; ++i) {
        const Vec& p = bodies.position[i];
        const bool finite = p.allFinite();
        if (finite && (p.array() >= b.lo.array()).all() && (p.array() <= b.hi.array()).all()) continue;
        Diagnostic d;
        d.subject = "ball id " + std::to_string(bodies.id[i]) + " (group " + groups.group_name(bodies.group[i]) + ")";
        std::ostringstream s;
        s << "position " << first_components(p, dim) << ", velocity " << first_components(bodies.velocity[i], dim);
        if (!finite) {
            d.quantity = "non-finite state";
            d.detail = s.str();
            d.cause = "a contact model or pass returned NaN/Inf, or the state overflowed";
        } else {
            d.quantity = "domain";
            s << " outside [" << first_components(b.lo, dim) << "] .. [" << first_components(b.hi, dim) << "]";
            d.detail = s.str();
            d.cause = "a particle went through a wall (the wall contact is too soft or the particle too fast), or the "
                      "domain is too small (scene.domain, scene.stability.domain_margin)";
        }
        return d;
    }
    return {};
}

// Energy from nowhere: the balance (kinetic + strain - work + dissipated)
// may only stay or fall (a model that does not report what it dissipates,
// e.g. SPH viscosity, makes it fall); a rise beyond `energy_gain` times the
// energy turned over is an instability.
Diagnostic InstabilityDetector::energy_check(const Energies& e, const Bodies& bodies, const AssignmentTable& groups) {
    if (!(limits.energy_gain < kInf)) return {};
    // a sheared cell's boundary works on the balls (Lees–Edwards), and that
    // work is not summed: the balance would rise by the shear's work
    if (bodies.cell.sheared) return {};
    StabilityBaseline& b = baseline;
    const double work = std::fabs(e.body - b.body) + std::fabs(e.boundary - b.boundary);
    b.max_work = std::max(b.max_work, work);
    const double dissipated = e.slip + e.dashpot + e.local_damping + e.bond_break - b.dissipated;
    const double turnover = b.stored + b.max_work + std::max(dissipated, 0.0) + 0.01 * b.potential;
    const double gain = e.balance() - b.balance;
    if (!(gain > 0) || gain <= limits.energy_gain * turnover) return {};
    std::size_t top = 0;
    double top_kinetic = -1;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const double k = 0.5 * bodies.mass[i] * bodies.velocity[i].squaredNorm() +
                         0.5 * bodies.inertia[i] * bodies.angular_velocity[i].squaredNorm();
        if (k > top_kinetic) { top_kinetic = k; top = i; }
    }
    Diagnostic d;
    d.quantity = "energy gain";
    d.subject = bodies.size() ? "largest kinetic energy " + short_number(top_kinetic) + " J on ball id " +
                                    std::to_string(bodies.id[top]) + " (group " + groups.group_name(bodies.group[top]) + ")"
                              : "no bodies";
    d.detail = "the energy balance rose by " + short_number(gain) + " J with no work to account for it, more than " +
               short_number(limits.energy_gain) + " x the " + short_number(turnover) + " J turned over (scene.stability.energy_gain)";
    d.cause = "a timestep close to the stable limit (lower timestep.safety_factor or timestep.fixed), or a plug-in "
              "that adds energy";
    return d;
}

} // namespace plab
