// Unresolved SPH–DEM coupling (issue 5, plug-in coupling_fluid_particle):
// the drag law's limits (Stokes, Schiller–Naumann, the cylinder in 2D), the
// exact momentum exchange of the reaction returned to the fluid (thesis
// eq. 81), buoyancy from the SPH pressure gradient, and the quick
// sedimentation case (thesis §7.1) within its stated tolerance.
#include "simulation.hpp"

#include <plab/coupling/drag_law.hpp>
#include "../support/sph_boundary.hpp"
#include "../support/case_scene.hpp"
#include "../support/study_run.hpp"
#include <measurements/measurement.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include "study_points.hpp"

using namespace plab;
using namespace plab::coupling;

namespace {
// The names of the choices a study gives by number (PLAB_STUDY's fields)
std::string pressure_mode_name(double i) {
    return std::vector<std::string>{"rest", "extrapolated", "extrapolated_gravity"}.at(std::size_t(i));
}
std::string drag_2d_name(double i) { return std::vector<std::string>{"cylinder", "thesis"}.at(std::size_t(i)); }
std::string buoyancy_name(double i) { return std::vector<std::string>{"pressure_gradient", "hydrostatic"}.at(std::size_t(i)); }
} // namespace

TEST_CASE("drag law: a lone sphere at low Reynolds number feels Stokes drag 3 pi mu d", "[coupling]") {
    DragInput in;
    in.dim = 3;
    in.voidage = 1.0;
    in.mu = 0.01;
    in.d = 1e-3;
    const double w = 1e-6;  // Re = 1e-4
    CHECK(drag_coefficient(in, w) == Approx(3 * M_PI * in.mu * in.d).epsilon(1e-3));
    CHECK(drag_coefficient(in, 0.0) == Approx(3 * M_PI * in.mu * in.d).epsilon(1e-3));  // finite limit at rest
}

TEST_CASE("drag law: Wen-Yu at voidage one is half Cd rho A w^2 with the sphere's or the cylinder's Cd", "[coupling]") {
    DragInput in;
    in.mu = 0.01;
    in.d = 2.5e-3;
    in.rho_f = 1000;
    const double w = 0.05, re = in.rho_f * w * in.d / in.mu;  // 12.5
    in.dim = 3;
    const double area3 = M_PI * in.d * in.d / 4;
    CHECK(drag_coefficient(in, w) * w == Approx(0.5 * sphere_drag_coefficient(re) * in.rho_f * area3 * w * w));
    in.dim = 2;
    CHECK(drag_coefficient(in, w) * w == Approx(0.5 * cylinder_drag_coefficient(re) * in.rho_f * in.d * w * w));
    // a cylinder at Re = 10 has Cd ≈ 2.8 (Tritton 1959); Schiller–Naumann 4.15 at Re = 10
    CHECK(cylinder_drag_coefficient(10) == Approx(2.8).epsilon(0.1));
    CHECK(sphere_drag_coefficient(10) == Approx(24.0 / 10 * (1 + 0.15 * std::pow(10, 0.687))));
    // crowding raises the drag: ε^-1.65 in the Wen–Yu branch, Ergun below 0.8
    in.voidage = 0.9;
    const double k09 = drag_coefficient(in, w);
    in.voidage = 1.0;
    CHECK(k09 > drag_coefficient(in, w));
    in.voidage = 0.5;
    CHECK(drag_coefficient(in, w) > k09);
}

