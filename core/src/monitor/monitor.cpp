// The stability monitor (monitor.hpp): the detector's checks at the end of
// a cycle, the stable timestep, the names of the balls and contacts a
// diagnostic points at, and the stop (the cycle then restores the last good
// state, Cycle::step).
#include "monitor/monitor.hpp"

#include <plab_host/errors.hpp>

#include "forces/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace plab {

void Monitor::detect_instability() {
    if (!detector.limits.enabled) return;
    if (left_domain_)  // (the drift flagged a position out of the domain or not finite)
        if (Diagnostic d = detector.domain_check(in_.bodies, in_.groups); !d.quantity.empty()) stop(d);
    if (Diagnostic d = detector.energy_check(in_.energies, in_.bodies, in_.groups); !d.quantity.empty()) stop(d);
    check_overlaps();
}

// geometry() flags a contact set with an overlap beyond its model's limit
// while it computes the gaps; the slow path names the contact.
void Monitor::check_overlaps() {
    for (auto& inst : in_.instances)
        for (const ContactSet* s : {&inst->balls, &inst->walls})
            if (s->overlap_exceeded) overlap_stop(*inst, *s);
}

void Monitor::overlap_stop(const ModelInstance& inst, const ContactSet& s) {
    for (std::size_t k = 0; k < s.size(); ++k) {
        if (!s.active[k]) continue;  // (before the gap: a packed set's takes a square root)
        const double r = s.with_wall ? row_end_radius(in_.bodies, s, k, false) : std::min(row_end_radius(in_.bodies, s, k, false), row_end_radius(in_.bodies, s, k, true));
        const double gap = row_gap(in_.bodies, s, k);
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

std::string Monitor::contact_name(const ModelInstance& inst, const ContactSet& s, std::size_t k) const {
    const int i = s.end1[k];
    std::string name = "contact of ball id " + std::to_string(in_.bodies.id[i]) + " (group " + in_.groups.group_name(in_.bodies.group[i]) + ") and ";
    if (s.with_wall) {
        const Wall& w = in_.walls.walls[in_.walls.facets[s.end2[k]].wall];
        name += "wall '" + w.name + "' (group " + in_.groups.group_name(w.group) + ")";
    } else {
        const int j = s.end2[k];
        name += "ball id " + std::to_string(in_.bodies.id[j]) + " (group " + in_.groups.group_name(in_.bodies.group[j]) + ")";
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
std::string Monitor::timestep_assessment() const { return assess_timestep(snapshot_stable_, last_dt_, ""); }

void Monitor::stop(Diagnostic d) {
    d.step = step_count_;
    d.time = time_;
    std::string dt = timestep_assessment();
    // A limit that depends on the state (a drag that grows with the slip,
    // SPH's |v| in the CFL step) can fall below a fixed step after the last
    // good state: the limits the models reported in this step, if finite.
    if (dt.empty()) dt = assess_timestep(stable_timestep(), last_dt_, " at the failing step (it was above the step at "
                                                                     "the last good state)");
    if (!dt.empty()) d.cause = dt + "; else " + d.cause;
    stopped_ = d;
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
Diagnostic Monitor::pass_diagnostic(const std::string& pass, const std::string& raw) const {
    const std::string message = name_balls(raw, in_.bodies, in_.groups.group_names());
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

// For a plug-in author: the model and contact whose output went non-finite.
std::string Monitor::non_finite_contact(std::size_t body) const {
    for (const auto& inst : in_.instances)
        for (const ContactSet* set : {&inst->balls, &inst->walls})
            for (std::size_t k = 0; k < set->size(); ++k) {
                if (!set->active[k] || (std::size_t(set->end1[k]) != body && (set->with_wall || std::size_t(set->end2[k]) != body)))
                    continue;
                const Vec f(&set->force[3 * k]), m1 = moment1_at(*set, k), m2 = moment2_at(*set, k);
                if (f.allFinite() && m1.allFinite() && m2.allFinite()) continue;
                std::ostringstream s;
                s << "contact model '" << inst->model << "' returned a non-finite force or moment (a contact model returned NaN) for the contact of ball id "
                  << in_.bodies.id[set->end1[k]] << (set->with_wall ? " with a wall" : " and ball id " + std::to_string(in_.bodies.id[set->end2[k]]))
                  << " at gap " << row_gap(in_.bodies, *set, k) << " m: check its law for division by zero, sqrt or log of a negative "
                  << "number, or use of history before it is set";
                return s.str();
            }
    return "";
}

void Monitor::check_finite() {
    for (std::size_t i = 0; i < in_.bodies.size(); ++i) {
        if (in_.bodies.position[i].allFinite() && in_.bodies.force[i].allFinite() && in_.bodies.moment[i].allFinite() &&
            in_.bodies.velocity[i].allFinite())
            continue;
        std::ostringstream s;
        s << "position " << in_.bodies.position[i].transpose() << ", force " << in_.bodies.force[i].transpose();
        Diagnostic d;
        d.quantity = "non-finite state";
        d.subject = "ball id " + std::to_string(in_.bodies.id[i]) + " (group " + in_.groups.group_name(in_.bodies.group[i]) + ")";
        d.detail = s.str();
        // for a plug-in author: the model and contact whose output went non-finite
        const std::string culprit = non_finite_contact(i);
        d.cause = culprit.empty() ? "a contact model returned NaN or Inf (or a pass did), or the state overflowed" : culprit;
        stop(d);
    }
}

// PFC's per-ball estimate; the reason names the model and group that set
// it, so a diagnostic can say "2.1x the stable limit of model linear for
// group grains". Strings are built once, for the winner only.
StableStep Monitor::stable_timestep() {
    summed_stiffness();
    if (!nominal_valid_) { nominal_cache_ = nominal_timestep(); nominal_valid_ = true; }
    StableStep best = nominal_cache_;
    std::size_t ball = in_.bodies.size();
    bool rotation = false;
    // per-ball stiffness sums exist once forces were computed (prepare())
    const std::vector<double>&k_trans = stiffness.translational(), &k_rot = stiffness.rotational();
    const std::size_t summed = std::min(in_.bodies.size(), k_trans.size());
    for (std::size_t i = 0; i < summed; ++i) {
        if (k_trans[i] > 0) {
            const double dt = std::sqrt(in_.bodies.mass[i] / k_trans[i]);
            if (dt < best.critical) { best.critical = dt; ball = i; rotation = false; }
        }
        if (k_rot[i] > 0) {
            const double dt = std::sqrt(in_.bodies.inertia[i] / k_rot[i]);
            if (dt < best.critical) { best.critical = dt; ball = i; rotation = true; }
        }
    }
    const std::size_t clump = clump_timestep(k_trans, k_rot, best, rotation);
    if (clump < in_.clumps.size()) ball = in_.bodies.size();
    const ModelInstance* limit_model = nullptr;
    const ContactSet* limit_set = nullptr;
    std::size_t limit_row = 0;
    for (std::uint32_t si = 0; si < in_.sets.size(); ++si) {
        const ContactSet* s = in_.sets[si];
        auto consider = [&](double dt, std::size_t k) {
            if (!(dt < best.critical)) return;
            best.critical = dt;
            limit_model = in_.set_owner[si]; limit_set = s; limit_row = k;
            ball = in_.bodies.size();
        };
        if (in_.packed.has_limits(si)) {  // (their rows are active)
            for (const BatchLimit& b : in_.packed.limits(si)) consider(b.dt, b.row);
            continue;
        }
        if (s->dt_limit.empty()) continue;  // a set that keeps no step limit has none (ContactSet::keeps)
        for (std::size_t k = 0; k < s->size(); ++k)
            if (s->active[k]) consider(s->dt_limit[k], k);
    }
    if (clump < in_.clumps.size() && !limit_model && ball == in_.bodies.size()) {
        best.limited_by = "group " + in_.groups.group_name(in_.clumps.group[clump]) + ": " +
                          (rotation ? "rotation" : "translation") + " of clump id " + std::to_string(in_.clumps.id[clump]) +
                          (rotation ? " (sqrt(I_min/sum (k_r + k d^2)) over its pebbles)" : " (sqrt(M/sum k) over its pebbles)");
    } else if (limit_model) {
        best.limited_by = "model " + limit_model->model + " for groups " + contact_groups(*limit_set, limit_row) +
                          ": its step limit";
    } else if (ball < in_.bodies.size()) {
        best.limited_by = "model " + stiffest_model(ball) + " for group " + in_.groups.group_name(in_.bodies.group[ball]) + ": " +
                          (rotation ? "rotation" : "translation") + " of ball id " + std::to_string(in_.bodies.id[ball]) +
                          (rotation ? " (sqrt(I/sum k_r))" : " (sqrt(m/sum k))");
    }
    return best;
}

// A clump's critical step from its pebbles' stiffness sums: translation
// sqrt(M / Σ k), rotation sqrt(I_min / Σ (k_r + k d²)) with d the pebble's
// reach from the centre of mass (its centre's distance plus its radius), the
// stiffest a contact force on the pebble can turn the clump. Lowers `best`
// where a clump limits it; returns that clump (else the clump count).
std::size_t Monitor::clump_timestep(const std::vector<double>& k_trans, const std::vector<double>& k_rot,
                                    StableStep& best, bool& rotation) const {
    const Clumps& C = in_.clumps;
    std::size_t limit = C.size();
    for (std::size_t c = 0; c < C.size(); ++c) {
        double k = 0, k_turn = 0;
        for (std::size_t p = C.first_pebble[c]; p < C.first_pebble[c + 1]; ++p) {
            const std::size_t i = std::size_t(C.pebble_body[p]);
            if (i >= k_trans.size()) continue;
            const double reach = C.pebble_offset[p].norm() + in_.bodies.radius[i];
            k += k_trans[i];
            k_turn += k_rot[i] + k_trans[i] * reach * reach;
        }
        const double smallest = C.smallest_moment(c);
        if (k > 0 && std::sqrt(C.mass[c] / k) < best.critical) {
            best.critical = std::sqrt(C.mass[c] / k); limit = c; rotation = false;
        }
        if (k_turn > 0 && std::sqrt(smallest / k_turn) < best.critical) {
            best.critical = std::sqrt(smallest / k_turn); limit = c; rotation = true;
        }
    }
    return limit;
}

// "grains-walls": the groups of a contact's two ends.
std::string Monitor::contact_groups(const ContactSet& s, std::size_t k) const {
    const int g2 = s.with_wall ? in_.walls.walls[in_.walls.facets[s.end2[k]].wall].group : in_.bodies.group[s.end2[k]];
    return in_.groups.group_name(in_.bodies.group[s.end1[k]]) + "-" + in_.groups.group_name(g2);
}

// The model that gives ball i most of its stiffness.
std::string Monitor::stiffest_model(std::size_t i) const {
    std::vector<double> k_of(in_.instances.size(), 0.0);
    if (in_.body_contacts.built_for(in_.bodies.size()))
        for (const BodyContact& en : in_.body_contacts.of(i)) {
            const ContactSet& s = *in_.sets[en.set];
            const std::uint32_t k = en.row();
            if (!s.active[k]) continue;
            for (std::size_t m = 0; m < in_.instances.size(); ++m)
                if (in_.set_owner[en.set] == in_.instances[m].get()) k_of[m] += k_t_at(s, k);
        }
    const auto top = std::max_element(k_of.begin(), k_of.end());
    return top == k_of.end() || *top <= 0 ? std::string("(none)") : in_.instances[std::size_t(top - k_of.begin())]->model;
}

} // namespace plab
