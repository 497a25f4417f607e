// The progress line of a running command: where it is against where it
// ends, %, steps/s and the time left. On a terminal one line rewritten in
// place every half second; otherwise (a log file, a batch job) a plain line
// every 10 s, as LIGGGHTS's thermo output. Debian packages no C++
// progress-bar library, so this is the one place that draws it.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace plab {

class Progress {
public:
    // what the command runs to: simulated time (s) or a step count
    enum class Measure { time, steps, open };  // open: a ratio solve, no end known
    void start(Measure measure, double from, double to, std::uint64_t first_step);
    // called every step; draws at most every half second (10 s off a terminal)
    void update(double time, std::uint64_t step);
    void finish();  // clears the line on a terminal
    bool enabled = false;

private:
    std::string line(double time, std::uint64_t step, double elapsed) const;
    Measure measure_ = Measure::open;
    double from_ = 0, to_ = 0;
    std::uint64_t first_step_ = 0;
    bool tty_ = false, drawn_ = false;
    std::chrono::steady_clock::time_point started_, last_;
};

} // namespace plab
