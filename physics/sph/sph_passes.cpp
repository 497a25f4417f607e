// Passes of weakly compressible SPH (companions of the `sph` contact model,
// in one library with it, plab_sph), all in phase RATES_DONE: after the
// host's rates stage, where the model accumulated the continuity sum
// (thesis eq. 7) at the new positions and half-step velocities, and before
// the force stage. In stage order:
//   sph_density_integration  ρ += dt dρ/dt — the density is then in step with
//                            the positions (integrating after the forces
//                            instead lags the pressure a step: unstable).
//   sph_eos                  Tait equation of state (thesis eq. 80; Islam
//                            eq. 4) p = B((ρ/ρ0)^γ - 1), B = ρ0 c0²/γ. At its
//                            first run (t = 0) it also sets the initial
//                            density: ρ0 for boundary balls, and for fluid
//                            balls the hydrostatic profile by the inverse EOS
//                            ρ = ρ0 (1 + ρ0 g (H - y)/B)^(1/γ) (thesis §5.2).
//   sph_wall_pressure        boundary-ball pressure from the fluid (Islam
//                            eqs. 10–11), optional; with `no_slip` also the
//                            wall velocity seen by the viscous terms (Adami
//                            et al. 2012).
// Fixed boundary balls (thesis §2.2.4) keep ρ = ρ0 (and p = 0 without
// sph_wall_pressure): the passes skip the group whose index is
// `boundary_group` (groups are numbered in the order the scene first names
// them, bodies before walls; -1: none). The pass view carries no fixity,
// hence a group rather than "fixed DOFs".
#include <plab/sph/kernels.hpp>
#include <plab/sph/material.hpp>

#include <plab/pass.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// The fluid's constants (rho0, c0, gamma, h, the kernel) are the SPH
// package's material, sph_fluid (<plab/sph/material.hpp>): every pass that
// uses some takes them from it, as the sph model does, so a scene material
// states them once.
using plab::sph::FluidMaterial;
namespace fluid = plab::sph::fluid;

constexpr plab_property_desc boundary_group_desc = plab::prop::optional_group(
    "boundary_group", "group of fixed boundary balls", "their density stays rho0 (thesis 2.2.4); none: no boundary balls");