namespace {

// A free square blob of SPH fluid (no walls, no gravity) with `solids`
// discs moving through it: only the sph and fluid_particle models act.
json blob_with_solids(int dim) {
    const double dp = 0.002, h = 1.5 * dp;
    const json sph = {{"smoothing_length", h}, {"kernel", "wendland_c2"}, {"rest_density", 1000}, {"speed_of_sound", 5.0},
                      {"viscosity", "laminar"}, {"mu", 0.01}};
    const json kernel = {{"smoothing_length", h}, {"kernel", "wendland_c2"}};
    json drag = kernel;
    drag.update({{"fluid_group", "fluid"}, {"solid_group", "solid"}, {"rest_density", 1000}, {"mu", 0.01}});
    const double mass = dim == 2 ? 1000 * dp * dp : 1000 * dp * dp * dp;
    json box_max = dim == 2 ? json{0.03, 0.03} : json{0.016, 0.016, 0.016};
    json box_min = dim == 2 ? json{0, 0} : json{0, 0, 0};
    json p1 = dim == 2 ? json{0.01, 0.012} : json{0.006, 0.007, 0.008};
    json p2 = dim == 2 ? json{0.019, 0.02} : json{0.011, 0.009, 0.006};
    json v1 = dim == 2 ? json{0.3, -0.2} : json{0.3, -0.2, 0.1};
    json v2 = dim == 2 ? json{-0.1, 0.25} : json{-0.1, 0.25, -0.2};
    return {{"dimension", dim},
            {"plugins", {"sph", "coupling_fluid_particle"}},
            {"bodies",
             {{{"type", "lattice"}, {"group", "fluid"}, {"packing", dim == 2 ? "square" : "cubic"},
               {"box", {{"min", box_min}, {"max", box_max}}}, {"radius", dp / 2}, {"spacing", dp}, {"mass", mass},
               {"fix", {"rotation"}}},
              {{"type", "ball"}, {"group", "solid"}, {"position", p1}, {"radius", 0.0012}, {"density", 2500},
               {"velocity", v1}},
              {{"type", "ball"}, {"group", "solid"}, {"position", p2}, {"radius", 0.0015}, {"density", 1500},
               {"velocity", v2}}}},
            {"contact_models",
             {{{"groups", {"fluid", "fluid"}}, {"model", "sph"}, {"properties", sph}},
              {{"groups", {"fluid", "solid"}}, {"model", "fluid_particle"}, {"properties", kernel}}}},
            {"passes",
             {{{"name", "sph_density_integration"}},
              {{"name", "sph_eos"}, {"properties", {{"rest_density", 1000}, {"speed_of_sound", 5.0}}}},
              {{"name", "fluid_particle_drag"}, {"properties", drag}}}}};
}

} // namespace

TEST_CASE("fluid-particle coupling returns the drag to the fluid: momentum conserved to round-off", "[coupling]") {
    for (int dim : {2, 3}) {
        INFO("dim " << dim);
        Simulation sim(blob_with_solids(dim));
        sim.set_quiet(true);
        World& w = sim.world();
        const int solid = w.find_group("solid");
        auto momentum = [&](bool solids_only) {
            Vec p = Vec::Zero();
            for (std::size_t i = 0; i < w.bodies.size(); ++i)
                if (!solids_only || w.bodies.group[i] == solid) p += w.bodies.mass[i] * w.bodies.velocity[i];
            return p;
        };
        double scale = 0;  // Σ m|v|: the size of the terms summed
        for (std::size_t i = 0; i < w.bodies.size(); ++i) scale += w.bodies.mass[i] * w.bodies.velocity[i].norm();
        const Vec p0 = momentum(false), solids0 = momentum(true);
        const int fx = w.fields.index("fp_force_x"), fy = w.fields.index("fp_force_y"), fz = w.fields.index("fp_force_z");
        double worst_share_sum = 0;
        for (int k = 0; k < 200; ++k) {
            w.step();
            // the shares V_f W / S add up to the pass's fluid force on each solid (eqs. 81-82)
            for (std::size_t i = 0; i < w.bodies.size(); ++i) {
                if (w.bodies.group[i] != solid) continue;
                const Vec f(w.fields.column(fx)[i], w.fields.column(fy)[i], w.fields.column(fz)[i]);
                REQUIRE(f.norm() > 0);
                worst_share_sum = std::max(worst_share_sum, (w.bodies.force[i] - f).norm() / f.norm());
            }
        }
        CHECK(worst_share_sum < 1e-12);
        // the solids slowed down: momentum went to the fluid ...
        CHECK((momentum(true) - solids0).norm() > 0.1 * solids0.norm());
        // ... and none was lost or made
        CHECK((momentum(false) - p0).norm() <= 1e-12 * scale);
        // the fluid around the solids is thinned: voidage below one
        const auto& eps = w.fields.column(w.fields.index("voidage"));
        double lowest = 1;
        for (std::size_t i = 0; i < w.bodies.size(); ++i)
            if (w.bodies.group[i] != solid) lowest = std::min(lowest, eps[i]);
        CHECK(lowest < 0.95);
    }
}

