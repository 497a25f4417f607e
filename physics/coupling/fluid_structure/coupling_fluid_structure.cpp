// Fluid–structure coupling of SPH fluid and bonded DEM structures (thesis
// §4.2–4.3): the structure's balls join the SPH sums as particles whose
// density and pressure are not evolved by the continuity equation; the `sph`
// contact model, assigned to fluid × structure, then gives each pair equal
// and opposite forces (Newton's third law, thesis §4.2), and the bonds
// (`linear_pbond`) carry the load through the structure.
//
// This pass (phase RATES_DONE, stage 25: after sph_density_integration and
// sph_eos have touched every ball, before the force stage) sets the SPH state
// of the structure's balls, `pressure_mode` (index 0, 1, 2 to the pass):
//   rest (0)  thesis: ρ = ρ0, p = 0 at all times;
//   extrapolated (1)  extrapolated from the fluid as for a moving wall (Adami et al. 2012,
//      Islam eqs. 10–11): p_s = (Σ_f p_f W_sf + (g - a_s)·Σ_f ρ_f (x_s - x_f) W_sf) / Σ_f W_sf,
//      ρ_s = ρ0 (p_s/B + 1)^(1/γ), with a_s the ball's acceleration of the
//      last cycle (force / mass). A structure ball with no fluid neighbour
//      gets p = 0, ρ = ρ0;
//   extrapolated_gravity (2)  as 1 without the ball's acceleration, (g·(x_s - x_f)) only. A lattice
//      ball's F/m is dominated by its bond vibration (periods of ~0.1 ms,
//      accelerations of 1e4 m/s² against the surface's few m/s²), which mode 1
//      turns into pressure noise of ρ |a| h ≈ 3e4 Pa — enough to pull a
//      free-standing gate's balls below 0.75 ρ0 (gate_fracture, unbreakable
//      bonds, R 0.625 mm: unstable at 19 ms in mode 1, stable in mode 2).
//      The surface's own acceleration adds ρ a h ≈ 10 Pa: neglected.
// With p = 0 the structure pushes the fluid with only the fluid's own p/ρ²
// term, half of what holds it back at rest (docs/sph.md), so the fluid
// presses into the structure; mode 1 removes that.
#include <plab/sph/kernels.hpp>
#include <plab/sph/material.hpp>

#include <plab/pass.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr const char* pressure_mode_names[] = {"rest", "extrapolated", "extrapolated_gravity"};