struct SphEos {
    static constexpr const char* name = "sph_eos";
    static constexpr const char* doc =
        "Tait equation of state p = B((rho/rho0)^gamma - 1), B = rho0 c0^2/gamma (thesis eq. 80). At its first run "
        "sets the initial density: rho0 on boundary balls, hydrostatic (inverse EOS) on the others when "
        "hydrostatic_gravity > 0.";
    static constexpr uint32_t phase = PLAB_PHASE_RATES_DONE;
    static constexpr uint32_t stage = 10;  // after sph_density_integration
    using material = FluidMaterial;
    enum Prop : int {
        rest_density, speed_of_sound, gamma, boundary_group, hydrostatic_gravity, surface_level, density_band,
        initial_density, expected_max_speed, prop_count
    };
    static constexpr plab_property_desc properties[] = {
        fluid::rest_density, fluid::speed_of_sound, fluid::gamma,
        boundary_group_desc,
        plab::prop::number("hydrostatic_gravity", "gravity for the initial hydrostatic density", "m/s2", 0.0, 0.0, inf,
         PLAB_MAX_EXCLUSIVE, "g of the initial profile; 0: uniform rho0"),
        plab::prop::number("surface_level", "free-surface height H of the initial profile", "m", 0.0, -inf, inf,
         PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE, "vertical coordinate (y in 2D, z in 3D) of the free surface"),
        plab::prop::number("density_band", "largest |rho/rho0 - 1| of a fluid ball", "1", 0.05, 0.0, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
         "the run stops (last good state kept) when a fluid density leaves rho0 (1 +- band); the density error grows "
         "as (v/c0)^2 and g H/c0^2: 0.05 passes c0 = 5 x the largest speed and stops 3 x (docs/stability.md)"),
        plab::prop::boolean("initial_density", "set the initial density", true,
         "true: at the first run rho0 / the hydrostatic profile (a state for the continuity equation or the normalised "
         "summation); false: keep what the density pass computed (plain summation density, a function of positions)"),
        fluid::expected_max_speed,
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");
    enum Field : int { density, pressure };
    static constexpr plab_field_desc fields[] = {plab::field_desc("sph_density", "kg/m3", 1000.0), plab::field_desc("sph_pressure", "Pa", 0.0)};

    explicit SphEos(const double* p)
        : rho0_(p[rest_density]), gamma_(p[gamma]), b_(p[rest_density] * p[speed_of_sound] * p[speed_of_sound] / p[gamma]),
          boundary_(int(p[boundary_group])), g_(p[hydrostatic_gravity]), surface_(p[surface_level]),
          c0_(p[speed_of_sound]), band_(p[density_band]), expected_(p[expected_max_speed]),
          initialised_(int(p[initial_density]) == 0),
          whole_gamma_(gamma_ == std::floor(gamma_) && gamma_ <= 64 ? unsigned(gamma_) : 0) {}

    void run(const plab_pass_view& v) {
        if (!initialised_) initialise(v);
        double* rho = v.fields[density];
        double* p = v.fields[pressure];
        bool outside = false;  // some fluid ball outside the band (or NaN)
#pragma omp parallel for schedule(static) reduction(|| : outside) if (v.body_count >= 4096)
        for (std::int64_t i = 0; i < std::int64_t(v.body_count); ++i) {
            const double ratio = rho[i] / rho0_;
            p[i] = b_ * (power(ratio) - 1.0);
            outside = outside || (!(std::fabs(ratio - 1.0) <= band_) && v.group[i] != boundary_);
        }
        if (outside) throw plab::UnstableState{band_message(v, worst_ball(v))};
    }

    // Checkpoints carry whether the initial density was set: a restarted
    // run must not reset the densities to the hydrostatic profile.
    // Bytes: format version 1, then the flag.
    std::vector<unsigned char> save_state() const { return {1, static_cast<unsigned char>(initialised_ ? 1 : 0)}; }
    bool load_state(const unsigned char* data, std::size_t size) {
        if (size != 2 || data[0] != 1 || data[1] > 1) return false;
        initialised_ = data[1] == 1;
        return true;
    }

private:
    // (rho/rho0)^gamma of eq. 80. A whole gamma (7 for water) by repeated
    // squaring, x^7 = x * x^2 * x^4, four multiplications instead of
    // std::pow's exp(gamma log x): within a few units in the last place of
    // pow (the pressures change by rounding only), a tenth of the cost.
    double power(double x) const {
        if (whole_gamma_ == 0) return std::pow(x, gamma_);
        double result = 1.0, square = x;
        for (unsigned e = whole_gamma_; e != 0; e >>= 1) {
            if (e & 1u) result *= square;  // (1 x square is exact)
            square *= square;
        }
        return result;
    }

    // The fluid ball furthest outside the band (a NaN density counts as
    // outside), searched only once the band is left.
    uint32_t worst_ball(const plab_pass_view& v) const {
        const double* rho = v.fields[density];
        uint32_t worst = 0;
        double worst_dev = band_;
        for (uint32_t i = 0; i < v.body_count; ++i) {
            const double dev = std::fabs(rho[i] / rho0_ - 1.0);
            if (!(dev <= worst_dev) && v.group[i] != boundary_) { worst = i; worst_dev = dev; }  // NaN too
        }
        return worst;
    }

    // Names the ball, the density against the band and the likely cause:
    // a speed of sound too low for the flow (the Mach number sets the
    // density error) or a step above the CFL limit. The advice is the rule
    // the material applies: c0 >= 10 x the larger of the expected and the
    // observed largest speed (Monaghan 1994).
    std::string band_message(const plab_pass_view& v, uint32_t i) const {
        double v_max = 0;
        for (uint32_t j = 0; j < v.body_count; ++j) {
            const double* u = v.velocity + 3 * j;
            v_max = std::max(v_max, std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]));
        }
        const double need = 10.0 * std::max(v_max, expected_);
        char expected[200] = "";
        if (expected_ > 0)
            std::snprintf(expected, sizeof expected, "; the material's expected_max_speed is %.4g m/s (c0 = %.3g x it)%s",
                          expected_, c0_ / expected_,
                          v_max > expected_ ? ": the flow ran faster than expected, raise expected_max_speed" : "");
        char buf[900];
        std::snprintf(buf, sizeof buf,
                      "sph_density: ball index %u has density %.6g kg/m3 = %.4g rho0, outside rho0 (1 +- %.3g) "
                      "(sph_eos density_band); likely cause: speed of sound c0 = %.4g m/s too low (the density error "
                      "grows as (v/c0)^2 and g H/c0^2; now c0 = %.3g x the largest speed %.4g m/s%s; use c0 >= 10 x "
                      "the largest speed = %.4g m/s: in the material \"speed_of_sound\": \"auto\" with "
                      "\"expected_max_speed\" (a dam break of height H: {\"dam_break_height\": H}, 2 sqrt(g H); a "
                      "moving wall: {\"speed\": v})), or a timestep above the CFL limit",
                      i, v.fields[density][i], v.fields[density][i] / rho0_, band_, c0_, v_max > 0 ? c0_ / v_max : inf,
                      v_max, expected, need);
        return buf;
    }

    // Inverse of eq. 80 for p = ρ0 g (H - y): the particles start in
    // hydrostatic balance instead of ringing from a uniform density.
    void initialise(const plab_pass_view& v) {
        const int up = int(v.dim) - 1;  // y in 2D, z in 3D
        double* rho = v.fields[density];
        for (uint32_t i = 0; i < v.body_count; ++i) {
            rho[i] = rho0_;
            if (v.group[i] == boundary_ || g_ <= 0) continue;
            const double p = rho0_ * g_ * (surface_ - v.position[3 * i + up]);
            rho[i] = rho0_ * std::pow(std::max(1.0 + p / b_, 0.0), 1.0 / gamma_);
        }
        initialised_ = true;
    }

    double rho0_, gamma_, b_;
    int boundary_;
    double g_, surface_, c0_, band_, expected_;
    bool initialised_;
    unsigned whole_gamma_;  // gamma when it is a whole number up to 64, else 0 (std::pow)
};