TEST_CASE("buoyancy from the SPH pressure gradient carries a disc of fluid density", "[coupling]") {
    // the quick sedimentation box with the disc made neutrally buoyant: at
    // rest in hydrostatic fluid the net vertical force is weight - V ∇p
    json scene = testing_support::case_scene("sedimentation", {{"variables.dp", 0.0025}, {"variables.rho_s", 1000}});
    scene.erase("commands");
    Simulation sim(scene);
    sim.set_quiet(true);
    World& w = sim.world();
    w.prepare();
    const int disc = w.find_group("disc");
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        if (w.bodies.group[i] != disc) continue;
        const double weight = w.bodies.mass[i] * 9.81;
        INFO("net force " << w.bodies.force[i].transpose() << " N, weight " << weight << " N");
        CHECK(std::fabs(w.bodies.force[i].y()) < 0.05 * weight);
        CHECK(std::fabs(w.bodies.force[i].x()) < 0.05 * weight);
    }
}

TEST_CASE("quick sedimentation settles at the reference terminal velocity within 10 %", "[coupling]") {
    using namespace testing_support;  // the quick version of `plab validate sedimentation`
    const auto sim = run_scene(case_scene("sedimentation", {{"variables.dp", 0.0025}, {"variables.end_time", 0.7}}));
    INFO("terminal velocity " << metric(*sim, "terminal_velocity") << " m/s, " << sim->world().step_count << " steps");
    // |v - 0.0555| / 0.0555, v the mean over 0.35-0.66 s (Glowinski's plateau)
    CHECK(metric(*sim, "terminal_velocity", "error") < 0.10);
    // it falls monotonically after release: no rebound, no oscillation of the drag
    CHECK(metric(*sim, "fall") > 0.015);
}

// Not part of the test run (hidden tag): the resolution and drag-law study
// of docs/coupling.md, `build/tests/plab_tests "[.sedimentation_study]"`.
TEST_CASE("sedimentation study: terminal velocity against d/dp and the 2D drag reading", "[.sedimentation_study]") {
    using namespace testing_support;
    // e.g. PLAB_STUDY="0.0025:0:0.45,0.00125:1:0.8" = dp:drag_2d:end[:h/dp[:buoyancy[:h_coupling]]]
    for (const auto& v : study_points("0.0025:0:0.8,0.002:0:0.8,0.00125:0:0.8,0.001:0:0.8",
                                      {0.0025, 0, 0.8, 2.0, 0, 0.006})) {  // h_c 0: the fluid's kernel
        const auto sim = run_scene(case_scene("sedimentation", {{"variables.dp", v[0]}, {"variables.drag_2d", drag_2d_name(v[1])},
                                                                {"variables.end_time", v[2]}, {"variables.h_over_dp", v[3]},
                                                                {"variables.buoyancy", buoyancy_name(v[4])}, {"variables.coupling_length", v[5]}}));
        std::printf("h_c %.4f dp %.5f d/dp %.2f h/dp %.2f drag_2d %d buoyancy %d: terminal %.4f m/s (err %+.1f %%), RMS v %.4f m/s, "
                    "RMS y %.4f m, %llu steps, %.0f s CPU\n",
                    v[5], v[0], 0.0025 / v[0], v[3], int(v[1]), int(v[4]), metric(*sim, "terminal_velocity"),
                    100 * (metric(*sim, "terminal_velocity") / metric(*sim, "terminal_velocity", "reference") - 1),
                    metric(*sim, "velocity_rms", "error"), metric(*sim, "height_rms", "error"),
                    static_cast<unsigned long long>(sim->world().step_count), sim->summary()["cpu_seconds"].get<double>());
        if (std::getenv("PLAB_STUDY_HISTORY")) {
            const auto t = sim->history("time"), y = sim->history("disc_y"), vy = sim->history("disc_vy"),
                       eps = sim->history("voidage"), fy = sim->history("fluid_force_y"), K = sim->history("drag_coefficient");
            for (std::size_t k = 0; k < t.size(); k += 200)
                std::printf("  t %.4f y %.5f v %.5f eps_p %.3f F_y %.5f K %.4f\n", t[k], y[k], vy[k], eps[k], fy[k], K[k]);
        }
        std::fflush(stdout);
    }
}