struct StructureSphState {
    static constexpr const char* name = "structure_sph_state";
    static constexpr const char* doc =
        "SPH density and pressure of structure balls that join the SPH sums (thesis 4.2-4.3): rho0 and p = 0 "
        "(pressure_mode rest, thesis), or extrapolated from the fluid as for a moving wall (pressure_mode extrapolated, Adami 2012 / "
        "Islam eqs. 10-11 with the ball's acceleration). Runs after sph_eos; assign `sph` to fluid x structure.";
    static constexpr uint32_t phase = PLAB_PHASE_RATES_DONE;
    static constexpr uint32_t stage = 25;  // after sph_eos (10) and sph_wall_pressure (20)
    // h, the kernel, rho0, c0 and gamma are the fluid's (the SPH package's material)
    using material = plab::sph::FluidMaterial;
    enum Prop : int {
        structure_group, fluid_group, pressure_mode, smoothing_length, kernel, rest_density, speed_of_sound, gamma, gx, gy, gz,
        prop_count
    };
    static constexpr plab_property_desc properties[] = {
        plab::prop::group("structure_group", "group of the structure balls", "the balls given an SPH state"),
        plab::prop::group("fluid_group", "group of the SPH fluid", "the fluid the state is extrapolated from"),
        plab::prop::choice("pressure_mode", "structure pressure", pressure_mode_names, 1,
         "rest: rho0, p = 0 (thesis); extrapolated: from the fluid with the ball's acceleration; extrapolated_gravity: "
         "from the fluid with gravity only (for lattices whose balls vibrate: free-standing or breaking structures)"),
        plab::sph::fluid::smoothing_length, plab::sph::fluid::kernel, plab::sph::fluid::rest_density,
        plab::sph::fluid::speed_of_sound, plab::sph::fluid::gamma,
        plab::prop::number("gravity_x", "gravity, x", "m/s2", 0.0, -inf, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE, "the scene's gravity"),
        plab::prop::number("gravity_y", "gravity, y", "m/s2", 0.0, -inf, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE, "the scene's gravity"),
        plab::prop::number("gravity_z", "gravity, z", "m/s2", 0.0, -inf, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE, "the scene's gravity"),
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");
    enum Field : int { density, pressure };
    static constexpr plab_field_desc fields[] = {plab::field_desc("sph_density", "kg/m3", 1000.0), plab::field_desc("sph_pressure", "Pa", 0.0)};

    explicit StructureSphState(const double* p)
        : structure_(int(p[structure_group])), fluid_(int(p[fluid_group])), extrapolate_(int(p[pressure_mode]) >= 1),
          ball_acceleration_(int(p[pressure_mode]) == 1),
          kind_(plab::sph::KernelKind(int(p[kernel]))), h_(p[smoothing_length]), rho0_(p[rest_density]),
          gamma_(p[gamma]), b_(p[rest_density] * p[speed_of_sound] * p[speed_of_sound] / p[gamma]),
          g_{p[gx], p[gy], p[gz]} {}

    void run(const plab_pass_view& v) {
        double* rho = v.fields[density];
        double* p = v.fields[pressure];
        if (extrapolate_) extrapolate(v);
        for (uint32_t i = 0; i < v.body_count; ++i) {
            if (v.group[i] != structure_) continue;
            p[i] = extrapolate_ && weights_[i] > 0 ? weighted_[i] / weights_[i] : 0.0;
            rho[i] = rho0_ * std::pow(std::max(p[i] / b_ + 1.0, 0.0), 1.0 / gamma_);
        }
    }

private:
    // Σ_f (p_f + ρ_f (g - a_s)·(x_s - x_f)) W_sf and Σ_f W_sf over the fluid
    // neighbours f of each structure ball s.
    void extrapolate(const plab_pass_view& v) {
        const plab::sph::Kernel W{kind_, int(v.dim), h_};
        weighted_.assign(v.body_count, 0.0);
        weights_.assign(v.body_count, 0.0);
        const double* rho = v.fields[density];
        const double* p = v.fields[pressure];
        for (uint32_t k = 0; k < v.contact_count; ++k) {
            if (v.contact_end2_is_wall[k]) continue;
            int32_t s = v.contact_end1[k], f = v.contact_end2[k];
            if (v.group[f] == structure_) std::swap(s, f);
            if (v.group[s] != structure_ || v.group[f] != fluid_) continue;
            const plab::Vec3 x_sf = plab::separation(v, f, s);  // x_s - x_f (also across a periodic boundary)
            const double d[3] = {x_sf.x, x_sf.y, x_sf.z};
            double r2 = 0;
            for (int c = 0; c < 3; ++c) r2 += d[c] * d[c];
            const double w = W.value(std::sqrt(r2));
            double acc_term = 0;  // (g - a_s)·(x_s - x_f), a_s = F_s/m_s of the last cycle
            for (int c = 0; c < 3; ++c)
                acc_term += (g_[c] - (ball_acceleration_ ? v.force[3 * s + c] / v.mass[s] : 0.0)) * d[c];
            weighted_[s] += (p[f] + rho[f] * acc_term) * w;
            weights_[s] += w;
        }
    }

    int structure_, fluid_;
    bool extrapolate_, ball_acceleration_;
    plab::sph::KernelKind kind_;
    double h_, rho0_, gamma_, b_;
    double g_[3];
    std::vector<double> weighted_, weights_;
};

} // namespace

PLAB_PLUGIN(plab::add_pass<StructureSphState>(r))
