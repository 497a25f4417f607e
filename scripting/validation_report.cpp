// `plab validate --report DIR`: a Markdown page a reviewer can read on the
// forge or locally, with the plots the cases hand back (CaseResult::plots).
#include "validation.hpp"

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace plab {

std::string write_validation_report(const std::string& dir, const std::vector<CaseRun>& runs, bool quick) {
    fs::create_directories(dir);
    std::ofstream md(fs::path(dir) / "report.md");
    char buf[512];
    const std::time_t now = std::time(nullptr);
    std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    md << "# ParticleLab validation report\n\n"
       << "`plab validate" << (quick ? " --quick" : "") << "`, " << buf
       << (quick ? " — coarse versions (as in CI); the full runs are `plab validate --all`." : ".") << "\n\n"
       << "| case | verdict | error | tolerance | what the error measures | CPU (s) |\n|---|---|---:|---:|---|---:|\n";
    int failed = 0;
    for (const CaseRun& r : runs) {
        std::snprintf(buf, sizeof buf, "| [%s](#%s) | %s | %.4g | %.4g | %s | %.2f |\n", r.name.c_str(), r.name.c_str(),
                      r.result.passed() ? "PASS" : "**FAIL**", r.result.error, r.result.tolerance, r.result.metric.c_str(),
                      r.cpu_seconds);
        md << buf;
        failed += !r.result.passed();
    }
    md << "\n" << runs.size() - failed << " passed, " << failed << " failed.\n";
    for (const CaseRun& r : runs) {
        md << "\n## " << r.name << "\n\n" << r.description << "\n\n";
        std::snprintf(buf, sizeof buf, "**%s**: error %.4g against tolerance %.4g (%s); CPU %.2f s.\n\n",
                      r.result.passed() ? "PASS" : "FAIL", r.result.error, r.result.tolerance, r.result.metric.c_str(),
                      r.cpu_seconds);
        md << buf;
        if (!r.stopped.empty()) md << "Stopped: `" << r.stopped << "`\n\n";
        if (!r.result.details.empty()) md << "```\n" << r.result.details << "```\n\n";
        for (std::size_t k = 0; k < r.result.plots.size(); ++k) {
            const std::string png = r.name + "_" + std::to_string(k) + ".png";
            write_plot_png(r.result.plots[k], (fs::path(dir) / png).string());
            md << "![" << r.result.plots[k].title << "](" << png << ")\n\n";
        }
    }
    return (fs::path(dir) / "report.md").string();
}

} // namespace plab
