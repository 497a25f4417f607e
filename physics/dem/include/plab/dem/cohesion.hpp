// Simplified JKR cohesion (LIGGGHTS `cohesion sjkr`): an attractive normal
// force proportional to the contact area, for wet or cohesive powders.
// Part of the SDK (<plab/dem/cohesion.hpp>), an option of `hertz` and of any
// law that adds it to its own normal force.
//
//   F_c = k_c A                      k_c the cohesion energy density, J/m³
//   A = pi a² (3D), 2 a L (2D discs of length L = 1 m)
//   a² = (S² − d²)(d² − Δ²) / (4 d²)  two balls: d the centre distance,
//                                    S = r1 + r2, Δ = r1 − r2 (the chord of
//                                    the two overlapping circles)
//   a² = 2 r δ − δ²                  a ball on a wall, δ its overlap
//
// Its potential U = −∫ F_c dδ is kept per contact (trapezoidal in the
// overlap, two history slots), so the energy balance closes with it. Its
// stiffness dF_c/dδ is not added to the stable step: at first touch it is
// 2 pi k_c R* in 3D (unbounded in 2D, as a² grows like δ), which stays
// below Hertz's S_n = 2 E* a once a > pi k_c R* / E*, a fraction of a
// nanometre for powders (k_c ~ 1e5–1e6 J/m³, E* ~ 1e8 Pa and up).
#pragma once

#include <plab/contact_model.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace plab::cohesion {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
inline constexpr double kPi = 3.14159265358979323846;

inline constexpr plab_property_desc cohesion_energy_density =
    plab::prop::number("k_c", "cohesion energy density", "J/m^3", 0.0, 0.0, kInfinity, PLAB_MAX_EXCLUSIVE,
                       "simplified JKR cohesion F = k_c A, A the contact area (LIGGGHTS cohesion sjkr); 0: none",
                       PLAB_MIX_ARITHMETIC);

// the overlap at the last call and the cohesion's potential energy (<= 0)
inline constexpr plab_history_desc cohesion_overlap =
    plab::history_desc("cohesion_overlap", 0.0, PLAB_SWAP_KEEP, "the overlap at the last step, m");
inline constexpr plab_history_desc cohesion_energy =
    plab::history_desc("cohesion_energy", 0.0, PLAB_SWAP_KEEP, "the cohesion's potential energy, J (<= 0)");

// the inputs it reads (a model adds them to its `io`)
inline constexpr uint32_t io = PLAB_IO_RADII;

// The contact area at overlap `overlap` (0 when apart).
inline double contact_area(const Contact& c, double overlap) {
    const double r1 = c.radius1();
    double a2;
    if (c.with_wall()) {
        a2 = 2.0 * r1 * overlap - overlap * overlap;
    } else {
        const double r2 = c.radius2(), S = r1 + r2, D = r1 - r2, d = S - overlap;
        a2 = (S * S - d * d) * (d * d - D * D) / (4.0 * d * d);
    }
    const double a = std::sqrt(std::max(0.0, overlap > 0.0 ? a2 : 0.0));
    return c.dim() == 2 ? 2.0 * a : kPi * a * a;
}

struct Result {
    Vec3 force;     // on end 2: towards end 1
    double strain;  // the potential energy, <= 0
};

// The cohesion of a touching contact (slots [slot, slot + 2)), k_c > 0.
inline Result apply(double k_c, const Contact& c, int slot) {
    const double overlap = std::max(0.0, c.overlap());
    const double before = c.history(slot);
    const double f = k_c * contact_area(c, overlap), f_before = k_c * contact_area(c, before);
    const double energy = overlap > 0.0 ? c.history(slot + 1) - 0.5 * (f + f_before) * (overlap - before) : 0.0;
    c.history(slot) = overlap;
    c.history(slot + 1) = energy;
    return {-f * c.normal(), energy};
}

} // namespace plab::cohesion
