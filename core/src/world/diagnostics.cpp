// The world's diagnostics: the detector's checks at the end of a cycle,
// the names of the balls and contacts a diagnostic points at, and the stop
// that restores the last good state (Cycle::step).
#include "world/cycle.hpp"

#include <plab_host/errors.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace plab {

void Cycle::detect_instability() {
    if (!detector_.limits.enabled) return;
    if (left_domain_)  // (the drift flagged a position out of the domain or not finite)
        if (Diagnostic d = detector_.domain_check(bodies, assignment_); !d.quantity.empty()) stop(d);
    if (Diagnostic d = detector_.energy_check(energies, bodies, assignment_); !d.quantity.empty()) stop(d);
    check_overlaps();
}

// geometry() flags a contact set with an overlap beyond its model's limit
// while it computes the gaps; the slow path names the contact.
void Cycle::check_overlaps() {
    for (auto& inst : instances_)
        for (const ContactSet* s : {&inst->balls, &inst->walls})
            if (s->overlap_exceeded) overlap_stop(*inst, *s);
}

void Cycle::overlap_stop(const ModelInstance& inst, const ContactSet& s) {
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

std::string Cycle::contact_name(const ModelInstance& inst, const ContactSet& s, std::size_t k) const {
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
std::string Cycle::timestep_assessment() const { return assess_timestep(snapshot_stable_, last_dt, ""); }

void Cycle::stop(Diagnostic d) {
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
Diagnostic Cycle::pass_diagnostic(const std::string& pass, const std::string& raw) const {
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
