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
// diagnostic (abi.h, ABI 2; World::run_passes). When a check fires, the run
// stops with a Diagnostic; World::step() restores the last good state.
#include "world/world.hpp"

#include "common/error.hpp"

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
void World::set_stability_baseline() {
    StabilityBaseline& b = baseline_;
    const Energies& e = energies;
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
    b.lo = stability.domain_min;
    b.hi = stability.domain_max;
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
            const double margin = stability.domain_margin * (hi - lo).head(dim).maxCoeff();
            b.lo = lo - Vec::Constant(margin);
            b.hi = hi + Vec::Constant(margin);
        }
    }
    if (dim == 2) { b.lo.z() = -kInf; b.hi.z() = kInf; }
}

void World::detect_instability() {
    if (!stability.enabled) return;
    check_domain_and_finite();
    check_energy();
    check_overlaps();
}

// The drift flags a position outside the domain or not finite while it moves
// the balls (a second pass over positions would cost more than the check);
// the slow path here names the ball.
void World::check_domain_and_finite() {
    if (!left_domain_) return;
    const StabilityBaseline& b = baseline_;
    const std::size_t n = bodies.size();
    for (std::size_t i = 0; i < n; ++i) {
        const Vec& p = bodies.position[i];
        const bool finite = p.allFinite();
        if (finite && (p.array() >= b.lo.array()).all() && (p.array() <= b.hi.array()).all()) continue;
        Diagnostic d;
        d.subject = "ball id " + std::to_string(bodies.id[i]) + " (group " + assignment_.group_name(bodies.group[i]) + ")";
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
        stop(d);
    }
}

// Energy from nowhere: the balance (kinetic + strain - work + dissipated)
// may only stay or fall (a model that does not report what it dissipates,
// e.g. SPH viscosity, makes it fall); a rise beyond `energy_gain` times the
// energy turned over is an instability.
void World::check_energy() {
    if (!(stability.energy_gain < kInf)) return;
    StabilityBaseline& b = baseline_;
    const Energies& e = energies;
    const double work = std::fabs(e.body - b.body) + std::fabs(e.boundary - b.boundary);
    b.max_work = std::max(b.max_work, work);
    const double dissipated = e.slip + e.dashpot + e.local_damping + e.bond_break - b.dissipated;
    const double turnover = b.stored + b.max_work + std::max(dissipated, 0.0) + 0.01 * b.potential;
    const double gain = e.balance() - b.balance;
    if (!(gain > 0) || gain <= stability.energy_gain * turnover) return;
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
                                    std::to_string(bodies.id[top]) + " (group " + assignment_.group_name(bodies.group[top]) + ")"
                              : "no bodies";
    d.detail = "the energy balance rose by " + short_number(gain) + " J with no work to account for it, more than " +
               short_number(stability.energy_gain) + " x the " + short_number(turnover) + " J turned over (scene.stability.energy_gain)";
    d.cause = "a timestep close to the stable limit (lower timestep.safety_factor or timestep.fixed), or a plug-in "
              "that adds energy";
    stop(d);
}

// geometry() flags a contact set with an overlap beyond its model's limit
// while it computes the gaps; the slow path names the contact.
void World::check_overlaps() {
    for (auto& inst : instances_)
        for (const ContactSet* s : {&inst->balls, &inst->walls})
            if (s->overlap_exceeded) overlap_stop(*inst, *s);
}

void World::overlap_stop(const ModelInstance& inst, const ContactSet& s) {
    for (std::size_t k = 0; k < s.size(); ++k) {
        if (!s.active[k]) continue;  // (before the gap: a packed set's takes a square root)
        const double r = s.with_wall ? end_radius(s, k, false) : std::min(end_radius(s, k, false), end_radius(s, k, true));
        const double gap = contact_gap(s, k);
        if (-gap <= inst.max_overlap * r) continue;
        Diagnostic d;
        d.quantity = "overlap";
        d.subject = contact_name(inst, s, k);
        d.detail = "overlap " + short_number(-gap) + " m is " + short_number(-gap / r) + " x the smaller radius " + short_number(r) +
                   " m, above the limit " + short_number(inst.max_overlap) + " (contact_models[].max_overlap)";
        d.cause = "the contact is too soft for the load or the impact speed (the overlap of an impact grows as "
                  "v sqrt(m/k)): raise the stiffness or lower the speed";
        stop(d);
    }
}

