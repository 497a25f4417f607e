#include "validation.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

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

std::vector<std::vector<std::string>> reference_rows(const std::string& file) {
    const std::string path = reference_dir() + "/" + file;
    std::ifstream f(path);
    if (!f) throw std::runtime_error("reference data not found: " + path + " (set PLAB_REFERENCE_DIR)");
    std::vector<std::vector<std::string>> rows;
    bool header = true;
    for (std::string line; std::getline(f, line);) {
        if (line.empty() || line[0] == '#') continue;
        if (header) { header = false; continue; }
        std::vector<std::string> cells;
        std::stringstream ss(line);
        for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
        rows.push_back(std::move(cells));
    }
    return rows;
}

double sample_history(const std::vector<double>& ts, const std::vector<double>& xs, double t) {
    auto it = std::lower_bound(ts.begin(), ts.end(), t);
    if (it == ts.begin()) return xs.front();
    if (it == ts.end()) return xs.back();
    const std::size_t k = std::size_t(it - ts.begin());
    const double a = (t - ts[k - 1]) / (ts[k] - ts[k - 1]);
    return xs[k - 1] + a * (xs[k] - xs[k - 1]);
}

} // namespace plab
