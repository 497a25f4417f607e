// Measurements behind the DEM validation cases (issue: kernel). The tests
// call the same functions and assert the physics with stated tolerances.
#pragma once

#include <string>

namespace plab::cases {

// Free fall of one ball under gravity: max relative position error of the
// leapfrog against x0 + v0 t + g t²/2.
double free_fall_error(int dim, double dt, long steps);

struct Impact {
    double restitution = 0;        // measured e
    double duration = 0;           // measured contact time, s
    double expected_restitution = 0;  // exp(-βπ/√(1-β²))
    double expected_duration = 0;     // π/(ω√(1-β²))
};
// Normal impact of a ball on a ball (equal, head-on) or on a wall, linear
// model with normal damping ratio beta and dashpot mode (0 full, 2 no tension).
Impact normal_impact(int dim, bool on_wall, double beta, int dp_mode = 0);

// A ball launched sliding without spin on a frictional floor: returns the
// final rolling speed over the launch speed (2/3 disc, 5/7 sphere).
double rolling_speed_ratio(int dim);

// A box of elastic balls (packed: persistent contacts; else a dilute gas),
// no damping or friction, run `steps` at `fraction`
// of the critical step. Drift: the secular change (mean energy over the last
// 10 % of the run minus the first 10 %) over E0. Fluctuation: max |E - E0|/E0,
// the leapfrog's bounded O(dt²) oscillation while contacts are compressed.
struct EnergyRecord {
    double drift = 0, max_fluctuation = 0;
};
EnergyRecord energy_drift(int dim, double fraction, long steps, bool packed);

} // namespace plab::cases
