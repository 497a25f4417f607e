// Validation cases: a scene plus a comparison with reference data or an
// analytical solution, with a stated tolerance. Each case is a folder
// validation/<case>/ with a case.json (case_runner.cpp, docs/validation.md):
// a new case needs a folder, not code.
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
    // judged by all the case's checks, `error` and `tolerance` being the first one's
    int failed_checks = 0;
    bool passed() const { return failed_checks == 0; }
};

struct ValidationCase {
    std::string name, description;
    std::function<CaseResult(bool quick)> run;
};

// Every case: the folders of validation_dir() with a case.json, by name.
std::vector<ValidationCase>& validation_cases();
// The cases of FOLDER/<case>/case.json, each named after its folder.
std::vector<ValidationCase> data_cases(const std::string& folder);
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

// Directory of the published reference data: validation/reference in the
// repository, or PLAB_REFERENCE_DIR.
std::string reference_dir();
} // namespace plab
