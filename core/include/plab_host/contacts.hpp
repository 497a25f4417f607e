// Read views of a world's contacts, as the last force pass left them: per
// model instance its two contact tables (ball–ball, ball–wall), row by row.
// The rows are candidates within the neighbour lists' skin; active() says
// which touch (are within the model's range).
#pragma once

#include <plab_host/types.hpp>

#include <plab/abi.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace plab {

class Cycle;
struct ModelInstance;
struct ContactSet;

// Rows per call of a model (one C ABI call per batch). Batches are fixed row
// ranges, never per thread, so sums taken per batch are thread-count free.
constexpr std::size_t kContactBatch = 512;

// A row's key: the ball id of end 1 and the ball or facet id of end 2.
using ContactKey = std::pair<BodyId, BodyId>;

class ContactTable {
public:
    ContactTable(const Cycle& cycle, const ModelInstance& instance, const ContactSet& set)
        : cycle_(&cycle), instance_(&instance), set_(&set) {}
    std::size_t size() const;
    bool with_wall() const;  // end 2 is a wall facet
    bool active(std::size_t k) const;
    std::size_t end1(std::size_t k) const;  // ball index
    std::size_t end2(std::size_t k) const;  // ball index, or facet index (with_wall)
    ContactKey key(std::size_t k) const;
    // The row's history slots (ModelView::history_slot gives their order).
    const double* history(std::size_t k) const;
    // Whether the row is bonded: its model's persist slot is set.
    bool bonded(std::size_t k) const;
    Vec force(std::size_t k) const;  // on end 2, N
    // Normal (end 1 to end 2), contact point and surface gap: a packed
    // table's are recomputed from the positions with the force pass's
    // arithmetic (the same bits, as long as no ball moved since).
    Vec normal(std::size_t k) const;
    Vec point(std::size_t k) const;
    double gap(std::size_t k) const;
    double end_radius(std::size_t k, bool end2) const;  // a wall's: 0
    double stiffness(std::size_t k) const;              // translational, N/m, for the stable step
    double dt_limit(std::size_t k) const;               // s; inf: none

private:
    const Cycle* cycle_;
    const ModelInstance* instance_;
    const ContactSet* set_;
};

// A contact-model instance: the model, its property values, its tables.
class ModelView {
public:
    ModelView(const Cycle& cycle, const ModelInstance& instance) : cycle_(&cycle), instance_(&instance) {}
    const std::string& model() const;
    const plab_contact_model_desc& desc() const;
    const std::vector<double>& properties() const;  // in the model's declaration order
    double range() const;  // activity range, m: a gap or a centre distance (desc().range_kind)
    // By name (std::out_of_range when the model has none of that name).
    int history_slot(const std::string& name) const;
    double property(const std::string& name) const;
    ContactTable balls() const;
    ContactTable walls() const;

private:
    const Cycle* cycle_;
    const ModelInstance* instance_;
};

} // namespace plab
