// Validation cases: a scene plus a comparison with reference data or an
// analytical solution, with a stated tolerance. Cases register themselves
// (PLAB_VALIDATION_CASE) so later issues add theirs without touching the CLI.
#pragma once

#include "plot.hpp"

#include <functional>
#include <string>
#include <vector>

namespace plab {

struct CaseResult {
    double error = 0;      // the case's error figure (relative unless `metric` says otherwise)
    double tolerance = 0;  // passes when error <= tolerance
    std::string metric;    // what `error` measures
    std::string details;   // per-sub-case lines for the report
    std::vector<Plot> plots;  // optional: series against reference data, drawn by `plab validate --report`
    // data cases: judged by all their checks, `error` and `tolerance` being the first one's
    bool judged_by_checks = false;
    int failed_checks = 0;
    bool passed() const { return judged_by_checks ? failed_checks == 0 : error <= tolerance; }
};

struct ValidationCase {
    std::string name, description;
    std::function<CaseResult(bool quick)> run;
};

// Every case: the folders of validation/ with a case.json (case_runner.cpp),
// then those written in C++.
std::vector<ValidationCase>& validation_cases();
// Registers each FOLDER/<case>/case.json as a case named after its folder.
void register_data_cases(const std::string& folder);
// validation/ in the repository (PLAB_VALIDATION_DIR overrides).
std::string validation_dir();

// One case as run by `plab validate`, for the report.
struct CaseRun {
    std::string name, description;
    CaseResult result;
    double cpu_seconds = 0;
    std::string stopped;  // the exception text when the case stopped
};
// Writes DIR/report.md (a table of every case: verdict, error, tolerance,
// CPU time; then per case its details and plots) and DIR/<case>_<k>.png.
// Returns the path of report.md.
std::string write_validation_report(const std::string& dir, const std::vector<CaseRun>& runs, bool quick);
bool register_case(ValidationCase c);

// Directory of the published reference data: validation/reference in the
// repository, or PLAB_REFERENCE_DIR.
std::string reference_dir();
// Directory of the repository's examples (PLAB_EXAMPLES_DIR at build time).
std::string examples_dir();

// The data rows of a reference CSV in reference_dir(), split into cells:
// comment lines (#), blank lines and the one header line are skipped.
// Throws, naming the path, when the file is missing.
std::vector<std::vector<std::string>> reference_rows(const std::string& file);

// A sampled history (ts ascending) at time t: linear between samples, the
// end value outside them.
double sample_history(const std::vector<double>& ts, const std::vector<double>& xs, double t);

} // namespace plab

#define PLAB_CAT2(a, b) a##b
#define PLAB_CAT(a, b) PLAB_CAT2(a, b)
#define PLAB_VALIDATION_CASE(name, description, ...) \
    static const bool PLAB_CAT(plab_case_, __LINE__) = ::plab::register_case({name, description, __VA_ARGS__})