// Boundary pressure by extrapolation from the fluid (Islam eqs. 10–11,
// after Adami et al. 2012), an alternative to the thesis' boundary balls at
// p = 0: each boundary ball w takes
//   p_w = (Σ_f p_f W_wf + g·Σ_f ρ_f (x_w - x_f) W_wf) / Σ_f W_wf,
//   ρ_w = ρ0 (p_w/B + 1)^(1/γ),
// over its fluid neighbours f, with g - a_w in place of g (Islam eq. 10):
// a_w is the wall ball's acceleration, from the change of its prescribed
// velocity since the previous step, a_w = (v_w - v_w,prev)/dt (zero for a
// wall at rest or at constant velocity). A re-evaluation (dt = 0: start, a
// `set`, a restart) keeps the stored a_w and takes the velocity as the new
// reference, so a velocity set by a command is a new motion, not an
// infinite acceleration, and a restart sees the a_w of the run it continues.
// With p_w = 0 the wall pushes with half the pressure the fluid needs and
// the first fluid row is over-compressed (docs/sph.md).
// No-slip (Adami et al. 2012, eq. 22): the viscous terms see the wall ball
// at v_w = 2 v_prescribed - ṽ_w, ṽ_w = Σ_f v_f W_wf / Σ_f W_wf, so the
// velocity interpolated to the wall surface is the wall's own. The pass
// stores v_w - v_prescribed = v_prescribed - ṽ_w in the field
// sph_wall_velocity_correction, which the sph model adds to the ball's
// velocity in its viscous terms only.
struct SphWallPressure {
    static constexpr const char* name = "sph_wall_pressure";
    static constexpr const char* doc =
        "Boundary-ball pressure extrapolated from fluid neighbours with the hydrostatic correction (Islam eqs. 10-11), "
        "density by the inverse EOS. Runs after sph_eos.";
    static constexpr uint32_t phase = PLAB_PHASE_RATES_DONE;
    static constexpr uint32_t stage = 20;  // after sph_eos
    using material = FluidMaterial;
    enum Prop : int {
        smoothing_length, kernel, rest_density, speed_of_sound, gamma, boundary_group, gx, gy, gz, no_slip,
        wall_acceleration, prop_count
    };
    static constexpr plab_property_desc properties[] = {
        fluid::smoothing_length, fluid::kernel, fluid::rest_density, fluid::speed_of_sound, fluid::gamma,
        boundary_group_desc,
        plab::prop::number("gravity_x", "gravity, x", "m/s2", 0.0, -inf, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE, "the scene's gravity"),
        plab::prop::number("gravity_y", "gravity, y", "m/s2", 0.0, -inf, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE, "the scene's gravity"),
        plab::prop::number("gravity_z", "gravity, z", "m/s2", 0.0, -inf, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE, "the scene's gravity"),
        plab::prop::boolean("no_slip", "no-slip walls", true,
         "true: viscous terms see the wall at 2 v_wall - (fluid velocity interpolated to the wall ball) (Adami 2012); "
         "false: at the wall ball's own velocity"),
        plab::prop::boolean("wall_acceleration", "wall acceleration term", true,
         "true: g - a_w in the extrapolation (Islam eq. 10), a_w from the wall ball's prescribed velocity history; "
         "false: g only (a_w = 0)"),
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");
    enum Field : int { density, pressure, wall_dvx, wall_ax = wall_dvx + 3, wall_vx_prev = wall_ax + 3 };
    static constexpr plab_field_desc fields[] = {
        plab::field_desc("sph_density", "kg/m3", 1000.0), plab::field_desc("sph_pressure", "Pa", 0.0),
        plab::field_desc("sph_wall_velocity_correction_x", "m/s", 0.0), plab::field_desc("sph_wall_velocity_correction_y", "m/s", 0.0),
        plab::field_desc("sph_wall_velocity_correction_z", "m/s", 0.0),
        // fields rather than pass state: checkpoints and the last good state carry them
        plab::field_desc("sph_wall_acceleration_x", "m/s2", 0.0), plab::field_desc("sph_wall_acceleration_y", "m/s2", 0.0),
        plab::field_desc("sph_wall_acceleration_z", "m/s2", 0.0),
        plab::field_desc("sph_wall_velocity_previous_x", "m/s", 0.0), plab::field_desc("sph_wall_velocity_previous_y", "m/s", 0.0),
        plab::field_desc("sph_wall_velocity_previous_z", "m/s", 0.0)};

    explicit SphWallPressure(const double* p)
        : kind_(plab::sph::KernelKind(int(p[kernel]))), h_(p[smoothing_length]), rho0_(p[rest_density]),
          gamma_(p[gamma]), b_(p[rest_density] * p[speed_of_sound] * p[speed_of_sound] / p[gamma]),
          boundary_(int(p[boundary_group])), g_{p[gx], p[gy], p[gz]}, no_slip_(int(p[no_slip]) == 1),
          accelerating_(int(p[wall_acceleration]) == 1) {}

    void run(const plab_pass_view& v) {
        if (accelerating_) update_wall_acceleration(v);
        const plab::sph::Kernel W{kind_, int(v.dim), h_};
        weighted_.assign(v.body_count, 0.0);
        weights_.assign(v.body_count, 0.0);
        fluid_velocity_.assign(3 * std::size_t(v.body_count), 0.0);
        double* rho = v.fields[density];
        double* p = v.fields[pressure];
        for (uint32_t k = 0; k < v.contact_count; ++k) {
            if (v.contact_end2_is_wall[k]) continue;
            int32_t w = v.contact_end1[k], f = v.contact_end2[k];
            if (v.group[f] == boundary_) std::swap(w, f);
            if (v.group[w] != boundary_ || v.group[f] == boundary_) continue;  // one wall ball, one fluid ball
            const double* xw = v.position + 3 * w;
            const double* xf = v.position + 3 * f;
            double d[3] = {xw[0] - xf[0], xw[1] - xf[1], xw[2] - xf[2]};
            plab::minimum_image(v, d);  // (a pair across a periodic boundary)
            const double kernel_value = W.value(std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
            double g_dot_d = g_[0] * d[0] + g_[1] * d[1] + g_[2] * d[2];
            if (accelerating_)  // (g - a_w)·(x_w - x_f), Islam eq. 10
                for (int c = 0; c < 3; ++c) g_dot_d -= v.fields[wall_ax + c][w] * d[c];
            weighted_[w] += (p[f] + rho[f] * g_dot_d) * kernel_value;
            weights_[w] += kernel_value;
            for (int c = 0; c < 3; ++c) fluid_velocity_[3 * w + c] += v.velocity[3 * f + c] * kernel_value;
        }
        for (uint32_t i = 0; i < v.body_count; ++i) {
            if (v.group[i] != boundary_) continue;
            const double sum = weights_[i];
            p[i] = sum > 0 ? weighted_[i] / sum : 0.0;
            rho[i] = rho0_ * std::pow(std::max(p[i] / b_ + 1.0, 0.0), 1.0 / gamma_);
            for (int c = 0; c < 3; ++c)  // v_w - v_prescribed = v_prescribed - ṽ_w (zero without fluid)
                v.fields[wall_dvx + c][i] =
                    no_slip_ && sum > 0 ? v.velocity[3 * i + c] - fluid_velocity_[3 * i + c] / sum : 0.0;
        }
    }

private:
    // a_w = (v - v_prev)/dt per boundary ball; dt = 0 (a re-evaluation)
    // keeps a_w and takes v as the new reference
    void update_wall_acceleration(const plab_pass_view& v) const {
        for (uint32_t i = 0; i < v.body_count; ++i) {
            if (v.group[i] != boundary_) continue;
            for (int c = 0; c < 3; ++c) {
                const double u = v.velocity[3 * i + c];
                double& prev = v.fields[wall_vx_prev + c][i];
                if (v.dt > 0) v.fields[wall_ax + c][i] = (u - prev) / v.dt;
                prev = u;
            }
        }
    }

    plab::sph::KernelKind kind_;
    double h_, rho0_, gamma_, b_;
    int boundary_;
    double g_[3];
    bool no_slip_, accelerating_;
    std::vector<double> weighted_, weights_, fluid_velocity_;
};

struct SphDensityIntegration {
    static constexpr const char* name = "sph_density_integration";
    static constexpr const char* doc =
        "rho += dt * drho/dt (continuity, thesis eq. 7) with the rate at the new positions and half-step velocities, "
        "before the EOS and the forces; boundary balls keep their density.";
    static constexpr uint32_t phase = PLAB_PHASE_RATES_DONE;
    static constexpr uint32_t stage = 0;
    static constexpr plab_property_desc properties[] = {boundary_group_desc};
    enum Field : int { density, drho_dt };
    static constexpr plab_field_desc fields[] = {plab::field_desc("sph_density", "kg/m3", 1000.0), plab::field_desc("sph_drho_dt", "kg/(m3 s)", 0.0)};

    explicit SphDensityIntegration(const double* p) : boundary_(int(p[0])) {}

    void run(const plab_pass_view& v) const {
        double* rho = v.fields[density];
        const double* rate = v.fields[drho_dt];
        for (uint32_t i = 0; i < v.body_count; ++i)
            if (v.group[i] != boundary_) rho[i] += v.dt * rate[i];
    }

private:
    int boundary_;
};

// Summation density (thesis eq. 8), ρ_i = Σ_j m_j W_ij over every ball
// within the support, the ball itself included (W_ii = W(0)), or its
// normalised form (eq. 9, Shepard; Randles & Libersky 1996)
// ρ_i = Σ_j m_j W_ij / Σ_j (m_j/ρ_j) W_ij, with ρ_j as the pass finds it.
// Fixed boundary balls contribute to the fluid's sums (thesis §2.2.4,
// LIGGGHTS' sph/density/summation) but keep their own density (ρ0, or the
// wall pressure pass's).
//  * Plain (eq. 8): instead of sph_density_integration; the density is a
//    function of the positions, recomputed every step before the EOS. It
//    underestimates the density where the support is truncated (free
//    surface: about 0.76 ρ0 on the top row of a resting lattice).
//  * Normalised (eq. 9): ρ_i is a weighted harmonic mean of the ρ_j, so
//    alone it cannot see a compression (a uniformly compressed lattice
//    keeps ρ_i = ρ_j). It is therefore a Shepard filter on the density of
//    the continuity equation: run it after sph_density_integration (stage
//    5 > 0). It removes the free-surface deficit (ρ0 at every particle of
//    a uniform fluid) and smooths the density noise of eq. 7.
// Every active pair within the support counts, whatever its model: not
// for scenes with DEM grains inside the fluid.
struct SphDensitySummation {
    static constexpr const char* name = "sph_density_summation";
    static constexpr const char* doc =
        "Summation density rho_i = sum_j m_j W_ij (thesis eq. 8; instead of sph_density_integration), or normalised "
        "by sum_j (m_j/rho_j) W_ij (eq. 9; a Shepard filter after sph_density_integration), every step before the "
        "EOS. Boundary balls contribute and keep their density.";
    static constexpr uint32_t phase = PLAB_PHASE_RATES_DONE;
    static constexpr uint32_t stage = 5;  // after sph_density_integration (0), before sph_eos (10)
    using material = FluidMaterial;
    enum Prop : int { smoothing_length, kernel, boundary_group, normalised, prop_count };
    static constexpr plab_property_desc properties[] = {
        fluid::smoothing_length, fluid::kernel,
        boundary_group_desc,
        plab::prop::boolean("normalised", "normalised summation", false,
         "false: rho_i = sum m_j W_ij (eq. 8); true: divided by sum (m_j/rho_j) W_ij (eq. 9, Shepard filter of the "
         "continuity density: use with sph_density_integration)"),
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");
    enum Field : int { density };
    static constexpr plab_field_desc fields[] = {plab::field_desc("sph_density", "kg/m3", 1000.0)};

    explicit SphDensitySummation(const double* p)
        : kind_(plab::sph::KernelKind(int(p[kernel]))), h_(p[smoothing_length]), boundary_(int(p[boundary_group])),
          normalised_(int(p[normalised]) == 1) {}

    void run(const plab_pass_view& v) {
        const plab::sph::Kernel W{kind_, int(v.dim), h_};
        const double w0 = W.value(0);
        const std::size_t n = v.body_count, width = stride() * n;
        const std::size_t per_chunk =
            std::max(kMinChunkContacts, (std::size_t(v.contact_count) + kMaxChunks - 1) / kMaxChunks);
        const std::size_t n_chunks = (std::size_t(v.contact_count) + per_chunk - 1) / per_chunk;
        partial_.resize(n_chunks * width);
        first_.resize(n_chunks);
        last_.resize(n_chunks);
        // (dynamic: the last chunk is mostly a short one, 9 on the dam break,
        // so a static split gave one thread 5 full chunks and the other 3 and
        // the short one; each chunk's sums are the same whichever thread
        // makes them, so the bits are too)
#pragma omp parallel for schedule(dynamic) if (n_chunks > 1)
        for (std::size_t c = 0; c < n_chunks; ++c)
            sum_chunk(v, W, c * per_chunk, std::min<std::size_t>(v.contact_count, (c + 1) * per_chunk),
                      partial_.data() + c * width, first_[c], last_[c]);
        add_chunks(v, n_chunks, w0);
    }

private:
    // Each body's chunk sums added in chunk order, then its own term: chunk
    // by chunk over blocks of bodies, a streaming loop, rather than body by
    // body over the chunks (a test per chunk and body; once the fluid has
    // mixed, every chunk's band spans nearly all bodies). Same additions in
    // the same order: the same bits.
    void add_chunks(const plab_pass_view& v, std::size_t n_chunks, double w0) {
        const std::size_t n = v.body_count, width = stride() * n;
        mass_sum_.assign(n, 0.0);
        if (normalised_) volume_sum_.assign(n, 0.0);
        double* rho = v.fields[density];
        constexpr std::int64_t kBlock = 2048;
        const std::int64_t n_blocks = (std::int64_t(n) + kBlock - 1) / kBlock;
#pragma omp parallel for schedule(static) if (n >= 4096)
        for (std::int64_t b = 0; b < n_blocks; ++b) {
            const std::int64_t i0 = b * kBlock, i1 = std::min<std::int64_t>(std::int64_t(n), i0 + kBlock);
            for (std::size_t c = 0; c < n_chunks; ++c) {  // (outside its band a chunk's sums are zero: x + 0 is x)
                const std::int64_t c0 = std::max(i0, first_[c]), c1 = std::min(i1, last_[c] + 1);
                const double* sum = partial_.data() + c * width;
                if (!normalised_) {
                    for (std::int64_t i = c0; i < c1; ++i) mass_sum_[i] += sum[i];
                    continue;
                }
                for (std::int64_t i = c0; i < c1; ++i) {
                    mass_sum_[i] += sum[2 * i];
                    volume_sum_[i] += sum[2 * i + 1];
                }
            }
            for (std::int64_t i = i0; i < i1; ++i) {
                if (v.group[i] == boundary_) continue;
                const double mass = mass_sum_[i] + v.mass[i] * w0;  // eq. 8 includes j = i
                rho[i] = normalised_ ? mass / (volume_sum_[i] + v.mass[i] / rho[i] * w0) : mass;
            }
        }
    }

    // The pairs are summed in chunks of contacts, each into its own partial
    // sums over the bodies its pairs touch (first to last index, usually a
    // narrow band: bodies are numbered along the lattice and pairs listed by
    // end 1), and each body adds its chunks' sums in chunk order: the same
    // bits for any thread count (the chunks depend on the contact count
    // only). At most kMaxChunks chunks, so the partial sums take at most 16
    // (32 normalised) doubles per body.
    static constexpr std::size_t kMinChunkContacts = 16384, kMaxChunks = 16;
    std::size_t stride() const { return normalised_ ? 2 : 1; }  // mass sum, then volume sum

    // eqs. 8–9 over the chunk of contacts [k0, k1), pairs within the support: m_j W_ij (and
    // (m_j/rho_j) W_ij) to end i, and the same with i and j swapped to end j;
    // body i's sums at sum[stride() i], for the bodies [first, last] that
    // the chunk's ball–ball pairs touch (none: first > last)
    void sum_chunk(const plab_pass_view& v, const plab::sph::Kernel& W, std::size_t k0, std::size_t k1, double* sum,
                   std::int64_t& first, std::int64_t& last) const {
        const std::size_t stride = this->stride();
        std::int32_t lo = std::numeric_limits<std::int32_t>::max(), hi = -1;
        // (two loops without a branch, which take a vector of rows at a time;
        // wall rows: end 2 is a facet, not summed below)
        const std::int32_t *end1 = v.contact_end1, *end2 = v.contact_end2;
        const std::uint8_t* is_wall = v.contact_end2_is_wall;
        for (std::size_t k = k0; k < k1; ++k) {
            lo = std::min(lo, end1[k]);
            hi = std::max(hi, end1[k]);
        }
        for (std::size_t k = k0; k < k1; ++k) {
            const std::int32_t ball = -std::int32_t(is_wall[k] == 0);  // all ones for a ball, 0 for a wall
            lo = std::min(lo, (end2[k] & ball) | (std::numeric_limits<std::int32_t>::max() & ~ball));
            hi = std::max(hi, (end2[k] & ball) | ~ball);  // (a wall: -1)
        }
        first = lo;
        last = hi;
        if (hi < lo) return;
        std::fill(sum + stride * std::size_t(lo), sum + stride * (std::size_t(hi) + 1), 0.0);
        const double support = W.support();
        // W.value(r) with its normalisation taken once, not per pair (same arithmetic)
        const double norm = plab::sph::normalisation(kind_, int(v.dim), h_);
        const double* rho = v.fields[density];
        // q = r/h as r (1/h): a square root and a division per pair kept the
        // divider busy; q changes by rounding only
        const double inv_h = 1.0 / h_;
        // The pairs of one end i come in a run (a neighbour list): i's sums
        // are held in locals over the run, not loaded and stored per pair,
        // which made each pair wait for the previous one's store. Same sums
        // in the same order: the same bits.
        std::int32_t held_i = -1;
        double held_mass = 0, held_volume = 0;
        auto put_back = [&] {
            if (held_i < 0) return;
            sum[stride * std::size_t(held_i)] = held_mass;
            if (normalised_) sum[stride * std::size_t(held_i) + 1] = held_volume;
        };
        // In blocks: each pair's W first, in a loop of its own (a vector of
        // pairs per instruction; interleaved with the sums, which wait on
        // one another, it took one pair at a time), then the sums
        constexpr std::size_t kBlock = 512;
        double r_of[kBlock], w_of[kBlock];
        for (std::size_t b0 = k0; b0 < k1; b0 += kBlock) {
            const std::size_t n = std::min(kBlock, k1 - b0);
            const double* r = v.contact_distance ? v.contact_distance + b0 : r_of;  // (plab_pass_view::contact_distance)
            if (!v.contact_distance)
                for (std::size_t a = 0; a < n; ++a) {  // (a wall row's is not used)
                    const std::size_t k = b0 + a;
                    r_of[a] = v.contact_end2_is_wall[k] ? inf : distance(v, v.contact_end1[k], v.contact_end2[k]);
                }
            kernel_values(r, n, inv_h, norm, w_of);
            for (std::size_t a = 0; a < n; ++a) {
                const std::size_t k = b0 + a;
                if (v.contact_end2_is_wall[k] || r[a] >= support) continue;
                const int32_t i = v.contact_end1[k], j = v.contact_end2[k];
                const double w = w_of[a];
                if (i != held_i) {
                    put_back();
                    held_i = i;
                    held_mass = sum[stride * std::size_t(i)];
                    if (normalised_) held_volume = sum[stride * std::size_t(i) + 1];
                }
                held_mass += v.mass[j] * w;
                if (normalised_) held_volume += v.mass[j] / rho[j] * w;
                if (j == held_i) {  // (a ball paired with itself: not in a neighbour list, but kept in order)
                    held_mass += v.mass[i] * w;
                    if (normalised_) held_volume += v.mass[i] / rho[i] * w;
                    continue;
                }
                double* sum_j = sum + stride * std::size_t(j);
                sum_j[0] += v.mass[i] * w;
                if (normalised_) sum_j[1] += v.mass[i] / rho[i] * w;
            }
        }
        put_back();
    }

    // W(r) = norm f(r/h) of n pairs, the kernel's shape fixed at compile
    // time: no switch per pair, so the loop takes a vector of pairs at a time
    void kernel_values(const double* r, std::size_t n, double inv_h, double norm, double* w) const {
        using plab::sph::KernelKind;
        const auto values = [&](auto kind) {
            for (std::size_t a = 0; a < n; ++a) w[a] = norm * plab::sph::detail::shape(decltype(kind)::value, r[a] * inv_h);
        };
        switch (kind_) {
        case KernelKind::wendland_c2: return values(std::integral_constant<KernelKind, KernelKind::wendland_c2>{});
        case KernelKind::cubic_spline: return values(std::integral_constant<KernelKind, KernelKind::cubic_spline>{});
        case KernelKind::quintic_spline: return values(std::integral_constant<KernelKind, KernelKind::quintic_spline>{});
        }
    }

    // |x_j - x_i| with the host's arithmetic (its range test: the same bits
    // whether the host passes the distances or not)
    static double distance(const plab_pass_view& v, int32_t i, int32_t j) {
        const double* xi = v.position + 3 * i;
        const double* xj = v.position + 3 * j;
        double d[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
        plab::minimum_image(v, d);  // (a pair across a periodic boundary)
        return std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }

    plab::sph::KernelKind kind_;
    double h_;
    int boundary_;
    bool normalised_;
    std::vector<double> partial_, mass_sum_, volume_sum_;
    std::vector<std::int64_t> first_, last_;  // each chunk's bodies
};

// XSPH (thesis eq. 18; Monaghan 1989): a particle moves with its velocity
// smoothed over its neighbours,
//   dx_i/dt = v_i + ε Σ_j m_j (v_j - v_i) W_ij / ρ̄_ij,   ρ̄_ij = (ρ_i + ρ_j)/2,
// with v at the half step. The pass runs before the drift (phase
// PLAB_PHASE_PRE_DRIFT) and writes the correction into the host's drift velocity
// correction fields; the velocity itself (momentum, kinetic energy) is
// untouched. Fluid–fluid pairs only: boundary balls neither receive nor give
// a correction, so Σ m_i δv_i = 0 exactly (each pair adds ±ε m_i m_j (v_j -
// v_i) W/ρ̄) and the fluid's centre of mass drifts with its momentum.
struct SphXsph {
    static constexpr const char* name = "sph_xsph";
    static constexpr const char* doc =
        "XSPH (thesis eq. 18): the drift moves a fluid ball with v_i + eps sum_j m_j (v_j - v_i) W_ij / rho_ij, "
        "fluid-fluid pairs, half-step velocities; the velocity itself is unchanged.";
    static constexpr uint32_t phase = PLAB_PHASE_PRE_DRIFT;
    static constexpr uint32_t stage = 0;
    using material = FluidMaterial;
    enum Prop : int { smoothing_length, kernel, boundary_group, epsilon, prop_count };
    static constexpr plab_property_desc properties[] = {
        fluid::smoothing_length, fluid::kernel,
        boundary_group_desc,
        plab::prop::number("epsilon", "XSPH coefficient", "1", 0.5, 0.0, 1.0, 0,
         "eps of eq. 18; 0.5 is usual, large values slow the flow unphysically (thesis 2.2.3)"),
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");
    enum Field : int { density, dvx, dvy, dvz };
    static constexpr plab_field_desc fields[] = {plab::field_desc("sph_density", "kg/m3", 1000.0),
                                                 plab::field_desc(PLAB_DRIFT_CORRECTION_X, "m/s", 0.0),
                                                 plab::field_desc(PLAB_DRIFT_CORRECTION_Y, "m/s", 0.0),
                                                 plab::field_desc(PLAB_DRIFT_CORRECTION_Z, "m/s", 0.0)};

    explicit SphXsph(const double* p)
        : kind_(plab::sph::KernelKind(int(p[kernel]))), h_(p[smoothing_length]), boundary_(int(p[boundary_group])),
          epsilon_(p[epsilon]) {}

    void run(const plab_pass_view& v) const {
        const plab::sph::Kernel W{kind_, int(v.dim), h_};
        const double support2 = W.support() * W.support();
        const double* rho = v.fields[density];
        double* dv[3] = {v.fields[dvx], v.fields[dvy], v.fields[dvz]};
        for (int c = 0; c < 3; ++c) std::fill(dv[c], dv[c] + v.body_count, 0.0);
        for (uint32_t k = 0; k < v.contact_count; ++k) {
            if (v.contact_end2_is_wall[k]) continue;
            const int32_t i = v.contact_end1[k], j = v.contact_end2[k];
            if (v.group[i] == boundary_ || v.group[j] == boundary_) continue;
            const double* xi = v.position + 3 * i;
            const double* xj = v.position + 3 * j;
            double d[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
            plab::minimum_image(v, d);  // (a pair across a periodic boundary)
            const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if (r2 >= support2) continue;
            const double s = epsilon_ * W.value(std::sqrt(r2)) / (0.5 * (rho[i] + rho[j]));
            for (int c = 0; c < 3; ++c) {
                const double v_ji = v.velocity[3 * j + c] - v.velocity[3 * i + c];
                dv[c][i] += s * v.mass[j] * v_ji;
                dv[c][j] -= s * v.mass[i] * v_ji;
            }
        }
    }

private:
    plab::sph::KernelKind kind_;
    double h_;
    int boundary_;
    double epsilon_;
};

} // namespace

namespace plab::sph {

// The passes of plab_sph, registered by its plab_plugin_init (sph.cpp).
int register_passes(const plab_registrar* r) {
    return plab::add_pass<SphEos>(r) != 0                  ? 1
           : plab::add_pass<SphWallPressure>(r) != 0       ? 1
           : plab::add_pass<SphDensityIntegration>(r) != 0 ? 1
           : plab::add_pass<SphDensitySummation>(r) != 0   ? 1
                                                           : plab::add_pass<SphXsph>(r);
}

} // namespace plab::sph
