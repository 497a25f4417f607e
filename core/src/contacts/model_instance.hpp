// A contact model instance: a loaded model with the property values of one
// contact rule of the scene, its plug-in state, and its two contact tables.
#pragma once

#include "contacts/contact_set.hpp"

#include <plab/abi.h>

#include <memory>
#include <string>
#include <vector>

namespace plab {

struct ModelInstance {
    std::string model;
    const plab_contact_model_desc* desc = nullptr;
    std::vector<double> props;
    void* state = nullptr;
    double range = 0;  // activity range (gap or distance, see desc->range_kind)
    int stride = 0;    // history doubles per contact
    double max_overlap = kInf;  // stability: overlap limit, fraction of the smaller radius (1)
    std::vector<int> fields_read, fields_accumulated;  // world field indices
    ContactSet balls, walls;

    // By name, for measurements: a history slot's index and a property's
    // value (std::out_of_range when the model has none of that name).
    int history_slot(const std::string& name) const;
    double property(const std::string& name) const;
    // whether the model reads optional input / writes optional output
    // `bit` (PLAB_IO_*): all of them unless it declared which (abi.h, io)
    bool uses(std::uint32_t bit) const { return (desc->io & bit) != 0; }
};

using Instances = std::vector<std::unique_ptr<ModelInstance>>;

} // namespace plab
