// The history quantities a scene can record (`histories.record[k].quantity`),
// with their SI units: `plab quantities` lists them, history columns carry
// their unit into summary.json, and `plab plot` labels its axes with it.
#pragma once

#include <plab_host/world.hpp>

#include <string>
#include <vector>

namespace plab {

struct QuantityInfo {
    std::string name;  // e.g. "ball.velocity.<x|y|z|magnitude>"
    std::string unit;  // SI, "-" for a count or a ratio
    std::string doc;
};

// Built-in quantities, then probe.<field> and every measure.<name>.
std::vector<QuantityInfo> history_quantities();

// The dotted parts of a quantity's name ("ball.velocity.x": ball, velocity,
// x), empty ones kept ("ball." has two) so that a stray dot is refused.
std::vector<std::string> quantity_parts(const std::string& quantity);

// The unit of a recorded quantity ("" when it cannot be told: an
// expression, a measurement whose unit depends on its parameters).
std::string quantity_unit(const std::string& quantity, const World& w);

} // namespace plab
