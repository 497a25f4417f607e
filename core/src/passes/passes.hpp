// The passes a scene loads: plug-in functions over all bodies at one phase
// of the cycle (abi.h plab_pass_desc), reading and writing the body fields
// they declare and seeing the active contacts (PySPH's staged equation
// groups). This subsystem owns their instances, in the order they run (by
// phase, then stage, then order of addition), and runs a phase's passes on
// the bodies' state.
#pragma once

#include <plab_host/bodies.hpp>
#include <plab_host/fields.hpp>

#include "detection/range_test.hpp"

#include <plab/abi.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace plab {

struct PassInstance {
    const plab_pass_desc* desc = nullptr;
    std::vector<double> props;
    void* state = nullptr;
    std::vector<int> fields;  // the declared fields' indices in BodyFields
};

// What the passes read and write.
struct PassInputs {
    const int dim;
    const Bodies& bodies;
    BodyFields& fields;
    const PassContacts& contacts;
    const double& time;
    const double& last_dt;
};

class Passes {
public:
    explicit Passes(const PassInputs& in) : in_(in) {}
    ~Passes();  // each pass's state, destroyed by its plug-in
    Passes(const Passes&) = delete;
    Passes& operator=(const Passes&) = delete;

    void add(PassInstance p);  // at its place in the run order
    bool empty() const { return list_.empty(); }
    bool any_at(std::uint32_t phase) const;
    std::vector<PassInstance>::const_iterator begin() const { return list_.begin(); }
    std::vector<PassInstance>::const_iterator end() const { return list_.end(); }
    std::vector<PassInstance>& instances() { return list_; }  // for checkpoints
    const std::vector<PassInstance>& instances() const { return list_; }

    // Runs the passes of `phase` in order. `distances_current`: the range
    // test listed the contacts at the current positions, so a pass sees
    // their distances. A pass that reports its run unstable hands its
    // diagnostic to `unstable` (which may stop the run); any other failure
    // throws RunError naming the pass and `step`.
    using Unstable = std::function<void(const std::string& pass, const char* diagnostic)>;
    void run(std::uint32_t phase, bool distances_current, std::uint64_t step, const Unstable& unstable);

private:
    mutable std::array<double, 3> periodic_length_{};  // what a view's periodic_length points at
    PassInputs in_;
    std::vector<PassInstance> list_;
    plab_pass_view view(const PassInstance& p, bool distances_current, std::vector<double*>& columns) const;
};

} // namespace plab
