// The quick static tank of `plab validate static_tank --quick` (15 x 15
// particles at 10 mm, 0.3 s; validation/static_tank), run with overrides
// and read back through the case's own measurements.
#pragma once

#include "case_scene.hpp"

namespace plab::testing_support {

struct TankFigures {
    double pressure_l2 = 0;       // time-averaged pressure against rho0 g_eff (H - y), top rows excluded
    double max_displacement = 0;  // m, in the tank's frame
    double min_clearance = 0;     // m, smallest over the run
    int fluid = 0;
};

inline json quick_tank_scene(std::vector<std::pair<std::string, json>> sets = {}) {
    sets.insert(sets.begin(), {{"variables.columns", 15}, {"variables.rows", 15}, {"variables.dp", 0.01}, {"variables.end_time", 0.3}});
    return case_scene("static_tank", sets);
}

// Runs the scene to its end; a tank with tank_acceleration a > 0 has its
// boundary balls driven at v = a (t + dt/2) over each fixed step, so they
// rise as ½ a t² exactly.
inline TankFigures run_tank(json scene) {
    const double a = scene["variables"].value("tank_acceleration", 0.0);
    if (a > 0) scene["timestep"] = {{"fixed", "$(0.2 * h_over_dp * dp / c0)"}};
    const double end = scene["variables"]["end_time"].get<double>();
    scene.erase("commands");
    Simulation sim(scene);
    sim.set_quiet(true);
    World& w = sim.world();
    const int boundary = w.find_group("boundary"), fluid = w.find_group("fluid");
    while (w.time < end) {
        if (a > 0)
            for (std::size_t i = 0; i < w.bodies.size(); ++i)
                if (w.bodies.group[i] == boundary) w.bodies.velocity[i].y() = a * (w.time + 0.5 * w.fixed_dt);
        sim.cycle(1);
    }
    TankFigures f;
    f.pressure_l2 = sim.history("pressure_error").back();
    f.max_displacement = sim.history("displacement").back();
    f.min_clearance = sim.history("clearance").back();
    for (std::size_t i = 0; i < w.bodies.size(); ++i) f.fluid += w.bodies.group[i] == fluid;
    return f;
}

} // namespace plab::testing_support