// Not part of the test run (hidden tag): the elastic gate case's scene
// (validation/elastic_gate) at chosen resolutions,
// PLAB_STUDY="dp:R:end[:pressure_mode]", comma-separated.
TEST_CASE("elastic gate study: free-end displacement against Antoci 2007", "[.elastic_gate_study]") {
    using namespace testing_support;
    for (const auto& v : study_points("0.0025:0.000625:0.4", {0.0025, 0.000625, 0.4, 1})) {
        Simulation sim(case_scene("elastic_gate", {{"variables.dp", v[0]}, {"variables.R", v[1]}, {"variables.end_time", v[2]},
                                                   {"variables.pressure_mode", pressure_mode_name(v[3])}}),
                       case_dir("elastic_gate"));
        const std::string stopped = run_study(sim);
        std::printf("dp %.5f R %.5f mode %d: %d fluid, %d gate balls; x RMS %.1f %% of peak, peak %.4f m at %.3f s "
                    "(exp %.4f at %.3f); y RMS %.1f %%; %.0f broken; %llu steps, %.0f s CPU%s\n",
                    v[0], v[1], int(v[3]), group_count(sim, "fluid"), group_count(sim, "gate"), 100 * metric(sim, "x_rms", "error"),
                    metric(sim, "peak_x"), metric(sim, "peak_time"), metric(sim, "peak_x", "reference"),
                    metric(sim, "peak_time", "reference"), 100 * metric(sim, "y_rms", "error"), metric(sim, "broken"),
                    static_cast<unsigned long long>(sim.world().step_count), sim.summary()["cpu_seconds"].get<double>(),
                    stopped.c_str());
        if (std::getenv("PLAB_STUDY_HISTORY")) {
            const std::vector<double> t = sim.history("time"), dx = sim.history("tip_dx"), dy = sim.history("tip_dy");
            for (std::size_t k = 0; k < t.size(); k += 100) std::printf("  t %.4f dx %.5f dy %.5f\n", t[k], dx[k], dy[k]);
        }
        std::fflush(stdout);
    }
}