std::string World::contact_name(const ModelInstance& inst, const ContactSet& s, std::size_t k) const {
    const int i = s.end1[k];
    std::string name = "contact of ball id " + std::to_string(bodies.id[i]) + " (group " + assignment_.group_name(bodies.group[i]) + ") and ";
    if (s.with_wall) {
        const Wall& w = walls.walls[walls.facets[s.end2[k]].wall];
        name += "wall '" + w.name + "' (group " + assignment_.group_name(w.group) + ")";
    } else {
        const int j = s.end2[k];
        name += "ball id " + std::to_string(bodies.id[j]) + " (group " + assignment_.group_name(bodies.group[j]) + ")";
    }
    return name + ", model " + inst.model;
}

namespace {

// "timestep ... x the stable limit ... of MODEL", when dt is above the limit s.
std::string assess_timestep(const StableStep& s, double dt, const std::string& when) {
    if (!(s.critical < kInf) || !(s.critical > 0) || !(dt > 0)) return "";
    const double ratio = dt / s.critical;
    if (!(ratio > 1.0)) return "";
    return "timestep " + short_number(dt) + " s is " + short_number(ratio) + "x the stable limit " + short_number(s.critical) + " s of " +
           s.limited_by + when + " (lower timestep.fixed, or use the automatic step)";
}

} // namespace

// The first suspect of any instability: a step above the stable limit the
// models reported at the last good state.
std::string World::timestep_assessment() const { return assess_timestep(snapshot_stable_, last_dt, ""); }

void World::stop(Diagnostic d) {
    d.step = step_count;
    d.time = time;
    std::string dt = timestep_assessment();
    // A limit that depends on the state (a drag that grows with the slip,
    // SPH's |v| in the CFL step) can fall below a fixed step after the last
    // good state: the limits the models reported in this step, if finite.
    if (dt.empty()) dt = assess_timestep(stable_timestep(), last_dt, " at the failing step (it was above the step at "
                                                                     "the last good state)");
    if (!dt.empty()) d.cause = dt + "; else " + d.cause;
    stopped = d;
    throw RunError(d.message(), d.quantity);
}

} // namespace plab

namespace plab {

namespace {

// A pass knows a body only by its index in the view; the user knows it by
// the id in the scene and the outputs. "ball index N" in a pass's message
// (the convention of abi.h) becomes "ball id ID (group NAME)", so the ABI
// needs no id column.
std::string name_balls(std::string message, const Bodies& bodies, const std::vector<std::string>& groups) {
    const std::string key = "ball index ";
    for (std::size_t at = message.find(key); at != std::string::npos; at = message.find(key, at)) {
        std::size_t end = at + key.size();
        while (end < message.size() && message[end] >= '0' && message[end] <= '9' && end - at < key.size() + 18) ++end;
        const std::string digits = message.substr(at + key.size(), end - at - key.size());
        const unsigned long long i = digits.empty() ? ~0ull : std::stoull(digits);
        if (i >= bodies.size()) { at = end; continue; }  // not a body of this world: leave it as written
        const std::string name = "ball id " + std::to_string(bodies.id[i]) + " (group " + groups[bodies.group[i]] + ")";
        message.replace(at, end - at, name);
        at += name.size();
    }
    return message;
}

} // namespace

// A pass's message reads "QUANTITY: what, where, value against bound;
// likely cause: ..." (abi.h); the parts go where the host's own go.
Diagnostic World::pass_diagnostic(const std::string& pass, const std::string& raw) const {
    const std::string message = name_balls(raw, bodies, assignment_.group_names());
    Diagnostic d;
    const std::size_t colon = message.find(": ");
    d.quantity = colon == std::string::npos ? pass : message.substr(0, colon);
    std::string rest = colon == std::string::npos ? message : message.substr(colon + 2);
    const std::string marker = "; likely cause: ";
    const std::size_t cause = rest.find(marker);
    if (cause != std::string::npos) {
        d.cause = rest.substr(cause + marker.size());
        rest = rest.substr(0, cause);
    } else {
        d.cause = "see the pass " + pass;
    }
    d.subject = "pass " + pass;
    d.detail = rest.empty() ? "(no message)" : rest;
    return d;
}

} // namespace plab
