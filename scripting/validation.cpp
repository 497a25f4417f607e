#include "validation.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

#ifndef PLAB_SOURCE_DIR
#define PLAB_SOURCE_DIR "."
#endif

namespace plab {

namespace {
std::vector<ValidationCase>& registered() {
    static std::vector<ValidationCase> cases;
    return cases;
}
} // namespace

std::vector<ValidationCase>& validation_cases() {
    static std::vector<ValidationCase> cases = [] {
        std::vector<ValidationCase> code = std::move(registered());
        registered().clear();
        register_data_cases(validation_dir());
        std::vector<ValidationCase> all = std::move(registered());
        for (ValidationCase& c : code) {
            for (const ValidationCase& d : all)
                if (d.name == c.name) throw std::runtime_error("validation case \"" + c.name + "\" is defined twice: in C++ and in " + validation_dir());
            all.push_back(std::move(c));
        }
        return all;
    }();
    return cases;
}

bool register_case(ValidationCase c) {
    registered().push_back(std::move(c));
    return true;
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

std::string examples_dir() {
    return (std::filesystem::path(PLAB_SOURCE_DIR) / "examples").string();
}

std::vector<std::vector<std::string>> reference_rows(const std::string& file) {
    const std::string path = reference_dir() + "/" + file;
    std::ifstream f(path);
    if (!f) throw std::runtime_error("reference data not found: " + path);
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