TEST_CASE("a structure floor in the SPH sums carries the weight of the water above it", "[coupling]") {
    // water 0.1 x 0.1 m on a floor of fixed structure balls (not boundary
    // balls: their SPH state comes from structure_sph_state), side walls of
    // boundary balls; at rest in the hydrostatic state the floor's share of
    // the fluid force is the water's weight (the walls take only horizontal load)
    const double dp = 0.005, db = dp / 2, h = 1.25 * dp, c0 = 10 * std::sqrt(2 * 9.81 * 0.1), g = 9.81;
    const double t = std::ceil(2 * h / db) * db;
    const json sph = {{"smoothing_length", h}, {"kernel", "wendland_c2"}, {"rest_density", 1000}, {"speed_of_sound", c0},
                      {"viscosity", "artificial"}, {"alpha", 0.1}};
    const json eos = {{"rest_density", 1000}, {"speed_of_sound", c0}, {"gamma", 7.0}};
    json eos_pass = eos, wall_pass = eos, floor_pass = eos;
    eos_pass.update({{"boundary_group", "boundary"}, {"hydrostatic_gravity", g}, {"surface_level", 0.1}});
    wall_pass.update({{"smoothing_length", h}, {"kernel", "wendland_c2"}, {"boundary_group", "boundary"}, {"gravity_y", -g}});
    floor_pass.update({{"smoothing_length", h}, {"kernel", "wendland_c2"}, {"structure_group", "floor"}, {"fluid_group", "fluid"},
                       {"pressure_mode", "extrapolated"}, {"gravity_y", -g}});
    json floor = testing_support::boundary_block(-t, -t, 0.1 + t, 0, db);
    floor["group"] = "floor";
    const json scene = {
        {"dimension", 2},
        {"gravity", {0, -g}},
        {"plugins", {"sph", "coupling_fluid_structure"}},
        {"bodies",
         {{{"type", "lattice"}, {"group", "fluid"}, {"packing", "square"}, {"box", {{"min", {0, 0}}, {"max", {0.1, 0.1}}}},
           {"radius", dp / 2}, {"spacing", dp}, {"mass", 1000 * dp * dp}, {"fix", {"rotation"}}},
          testing_support::boundary_block(-t, 0, 0, 0.12, db), testing_support::boundary_block(0.1, 0, 0.1 + t, 0.12, db), floor}},
        {"contact_models",
         {{{"groups", {"fluid", "fluid"}}, {"model", "sph"}, {"properties", sph}},
          {{"groups", {"fluid", "boundary"}}, {"model", "sph"}, {"properties", sph}},
          {{"groups", {"fluid", "floor"}}, {"model", "sph"}, {"properties", sph}}}},
        {"passes",
         {{{"name", "sph_density_integration"}, {"properties", {{"boundary_group", "boundary"}}}},
          {{"name", "sph_eos"}, {"properties", eos_pass}},
          {{"name", "sph_wall_pressure"}, {"properties", wall_pass}},
          {{"name", "structure_sph_state"}, {"properties", floor_pass}}}}};
    for (const std::string mode : {"extrapolated", "rest"}) {
        json s = scene;
        s["passes"][3]["properties"]["pressure_mode"] = mode;
        Simulation sim(s);
        sim.set_quiet(true);
        World& w = sim.world();
        w.prepare();
        const int fluid = w.find_group("fluid"), floor_group = w.find_group("floor");
        double weight = 0, on_floor = 0;
        for (std::size_t i = 0; i < w.bodies.size(); ++i) {
            if (w.bodies.group[i] == fluid) weight += w.bodies.mass[i] * g;
            if (w.bodies.group[i] == floor_group) on_floor += w.bodies.force[i].y() + w.bodies.mass[i] * g;
        }
        INFO("pressure_mode " << mode << ": floor carries " << on_floor << " N/m of " << weight << " N/m");
        // extrapolated pressure: within 5 %; the thesis's p = 0 (rest) pushes with about half
        if (mode == "extrapolated") CHECK(-on_floor == Approx(weight).epsilon(0.05));
        else CHECK(-on_floor < 0.75 * weight);
    }
}

