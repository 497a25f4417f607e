#include "validation.hpp"

#include <cstdlib>
#include <filesystem>

#ifndef PLAB_SOURCE_DIR
#define PLAB_SOURCE_DIR "."
#endif

namespace plab {

std::vector<ValidationCase>& validation_cases() {
    static std::vector<ValidationCase> cases;
    return cases;
}

bool register_case(ValidationCase c) {
    validation_cases().push_back(std::move(c));
    return true;
}

std::string reference_dir() {
    if (const char* env = std::getenv("PLAB_REFERENCE_DIR")) return env;
    return (std::filesystem::path(PLAB_SOURCE_DIR) / ".." / "shared" / "reference").lexically_normal().string();
}

std::string examples_dir() {
    return (std::filesystem::path(PLAB_SOURCE_DIR) / "examples").string();
}

} // namespace plab
