// The linear contact law (thesis eqs. 21–29), shared by `linear` and by the
// linear components of `linear_pbond` and `linear_lubrication`: one law,
// written once. Part of the SDK (<plab/dem/linear_law.hpp>), for a model
// of its own built on the same spring-dashpot.
#pragma once

#include <plab/contact_model.hpp>

#include <cmath>
#include <type_traits>
#include <limits>

namespace plab::linear_law {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Property descriptions of the linear law, for every model built on it.
inline constexpr plab_property_desc kn = plab::prop::number("kn", "normal stiffness", "N/m", 1e6, 0.0, kInfinity,
                                          PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE, "linear normal spring (eq. 22)",
                                          PLAB_MIX_HARMONIC);
inline constexpr plab_property_desc ks = plab::prop::number("ks", "shear stiffness", "N/m", 1e6, 0.0, kInfinity, PLAB_MAX_EXCLUSIVE,
                                          "linear shear spring (eq. 24)", PLAB_MIX_HARMONIC);
inline constexpr plab_property_desc fric = plab::prop::number("fric", "friction coefficient", "1", 0.0, 0.0, kInfinity,
                                            PLAB_MAX_EXCLUSIVE, "Coulomb limit (eq. 26)", PLAB_MIX_MIN);
inline constexpr plab_property_desc dp_nratio = plab::prop::number("dp_nratio", "normal critical damping ratio", "1", 0.0, 0.0, 1.0,
                                                 PLAB_MAX_EXCLUSIVE, "normal dashpot 2*beta_n*sqrt(m*kn) (eq. 27)",
                                                 PLAB_MIX_ARITHMETIC);
inline constexpr plab_property_desc dp_sratio = plab::prop::number("dp_sratio", "shear critical damping ratio", "1", 0.0, 0.0, 1.0,
                                                 PLAB_MAX_EXCLUSIVE, "shear dashpot 2*beta_s*sqrt(m*ks) (eq. 28)",
                                                 PLAB_MIX_ARITHMETIC);
// the dashpot modes (PFC's dp_mode 0-3), the law's `dp_mode` in this order
inline constexpr const char* dp_mode_names[] = {"full", "slip_shear", "no_tension", "no_tension_slip_shear"};
inline constexpr plab_property_desc dp_mode = plab::prop::choice(
    "dp_mode", "dashpot mode", dp_mode_names, 0,
    "full: both dashpots always; slip_shear: the shear dashpot off while sliding; no_tension: the total normal "
    "force kept >= 0 (the dashpot never pulls); no_tension_slip_shear: both");
inline constexpr plab_property_desc rgap = plab::prop::number("rgap", "reference gap", "m", 0.0, -kInfinity, kInfinity,
                                            PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
                                            "the linear part is active while surface gap <= rgap");

// The DEM package's material, "dem_linear" (abi.h plab_material_desc): the
// linear law's properties, which a scene may state per group of balls,
//   "materials": {"sand": {"groups": ["sand"], "kn": 1e6, "fric": 0.5}, "glass": {...}},
// and which a contact between groups of two materials mixes by each
// property's rule (kn, ks harmonic; fric the smaller; the damping ratios
// arithmetic; dp_mode and rgap must agree). A model built on the law takes
// them with `using material = plab::linear_law::Material;`.
struct Material {
    static constexpr const char* name = "dem_linear";
    static constexpr const char* doc =
        "the linear spring-dashpot contact of a group of balls: stiffnesses, friction, damping ratios, dashpot mode, "
        "reference gap (thesis eqs. 21-29)";
    static constexpr plab_property_desc properties[] = {kn, ks, fric, dp_nratio, dp_sratio, dp_mode, rgap};
};

// History slots of the linear law's shear spring (three, in this order): a
// vector in the contact plane, which the host turns with the plane before
// the law reads it (abi.h, PLAB_HISTORY_TANGENTIAL).
inline constexpr plab_history_desc shear_force_x = plab::history_desc("shear_force_x", 0.0, PLAB_SWAP_NEGATE,
                                                    "linear shear force on end 2, global x, N", PLAB_HISTORY_TANGENTIAL);
inline constexpr plab_history_desc shear_force_y = plab::history_desc("shear_force_y", 0.0, PLAB_SWAP_NEGATE,
                                                    "linear shear force on end 2, global y, N");
inline constexpr plab_history_desc shear_force_z = plab::history_desc("shear_force_z", 0.0, PLAB_SWAP_NEGATE,
                                                    "linear shear force on end 2, global z, N");

struct Params {
    double kn, ks, fric, beta_n, beta_s;
    int dp_mode;
    double rgap;
    // derived once, not per contact: dashpot coefficients per sqrt(kg)
    // (2 beta sqrt(m k) = c sqrt(m), eqs. 27-28) and inverse stiffnesses
    double cn = 2.0 * beta_n * std::sqrt(kn), cs = 2.0 * beta_s * std::sqrt(ks);
    double inv_kn = 1.0 / kn, inv_ks = ks > 0.0 ? 1.0 / ks : 0.0;
};

// A 2D row's vector: its z is zero, so the law on the plane works on x and
// y alone, with the same arithmetic (a dot product's z term only adds a zero).
struct Plane {
    double x = 0, y = 0;
};
inline Plane operator+(const Plane& a, const Plane& b) { return {a.x + b.x, a.y + b.y}; }
inline Plane operator-(const Plane& a, const Plane& b) { return {a.x - b.x, a.y - b.y}; }
inline Plane operator-(const Plane& a) { return {-a.x, -a.y}; }
inline Plane operator*(const Plane& a, double s) { return {a.x * s, a.y * s}; }
inline Plane operator*(double s, const Plane& a) { return {a.x * s, a.y * s}; }
inline double dot(const Plane& a, const Plane& b) { return a.x * b.x + a.y * b.y; }
// each component of a or of b, as c says (a choice between values, not a branch)
inline Vec3 pick(bool c, const Vec3& a, const Vec3& b) { return {c ? a.x : b.x, c ? a.y : b.y, c ? a.z : b.z}; }
inline Plane pick(bool c, const Plane& a, const Plane& b) { return {c ? a.x : b.x, c ? a.y : b.y}; }
template <class V> V zero_vector() { return V{}; }
// A row's vector from three doubles of a column, and back (a 2D row: x and
// y; its z stored as zero).
template <class V> V row_vector(const double* c);
template <> [[gnu::always_inline]] inline Vec3 row_vector<Vec3>(const double* c) { return {c[0], c[1], c[2]}; }
template <> [[gnu::always_inline]] inline Plane row_vector<Plane>(const double* c) { return {c[0], c[1]}; }
[[gnu::always_inline]] inline void put_row_vector(double* c, const Vec3& v) { c[0] = v.x; c[1] = v.y; c[2] = v.z; }
[[gnu::always_inline]] inline void put_row_vector(double* c, const Plane& v) { c[0] = v.x; c[1] = v.y; c[2] = 0.0; }

// What the law needs of one contact, and what it gives back.
template <class V>
struct StateOf {
    V normal, rel_velocity, shear_force;  // shear force: the stored history, in the current contact plane
    double gap, eff_mass, dt;
};
template <class V>
struct ResultOf {
    V force, shear_force;          // force on end 2; the history to store
    double strain, slip, dashpot;  // strain energy; slip and dashpot energy to add
};
using State = StateOf<Vec3>;
using Result = ResultOf<Vec3>;

// The law (eqs. 21–29) for one contact, as a function of values: every
// contact takes the same operations and the branches are choices between
// values, so that a loop over a batch can be vectorised (apply_rows());
// apply() is the same function for one Contact. Inactive (surface gap >
// rgap): zero force and energies, and the shear history is forgotten.
template <class V>
inline ResultOf<V> law_of(const Params& p, const StateOf<V>& c) {
    const V& n = c.normal;
    const double overlap = p.rgap - c.gap;  // surface gap relative to the reference gap
    const bool active = !(overlap < 0.0);
    const V& v = c.rel_velocity;
    const double vn = dot(v, n);
    const V vs = v - vn * n;
    const double fn_lin = p.kn * overlap;  // eq. 22

    const V& fs_old = c.shear_force;
    const V fs_trial = fs_old - p.ks * c.dt * vs;  // eqs. 23–25
    const double fs_max = p.fric * fn_lin;            // eq. 26
    const double fs_mag2 = dot(fs_trial, fs_trial);   // compared squared: most contacts stick
    const bool sliding = fs_mag2 > fs_max * fs_max;
    // (the work of a sliding contact inside the choices: a scalar loop
    // branches around it, a vectorised one takes both sides)
    const double cap = sliding ? fs_max / std::sqrt(fs_mag2) : 1.0;
    const V fs = fs_trial * cap;  // (x 1: the same bits)

    const double sqrt_m = std::sqrt(c.eff_mass);
    double fn_d = -p.cn * sqrt_m * vn;  // eq. 27, on end 2
    // (& and |, not && and ||: no branch in a vectorised loop)
    const bool shear_dashpot = !(((p.dp_mode == 1) | (p.dp_mode == 3)) & sliding);
    const V fs_d_on = -p.cs * sqrt_m * vs;  // eq. 28
    const V fs_d = pick(shear_dashpot, fs_d_on, zero_vector<V>());
    const bool no_tension = ((p.dp_mode == 2) | (p.dp_mode == 3)) & (fn_lin + fn_d < 0.0);
    fn_d = no_tension ? -fn_lin : fn_d;  // no tension in total

    const double strain = 0.5 * fn_lin * fn_lin * p.inv_kn + 0.5 * dot(fs, fs) * p.inv_ks;
    const double dashpot = -(fn_d * vn + dot(fs_d, vs)) * c.dt;
    const V force = (fn_lin + fn_d) * n + fs + fs_d;
    ResultOf<V> r;
    r.force = pick(active, force, zero_vector<V>());
    r.shear_force = pick(active, fs, zero_vector<V>());
    r.strain = active ? strain : 0.0;
    // energy dissipated by the slip displacement (fs_trial - fs)/ks at mean force
    r.slip = active & sliding & (p.ks > 0.0) ? std::fabs(dot(0.5 * (fs + fs_old), (fs_trial - fs) * p.inv_ks)) : 0.0;
    r.dashpot = active ? dashpot : 0.0;
    return r;
}

inline Result law(const Params& p, const State& c) { return law_of<Vec3>(p, c); }

// Applies the law to contact c with its shear force stored in history slots
// [shear_slot, shear_slot + 3) (declared tangential). Returns the force on
// end 2; adds the strain, slip and dashpot energies.
inline Vec3 apply(const Params& p, const Contact& c, int shear_slot, double& strain) {
    const Result r = law(p, {c.normal(), c.rel_velocity(), c.history_vec(shear_slot), c.gap(), c.eff_mass(), c.dt()});
    c.set_history_vec(shear_slot, r.shear_force);
    c.add_slip_energy(r.slip);
    c.add_dashpot_energy(r.dashpot);
    strain += r.strain;
    return r.force;
}

// The law on rows [k0, k1) of a batch whose rows are all active (the host's
// packed batch), with a shear force in history slots [shear_slot, +3) and
// the force, strain energy and stiffness set as `linear` sets them. One loop
// over the rows' columns that GCC vectorises when the history stride is
// known (Stride > 0; two contacts per SSE2 instruction; the plug-in is built
// with -fno-trapping-math, which lets it evaluate both sides of a choice):
// the same operations as apply(), so the same bits.
// (restrict parameters, not locals: GCC proves the columns apart only so)
// The law over rows [k0, k1) of a batch's columns; Planar: 2D rows, whose
// z components are zero, worked out on x and y (z stored as zero).
template <std::size_t Stride, bool Planar>
[[gnu::always_inline]] inline void apply_rows(const Params p, std::size_t k0, std::size_t k1, double dt, std::size_t stride,
                const double* __restrict normal, const double* __restrict rel_velocity, const double* __restrict gap,
                const double* __restrict eff_mass, double* __restrict history, double* __restrict force,
                double* __restrict strain, double* __restrict slip, double* __restrict dashpot,
                double* __restrict k_t, double stiffness) {
    if (Stride > 0) stride = Stride;
    for (std::size_t k = k0; k < k1; ++k) {
        double* h = history + k * stride;
        using V = std::conditional_t<Planar, Plane, Vec3>;
        const ResultOf<V> r = law_of<V>(
            p, {row_vector<V>(normal + 3 * k), row_vector<V>(rel_velocity + 3 * k), row_vector<V>(h), gap[k],
                eff_mass[k], dt});
        put_row_vector(h, r.shear_force);
        put_row_vector(force + 3 * k, r.force);
        slip[k] += r.slip;
        dashpot[k] += r.dashpot;
        strain[k] = r.strain;
        k_t[k] = stiffness;
    }
}
template <bool Planar>
[[gnu::always_inline]] inline void apply_rows_in(const Params& p, const plab_contact_batch& b, std::size_t k0,
                                                 std::size_t k1, int shear_slot, double stiffness) {
    if (b.history_stride == 3)
        apply_rows<3, Planar>(p, k0, k1, b.dt, 3, b.normal, b.rel_velocity, b.gap, b.eff_mass, b.history + shear_slot,
                              b.force, b.strain_energy, b.slip_energy, b.dashpot_energy, b.stiffness_translational,
                              stiffness);
    else
        apply_rows<0, Planar>(p, k0, k1, b.dt, b.history_stride, b.normal, b.rel_velocity, b.gap, b.eff_mass,
                              b.history + shear_slot, b.force, b.strain_energy, b.slip_energy, b.dashpot_energy,
                              b.stiffness_translational, stiffness);
}
[[gnu::always_inline]] inline void apply_rows(const Params& p, const plab_contact_batch& b, std::size_t k0,
                                              std::size_t k1, int shear_slot, double stiffness) {
    if (b.dim == 2) apply_rows_in<true>(p, b, k0, k1, shear_slot, stiffness);
    else apply_rows_in<false>(p, b, k0, k1, shear_slot, stiffness);
}

} // namespace plab::linear_law