// Not part of the test run (hidden tag): the gate fracture case's scene
// (validation/gate_fracture) at chosen settings,
// PLAB_STUDY="dp:R:end:strength[:pressure_mode[:density_band]]", comma-separated; band 0: the scene's (5 %).
TEST_CASE("gate fracture study", "[.gate_fracture_study]") {
    using namespace testing_support;
    for (const auto& v : study_points("0.005:0.000833333:0.15:1.15e6", {0.005, 0.000833333, 0.15, 1.15e6, 2, 0})) {
        std::vector<std::pair<std::string, json>> sets = {{"variables.dp", v[0]}, {"variables.R", v[1]}, {"variables.end_time", v[2]},
                                                          {"variables.strength", v[3]}, {"variables.pressure_mode", pressure_mode_name(v[4])}};
        if (v[5] > 0) sets.emplace_back("variables.density_band", v[5]);
        Simulation sim(case_scene("gate_fracture", sets), case_dir("gate_fracture"));
        const std::string stopped = run_study(sim);
        std::printf("dp %.4f R %.5f strength %.3g: %.0f of %.0f broken, first at %.3f s y %.4f mode %.0f; x [%.4f, %.4f], min y %.4f, "
                    "wall clearance %.4f m; %llu steps, %.0f s CPU%s\n",
                    v[0], v[1], v[3], metric(sim, "broken"), metric(sim, "bonds"), metric(sim, "first_break_time"),
                    metric(sim, "first_break_y"), metric(sim, "first_break_mode"), metric(sim, "gate_min_x"), metric(sim, "gate_max_x"),
                    metric(sim, "gate_min_y"), metric(sim, "wall_clearance"), static_cast<unsigned long long>(sim.world().step_count),
                    sim.summary()["cpu_seconds"].get<double>(), stopped.c_str());
        std::fflush(stdout);
    }
}

namespace {

// The largest stresses of the intact bonds now (eqs. 49-50 in 2D, from the
// bond force and moment linear_pbond keeps in its history), for the fpsi study.
struct BondStress {
    double sigma_axial = 0;  // largest Fn/A over the bonds (eq. 49 with β̄ = 0), Pa
    double sigma = 0;        // largest Fn/A + |Mb| R/I (β̄ = 1), Pa
    double tau = 0;          // largest |Fs|/A (eq. 50, 2D), Pa
    double x = 0, y = 0;     // midpoint of the bond with the largest sigma, m
};

BondStress bond_stress(const World& w) {
    BondStress b;
    for (std::size_t m = 0; m < w.model_count(); ++m) {
        const ModelView inst = w.model(m);
        if (inst.model() != "linear_pbond") continue;
        const double rmul = inst.property("pb_rmul");
        const int fn_slot = inst.history_slot("bond_normal_force"), fs_slot = inst.history_slot("bond_shear_force_x"),
                  m_slot = inst.history_slot("bond_moment_x");
        const ContactTable c = inst.balls();
        for (std::size_t k = 0; k < c.size(); ++k) {
            const double* h = c.history(k);
            if (!c.bonded(k)) continue;
            const std::size_t i = c.end1(k), j = c.end2(k);
            const double r = rmul * std::min(w.bodies.radius[i], w.bodies.radius[j]);
            const double area = 2 * r, inertia = 2 * r * r * r / 3;  // 2D, unit thickness (eq. 39)
            const double axial = h[fn_slot] / area;
            const double moment = std::sqrt(h[m_slot] * h[m_slot] + h[m_slot + 1] * h[m_slot + 1] + h[m_slot + 2] * h[m_slot + 2]);
            const double shear = std::sqrt(h[fs_slot] * h[fs_slot] + h[fs_slot + 1] * h[fs_slot + 1] + h[fs_slot + 2] * h[fs_slot + 2]);
            b.sigma_axial = std::max(b.sigma_axial, axial);
            b.tau = std::max(b.tau, shear / area);
            if (axial + moment * r / inertia > b.sigma) {
                b.sigma = axial + moment * r / inertia;
                b.x = 0.5 * (w.bodies.position[i].x() + w.bodies.position[j].x());
                b.y = 0.5 * (w.bodies.position[i].y() + w.bodies.position[j].y());
            }
        }
    }
    return b;
}

// The plate's top ball nearest its mid-line (x = mid_x).
std::size_t plate_tip(const World& w, int plate, double mid_x) {
    std::size_t tip = w.bodies.size();
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        if (w.bodies.group[i] != plate) continue;
        if (tip == w.bodies.size()) { tip = i; continue; }
        const Vec &x = w.bodies.position[i], &top = w.bodies.position[tip];
        if (x.y() > top.y() + 1e-9 || (x.y() > top.y() - 1e-9 && std::fabs(x.x() - mid_x) < std::fabs(top.x() - mid_x))) tip = i;
    }
    return tip;
}

} // namespace

