// SPH validation case `dam_break` (thesis §5.2; Islam §5.1): a 2D water
// column of width a and height 2a released onto a dry bed. The surge front
// x/a against T = t √(2g/a) is compared with Martin & Moyce (1952),
// validation/reference/martin_moyce_1952_surge.csv (every series, T ≤ 3).
#include "sph_cases.hpp"

#include "../simulation.hpp"
#include "../validation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>

namespace plab::cases {

namespace {

constexpr double g = 9.81, rho0 = 1000.0, column_width = 0.1;

} // namespace

namespace {

// A block of fixed boundary balls (thesis §2.2.4) filling [lo, hi] at
// spacing db; 2D blocks drop z.
json wall_block(std::array<double, 3> lo, std::array<double, 3> hi, double db, int dim, const char* group) {
    auto point = [dim](const std::array<double, 3>& p) { return dim == 2 ? json{p[0], p[1]} : json{p[0], p[1], p[2]}; };
    return {{"type", "lattice"}, {"group", group}, {"packing", dim == 2 ? "square" : "cubic"},
            {"box", {{"min", point(lo)}, {"max", point(hi)}}}, {"radius", db / 2}, {"spacing", db},
            {"mass", rho0 * std::pow(db, dim)}, {"fix", {"all"}}};
}

} // namespace

// The tank is 5a long; boundary balls deep enough to cover the kernel support
// 2h. In 3D the column is `depth` thick between two side walls of group
// "side", free-slip (pressure only, their own sph_wall_pressure pass), so the
// flow stays two-dimensional and its front can be compared with the 2D one.
json dam_break_scene(const DamBreakSpec& s) {
    const int dim = s.dim;
    const double a = column_width, dp = s.spacing, db = s.boundary_ratio * dp, h = s.h_over_dp * dp;
    const double t = std::ceil(2 * h / db - 1e-9) * db, length = 5 * a, D = s.depth;
    const double wall_top = dim == 2 ? 2.5 * a : 2 * a + t;  // 3D: only as high as the column (fewer balls)
    const double c0 = s.sound_speed_factor * std::sqrt(2 * g * 2 * a);  // ten times the largest speed √(2 g H)
    json water = {{"groups", {"fluid", "boundary"}}, {"smoothing_length", h}, {"kernel", 0},
                  {"rest_density", rho0}, {"speed_of_sound", c0}, {"gamma", 7.0}};
    const json viscosity = s.mu > 0 ? json{{"viscosity", 0}, {"mu", s.mu}} : json{{"viscosity", 1}, {"alpha", s.alpha}};
    json sph = viscosity, sph_wall = viscosity;  // δ-SPH between fluid balls only
    sph["density_diffusion"] = s.delta;
    json passes = density_passes(s.density, 1);
    for (json p : json::array({
        {{"name", "sph_eos"}, {"material", "water"},
         {"properties", {{"boundary_group", 1}, {"hydrostatic_gravity", g}, {"surface_level", 2 * a}}}},
        {{"name", "sph_wall_pressure"}, {"material", "water"},
         {"properties", {{"boundary_group", 1}, {"no_slip", s.no_slip ? 1 : 0}}}}}))
        passes.push_back(p);
    if (s.xsph > 0)
        passes.push_back({{"name", "sph_xsph"}, {"material", "water"},
                          {"properties", {{"boundary_group", 1}, {"epsilon", s.xsph}}}});
    json bodies = {
        {{"type", "lattice"}, {"group", "fluid"}, {"packing", dim == 2 ? "square" : "cubic"},
         {"box", {{"min", dim == 2 ? json{0, 0} : json{0, 0, 0}}, {"max", dim == 2 ? json{a, 2 * a} : json{a, 2 * a, D}}}},
         {"radius", dp / 2}, {"spacing", dp}, {"mass", rho0 * std::pow(dp, dim)}, {"fix", {"rotation"}}},
        wall_block({-t, -t, -t}, {length + t, 0, D + t}, db, dim, "boundary"),
        wall_block({-t, 0, 0}, {0, wall_top, D}, db, dim, "boundary"),
        wall_block({length, 0, 0}, {length + t, wall_top, D}, db, dim, "boundary")};
    json rules = {{{"groups", {"fluid", "fluid"}}, {"model", "sph"}, {"properties", sph}},
                  {{"groups", {"fluid", "boundary"}}, {"model", "sph"}, {"properties", sph_wall}}};
    if (dim == 3) {
        bodies.push_back(wall_block({-t, 0, -t}, {length + t, wall_top, 0}, db, dim, "side"));
        bodies.push_back(wall_block({-t, 0, D}, {length + t, wall_top, D + t}, db, dim, "side"));
        water["groups"].push_back("side");
        rules.push_back({{"groups", {"fluid", "side"}}, {"model", "sph"}, {"properties", {{"viscosity", 1}, {"alpha", 0}}}});
        // the side balls are integrated and given an EOS pressure like fluid; this pass overwrites both
        passes.push_back({{"name", "sph_wall_pressure"}, {"material", "water"},
                          {"properties", {{"boundary_group", 2}, {"no_slip", 0}}}});
    }
    return {{"description", "dam break, column a x 2a (thesis 5.2, Martin & Moyce 1952)"},
            {"dimension", dim},
            {"gravity", dim == 2 ? json{0, -g} : json{0, -g, 0}},
            {"plugins", {"sph", "sph_passes"}},
            {"bodies", bodies},
            {"materials", {{"water", water}}},
            {"contact_models", rules},
            {"passes", passes}};
}

std::vector<std::pair<double, double>> martin_moyce(double t_max) {
    std::vector<std::pair<double, double>> points;  // columns: series, T, Z, t_orig_s
    for (const auto& c : reference_rows("martin_moyce_1952_surge.csv")) {
        if (c.size() < 3) continue;
        const double t = std::stod(c[1]);
        if (t <= t_max) points.emplace_back(t, std::stod(c[2]));
    }
    return points;
}

double front_at(const DamBreakResult& r, double T) {
    const auto it = std::lower_bound(r.T.begin(), r.T.end(), T);
    const std::size_t k = std::min<std::size_t>(std::size_t(it - r.T.begin()), r.T.size() - 1);
    return k == 0 ? r.Z[0] : r.Z[k - 1] + (r.Z[k] - r.Z[k - 1]) * (T - r.T[k - 1]) / (r.T[k] - r.T[k - 1]);
}

namespace {
// std/mean of the distance from each ball of a group to its nearest
// neighbour in that group (O(n²): a measurement at the end of a run).
double nearest_neighbour_spread(const World& w, int group) {
    std::vector<double> nearest;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        if (w.bodies.group[i] != group) continue;
        double best = 1e300;
        for (std::size_t j = 0; j < w.bodies.size(); ++j)
            if (j != i && w.bodies.group[j] == group)
                best = std::min(best, (w.bodies.position[j] - w.bodies.position[i]).squaredNorm());
        nearest.push_back(std::sqrt(best));
    }
    double mean = 0, var = 0;
    for (double d : nearest) mean += d / double(nearest.size());
    for (double d : nearest) var += (d - mean) * (d - mean) / double(nearest.size());
    return std::sqrt(var) / mean;
}
} // namespace

