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

// shared/reference beside the clone (the project's layout), else beside the
// working directory or inside the clone; PLAB_REFERENCE_DIR overrides.
std::string reference_dir() {
    namespace fs = std::filesystem;
    if (const char* env = std::getenv("PLAB_REFERENCE_DIR")) return env;
    const fs::path candidates[] = {fs::path(PLAB_SOURCE_DIR) / ".." / "shared" / "reference",
                                   fs::current_path() / ".." / "shared" / "reference",
                                   fs::path(PLAB_SOURCE_DIR) / "shared" / "reference"};
    for (const fs::path& c : candidates) {
        std::error_code ec;
        if (fs::is_directory(c, ec)) return c.lexically_normal().string();
    }
    return candidates[0].lexically_normal().string();
}

std::string examples_dir() {
    return (std::filesystem::path(PLAB_SOURCE_DIR) / "examples").string();
}

} // namespace plab