// Not part of the test run (hidden tag): fpsi at chosen settings with the
// structure's largest bond stresses sampled (default every 2 ms; docs/coupling.md),
// PLAB_STUDY="dp:R:end:strength[:pressure_mode[:pb_mcf[:probe interval[:density band]]]]", comma-separated;
// strength 1e9 for unbreakable bonds.
TEST_CASE("fpsi study: bond stresses and the first break", "[.fpsi_study]") {
    using namespace testing_support;
    for (const auto& v : study_points("0.005:0.000833333:0.1:1e9", {0.005, 0.000833333, 0.1, 1e9, 2, 0, 0.002, 0})) {
        json scene = case_scene("fpsi", {{"variables.dp", v[0]}, {"variables.R", v[1]}, {"variables.end_time", v[2]},
                                         {"variables.bond_strength", v[3]}, {"variables.pressure_mode", pressure_mode_name(v[4])},
                                         {"variables.moment_factor", v[5]}, {"variables.density_band", v[7] > 0 ? v[7] : 0.05}});
        scene["commands"].erase(2);  // bond and clamp; the test steps it, probing on the way
        Simulation sim(scene);
        sim.set_quiet(true);
        sim.run();
        World& w = sim.world();
        const int plate = w.find_group("structure");
        const std::size_t tip = plate_tip(w, plate, 0.05 + 0.0025);
        const double tip_x0 = w.bodies.position[tip].x();
        const auto measure = [&](const char* name, const json& with) { return measurements().at(name).make(Node(with, "with"), w); };
        const json on_plate = {{"group", "structure"}};
        const Measurement pieces = measure("fragments", on_plate), largest = measure("largest_fragment", on_plate),
                          fell_apart = measure("fragmented_at", on_plate);
        std::vector<std::string> table;
        for (double next_probe = 0; w.time < v[2];) {
            sim.cycle(1);
            if (v[6] <= 0 || w.time < next_probe) continue;
            const BondStress b = bond_stress(w);
            char row[200];
            std::snprintf(row, sizeof row, "  %.3f   %8.2f   %8.2f (%.4f, %.4f)   %8.2f   %7.3f   %4zu   %3.0f (%.0f)\n", w.time,
                          b.sigma_axial / 1e3, b.sigma / 1e3, b.x, b.y, b.tau / 1e3, (w.bodies.position[tip].x() - tip_x0) * 1e3,
                          w.bond_breaks.size(), pieces(w), largest(w));
            table.push_back(row);
            next_probe += v[6];
        }
        const std::size_t broken = w.bond_breaks.size();
        const BondBreak first = broken ? w.bond_breaks.front() : BondBreak{};
        std::printf("dp %.4f R %.6f strength %.3g mode %d mcf %.2f: %zu of %zu broken, first at %.4f s (%.4f, %.4f) %s; "
                    "in pieces from %.4f s; %.0f pieces (largest %.0f); %llu steps\n",
                    v[0], v[1], v[3], int(v[4]), v[5], broken, broken + intact_bonds(w), broken ? first.time : -1.0,
                    first.point.x(), first.point.y(), first.mode == PLAB_BREAK_SHEAR ? "shear" : "tension", fell_apart(w),
                    pieces(w), largest(w), static_cast<unsigned long long>(w.step_count));
        std::printf("  t (s)   max Fn/A (kPa)  max sigma b=1 (kPa) at (x, y)   max tau (kPa)  tip dx (mm)  broken  pieces (largest)\n");
        for (const std::string& row : table) std::fputs(row.c_str(), stdout);
        std::fflush(stdout);
    }
}
