// Measurements behind the SPH validation cases (contact model `sph`, passes
// `sph_eos` and `sph_density_integration`). tests/physics/sph_test.cpp calls
// the same functions and asserts the physics with stated tolerances.
#pragma once

#include <nlohmann/json.hpp>

#include <utility>
#include <vector>

namespace plab::cases {

// A block of fixed SPH boundary balls (thesis §2.2.4): radius db/2 at
// spacing db, mass rho0 db², every degree of freedom fixed, group "boundary".
nlohmann::json boundary_block(double x0, double y0, double x1, double y1, double db, double rho0 = 1000.0);

// The density passes of a scene whose material is "water": method 0 the
// continuity equation (thesis eq. 7, sph_density_integration), 1 summation
// (eq. 8), 2 continuity filtered by the normalised summation (eq. 9).
nlohmann::json density_passes(int method, int boundary_group);

// Thesis §5.2, Islam §5.1: a water column a wide, 2a high, released onto a
// dry bed in a tank 5a long; the surge front x/a against T = t sqrt(2g/a),
// compared with Martin & Moyce (1952).
struct DamBreakSpec {
    double spacing = 0.005;  // dp, m
    double h_over_dp = 1.3;
    double alpha = 0.1;      // Monaghan artificial viscosity (0.02 lets spray lead the front: 8.9 % at a/dp 20)
    double mu = 0.0;         // > 0: Morris laminar viscosity, Pa s, instead of Monaghan's (Islam §5.1: 0.05)
    double delta = 0.1;      // δ-SPH density diffusion (Islam eq. 6, his 0.1), fluid–fluid pairs
    bool no_slip = true;     // Adami no-slip walls (Islam §2.1); false: the wall balls' own (zero) velocity
    double end_T = 3.0;
    double sound_speed_factor = 10;  // c0 = this x the largest speed sqrt(2 g 2a)
    int dim = 2;
    double boundary_ratio = 0.5;  // boundary-ball spacing / dp (thesis: 1/2; Islam: 1)
    double depth = 0.04;          // 3D: column thickness between the free-slip side walls, m
    double xsph = 0;              // > 0: XSPH with this epsilon (thesis eq. 18, sph_xsph pass)
    int density = 0;              // 0 continuity (eq. 7), 2 continuity filtered by the normalised summation (eq. 9)
};

struct DamBreakResult {
    std::vector<double> T, Z;  // front history
    double mean_error = 0, max_error = 0;
    long fluid = 0, steps = 0;
    double cpu_seconds = 0;
    // particle disorder at the end: coefficient of variation (std/mean) of
    // each fluid ball's distance to its nearest fluid neighbour (0: a lattice)
    double disorder = 0;
};

nlohmann::json dam_break_scene(const DamBreakSpec& s);
DamBreakResult dam_break(const DamBreakSpec& s);
// Martin & Moyce (1952) surge points (T, Z) with T <= t_max, every series.
std::vector<std::pair<double, double>> martin_moyce(double t_max);
// The front Z = x/a at time T, interpolated in the recorded history.
double front_at(const DamBreakResult& r, double T);

} // namespace plab::cases
