#include "validation.hpp"

#include <cstdlib>
#include <filesystem>

#ifndef PLAB_SOURCE_DIR
#define PLAB_SOURCE_DIR "."
#endif

namespace plab {

std::vector<ValidationCase>& validation_cases() {
    static std::vector<ValidationCase> cases = data_cases(validation_dir());
    return cases;
}

std::string validation_dir() {
    if (const char* env = std::getenv("PLAB_VALIDATION_DIR")) return env;
    return (std::filesystem::path(PLAB_SOURCE_DIR) / "validation").lexically_normal().string();
}

// The published data the cases compare with live in the repository
// (validation/reference, each file with its source header), so a clone in
// any folder validates; PLAB_REFERENCE_DIR points at another copy.
std::string reference_dir() {
    if (const char* env = std::getenv("PLAB_REFERENCE_DIR")) return env;
    return (std::filesystem::path(validation_dir()) / "reference").string();
}

} // namespace plab