DamBreakResult dam_break(const DamBreakSpec& s) {
    Simulation sim(dam_break_scene(s));
    sim.set_quiet(true);
    World& w = sim.world();
    const int fluid = w.find_group("fluid");
    const double a = column_width, time_scale = std::sqrt(2 * g / a);
    DamBreakResult r;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) r.fluid += w.bodies.group[i] == fluid;
    const std::clock_t c0 = std::clock();
    auto record = [&]() {
        double front = 0;
        for (std::size_t i = 0; i < w.bodies.size(); ++i)
            if (w.bodies.group[i] == fluid) front = std::max(front, w.bodies.position[i].x());
        r.T.push_back(w.time * time_scale);
        r.Z.push_back((front + 0.5 * s.spacing) / a);  // a particle reaches dp/2 beyond its centre
    };
    record();
    while (r.T.back() < s.end_T) {
        w.step();
        record();
    }
    r.cpu_seconds = double(std::clock() - c0) / CLOCKS_PER_SEC;
    r.steps = long(w.step_count);
    r.disorder = nearest_neighbour_spread(w, fluid);
    const auto ref = martin_moyce(s.end_T);
    // PLAB_DAM_BREAK_TRACE=1 prints the simulated front beside each reference point
    const bool show = std::getenv("PLAB_DAM_BREAK_TRACE") != nullptr;
    for (const auto& [T, Z] : ref) {
        const double z = front_at(r, T);
        const double e = std::fabs(z - Z) / Z;
        if (show) std::printf("T %.3f  Z_ref %.3f  Z_sim %.3f\n", T, Z, z);
        r.mean_error += e / double(ref.size());
        r.max_error = std::max(r.max_error, e);
    }
    return r;
}

} // namespace plab::cases

namespace {

using namespace plab;
using namespace plab::cases;

} // namespace

