#include "progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unistd.h>

namespace plab {

namespace {
std::string clock_text(double seconds) {
    char s[32];
    const long t = long(std::lround(seconds));
    if (t >= 3600) std::snprintf(s, sizeof s, "%ld:%02ld:%02ld", t / 3600, t / 60 % 60, t % 60);
    else std::snprintf(s, sizeof s, "%ld:%02ld", t / 60, t % 60);
    return s;
}
} // namespace

void Progress::start(Measure measure, double from, double to, std::uint64_t first_step) {
    measure_ = measure;
    from_ = from;
    to_ = to;
    first_step_ = first_step;
    tty_ = isatty(STDERR_FILENO);
    started_ = last_ = std::chrono::steady_clock::now();
}

std::string Progress::line(double time, std::uint64_t step, double elapsed) const {
    const double steps_done = double(step - first_step_), rate = steps_done / std::max(elapsed, 1e-9);
    const double at = measure_ == Measure::steps ? double(step) : time;
    char s[160];
    int n = std::snprintf(s, sizeof s, "t = %.4g s  step %llu", time, (unsigned long long)step);
    if (measure_ != Measure::open && to_ > from_) {
        const double fraction = std::clamp((at - from_) / (to_ - from_), 0.0, 1.0);
        const double left = fraction > 0 ? elapsed * (1 - fraction) / fraction : 0;
        n += std::snprintf(s + n, sizeof s - std::size_t(n), " of %.4g%s  %.1f %%  %.0f steps/s  ETA %s", to_,
                           measure_ == Measure::time ? " s" : "", 100 * fraction, rate,
                           fraction > 0 ? clock_text(left).c_str() : "-");
    } else {
        std::snprintf(s + n, sizeof s - std::size_t(n), "  %.0f steps/s", rate);
    }
    return s;
}

void Progress::update(double time, std::uint64_t step) {
    if (!enabled || (step & 63) != 0) return;
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_).count() < (tty_ ? 0.5 : 10.0)) return;
    last_ = now;
    const std::string text = line(time, step, std::chrono::duration<double>(now - started_).count());
    if (tty_) std::fprintf(stderr, "\r  %-100s", text.c_str());
    else std::fprintf(stderr, "progress: %s\n", text.c_str());
    std::fflush(stderr);
    drawn_ = true;
}

void Progress::finish() {
    if (tty_ && drawn_) std::fprintf(stderr, "\r%104s\r", "");
    drawn_ = false;
}

} // namespace plab
