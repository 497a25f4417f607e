// `plab plot`: recorded histories (CSV) as a PNG, optionally against reference data.
#pragma once

#include <string>
#include <vector>

namespace plab {

int cmd_plot(const std::vector<std::string>& args);

} // namespace plab
