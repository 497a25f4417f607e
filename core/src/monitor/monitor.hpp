// The stability monitor: the stable timestep (PFC's per-ball estimate, the
// models' own limits, a nominal contact per group pair before any contact
// exists), the instability detector's checks at the end of a cycle, and the
// stop that names the ball, contact or pass a diagnostic points at.
#pragma once

#include <plab_host/bodies.hpp>
#include <plab_host/clumps.hpp>
#include <plab_host/stability.hpp>
#include <plab_host/walls.hpp>
#include <plab_host/world.hpp>

#include "contacts/assignment.hpp"
#include "contacts/body_contacts.hpp"
#include "contacts/model_instance.hpp"
#include "forces/packed_tables.hpp"
#include "monitor/stability.hpp"
#include "monitor/stiffness_sums.hpp"

#include <string>
#include <vector>

namespace plab {

// What the monitor reads: the world's state and the contact tables.
struct MonitorInputs {
    const int dim;
    const Bodies& bodies;
    const Clumps& clumps;
    const Walls& walls;
    const AssignmentTable& groups;
    const Instances& instances;
    const std::vector<ContactSet*>& sets;  // every table, instance m's at 2m (balls) and 2m + 1 (walls)
    const std::vector<const ModelInstance*>& set_owner;
    const BodyContacts& body_contacts;
    const PackedTables& packed;  // the step limits of the packed tables
    const Energies& energies;
    const std::size_t& parallel_min;
};

class Monitor {
public:
    // `clock` and `stopped` are the world's: a stop dates its diagnostic and
    // leaves it there.
    Monitor(const MonitorInputs& in, const std::uint64_t& step_count, const double& time, const double& last_dt,
            Diagnostic& stopped)
        : in_(in), step_count_(step_count), time_(time), last_dt_(last_dt), stopped_(stopped) {}

    InstabilityDetector detector;  // its limits (the host's) and its baseline
    // Per-body stiffness sums of the last force pass, summed on demand
    // (summed_stiffness(): a cache, so a const monitor may fill it).
    mutable StiffnessSums stiffness;
    const StiffnessSums& summed_stiffness() const {
        stiffness.sum(in_.bodies, in_.body_contacts, in_.sets, in_.parallel_min);
        return stiffness;
    }

    // Critical step from the contacts of the last force pass, and from a
    // nominal contact per assigned group pair (cached until forget_nominal()).
    StableStep stable_timestep();
    StableStep nominal_timestep() const;
    void forget_nominal() { nominal_valid_ = false; }
    // The stable step at the last good state: the first suspect of a stop.
    void keep_snapshot_step() { snapshot_stable_ = stable_timestep(); }
    // The drift's verdict: a position left the domain or is not finite.
    void set_left_domain(bool left) { left_domain_ = left; }

    // The checks at the end of a cycle: domain, energy from nowhere, overlap.
    void detect_instability();
    // A body whose state is not finite after the reduction stops the run,
    // naming the contact whose output went non-finite.
    void check_finite();
    // Fills in the step, time and likely cause, keeps d as the world's
    // `stopped`, and throws RunError.
    [[noreturn]] void stop(Diagnostic d);
    // A pass's message (abi.h convention) as a diagnostic.
    Diagnostic pass_diagnostic(const std::string& pass, const std::string& message) const;

private:
    void check_overlaps();
    void overlap_stop(const ModelInstance& inst, const ContactSet& s);
    std::string contact_name(const ModelInstance& inst, const ContactSet& s, std::size_t k) const;
    std::string contact_groups(const ContactSet& s, std::size_t k) const;
    std::string stiffest_model(std::size_t ball) const;
    std::size_t clump_timestep(const std::vector<double>& k_trans, const std::vector<double>& k_rot, StableStep& best,
                               bool& rotation) const;
    std::string non_finite_contact(std::size_t body) const;
    std::string timestep_assessment() const;

    MonitorInputs in_;
    const std::uint64_t& step_count_;
    const double &time_, &last_dt_;
    Diagnostic& stopped_;
    StableStep nominal_cache_, snapshot_stable_;
    bool nominal_valid_ = false;
    bool left_domain_ = false;
};

} // namespace plab
