#include "contacts/model_instance.hpp"

#include <stdexcept>

namespace plab {

int ModelInstance::history_slot(const std::string& name) const {
    for (uint32_t k = 0; k < desc->history_count; ++k)
        if (name == desc->history[k].name) return int(k);
    throw std::out_of_range("contact model " + model + " has no history slot " + name);
}

double ModelInstance::property(const std::string& name) const {
    for (uint32_t k = 0; k < desc->property_count; ++k)
        if (name == desc->properties[k].key) return props[k];
    throw std::out_of_range("contact model " + model + " has no property " + name);
}

} // namespace plab
