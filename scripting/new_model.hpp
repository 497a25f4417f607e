// `plab new-model NAME [DIR]`: writes an out-of-tree contact-model project
// (CMakeLists.txt, a model with two properties, a Catch2 test, README) that
// builds against the installed SDK and loads into plab as it is.
#pragma once

#include <string>
#include <vector>

namespace plab {

int cmd_new_model(const std::vector<std::string>& args);

} // namespace plab
