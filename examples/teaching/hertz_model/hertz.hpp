// `hertz` — Hertz–Mindlin (no-slip) contact between elastic spheres, built
// step by step in docs/writing-a-contact-model.md. Both ends are of one
// material (E, nu); a wall is taken as the same material.
//
//   normal:      F_n = 4/3 E* sqrt(R*) d^(3/2)                  (Hertz 1882)
//   tangential:  dF_t = -k_t v_t dt,  k_t = 8 G* sqrt(R* d)      (Mindlin 1949, no slip)
//                |F_t| <= fric F_n                               (Coulomb)
//   damping:     F_d = -2 sqrt(5/6) beta sqrt(k m*) v,           (Tsuji et al. 1992 form,
//                beta = -ln e / sqrt(ln^2 e + pi^2)               coefficients as in LIGGGHTS/EDEM)
//   with 1/E* = 2 (1 - nu^2)/E, 1/G* = 2 (2 - nu)/G, G = E/(2 (1 + nu)),
//   R* = R1 R2/(R1 + R2), m* = m1 m2/(m1 + m2), d the overlap.
//
// Hertz theory is for spheres. In a 2D scene the same law acts between
// discs (a teaching simplification, not the 2D line-contact law).
#pragma once

#include <plab/contact_model.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tutorial {

struct ElasticSolid;  // the material whose properties a scene may state per group (below)

using plab::Contact;
using plab::Vec3;

struct Hertz {
    static constexpr const char* name = "hertz";
    static constexpr const char* doc =
        "Hertz-Mindlin (no-slip) contact of elastic spheres of one material: F_n = 4/3 E* sqrt(R*) d^1.5, "
        "tangential stiffness 8 G* sqrt(R* d), Coulomb limit fric*F_n, Tsuji damping from the restitution "
        "coefficient. No tension. Tutorial model: docs/writing-a-contact-model.md.";
    static constexpr const char* timestep_rule =
        "min of 0.2 x the Rayleigh time pi R sqrt(rho/G)/(0.1631 nu + 0.8766) of the smaller ball and, per ball, "
        "sqrt(m / sum k) with the tangent normal stiffness k = 2 E* sqrt(R* d)";
    static constexpr uint32_t range_kind = PLAB_RANGE_GAP;
    // what law() reads besides normal, gap and relative velocity, and writes besides force and energies
    static constexpr uint32_t io = PLAB_IO_RADII | PLAB_IO_MASSES | PLAB_IO_EFF_MASS | PLAB_IO_EFF_RADIUS | PLAB_IO_DT_LIMIT;
    // E, nu and fric are the ends' material: a scene material of the rule's
    // groups gives them (the pair's e is given in the rule)
    using material = ElasticSolid;

    // Step 1: the properties, each with an SI unit and a valid range.
    enum Prop : int { youngs_modulus, poisson_ratio, restitution, fric, prop_count };
    static constexpr double inf = std::numeric_limits<double>::infinity();
    static constexpr plab_property_desc properties[] = {
        // two materials' E mix harmonically (with equal nu, Hertz's 1/E* = (1 - nu^2)(1/E1 + 1/E2)),
        // their friction by the smaller; nu and e must agree
        plab::prop::number("E", "Young's modulus", "Pa", 70e9, 0.0, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
         "of both ends (and of walls)", PLAB_MIX_HARMONIC),
        plab::prop::number("nu", "Poisson's ratio", "1", 0.25, 0.0, 0.5, PLAB_MAX_EXCLUSIVE, "of both ends"),
        plab::prop::number("e", "coefficient of restitution", "1", 1.0, 0.0, 1.0, PLAB_MIN_EXCLUSIVE,
         "sets the Tsuji damping ratio beta = -ln e / sqrt(ln^2 e + pi^2); 1: no damping"),
        plab::prop::number("fric", "friction coefficient", "1", 0.0, 0.0, inf, PLAB_MAX_EXCLUSIVE, "Coulomb limit |F_t| <= fric F_n",
         PLAB_MIX_MIN),
    };

    // Step 3: the tangential force is remembered between steps. It is a
    // vector in the contact plane, which the host turns with the plane
    // before law() reads it (PLAB_HISTORY_TANGENTIAL on its x).
    enum Slot : int { shear_force_x, shear_force_y, shear_force_z, slot_count };
    static constexpr plab_history_desc history[] = {
        plab::history_desc("shear_force_x", 0.0, PLAB_SWAP_NEGATE, "tangential force on end 2, global x, N",
                           PLAB_HISTORY_TANGENTIAL),
        plab::history_desc("shear_force_y", 0.0, PLAB_SWAP_NEGATE, "tangential force on end 2, global y, N"),
        plab::history_desc("shear_force_z", 0.0, PLAB_SWAP_NEGATE, "tangential force on end 2, global z, N"),
    };

    // Only touching balls interact.
    static double activity_range(const double*) { return 0.0; }

    explicit Hertz(const double* p)
        : E_eff_(p[youngs_modulus] / (2.0 * (1.0 - p[poisson_ratio] * p[poisson_ratio]))),
          G_eff_(shear_modulus(p) / (2.0 * (2.0 - p[poisson_ratio]))),
          rayleigh_factor_(M_PI / (0.1631 * p[poisson_ratio] + 0.8766) / std::sqrt(shear_modulus(p))),
          beta_(damping_ratio(p[restitution])),
          fric_(p[fric]) {}

    void law(const Contact& c) const {
        const double d = c.overlap();
        const Vec3 n = c.normal();
        const double R = c.eff_radius(), m = c.eff_mass();
        const double sqrt_Rd = std::sqrt(R * d);

        // Step 2: Hertz normal force and its tangent stiffness dF/dd.
        const double fn_elastic = 4.0 / 3.0 * E_eff_ * sqrt_Rd * d;
        const double kn = 2.0 * E_eff_ * sqrt_Rd;
        const Vec3 v = c.rel_velocity();
        const double vn = dot(v, n);
        // Step 4: Tsuji damping, no tension in the total normal force.
        const double fn_damping = -2.0 * std::sqrt(5.0 / 6.0) * beta_ * std::sqrt(kn * m) * vn;
        const double fn = std::max(0.0, fn_elastic + fn_damping);

        // Step 3: Mindlin no-slip tangential spring, incremental (on the
        // stored force, already in the current plane), Coulomb-capped.
        const double kt = 8.0 * G_eff_ * sqrt_Rd;
        const Vec3 vt = v - vn * n;
        Vec3 ft = c.history_vec(shear_force_x) - kt * c.dt() * vt;
        const double ft_max = fric_ * fn;
        const double ft_mag = norm(ft);
        const bool sliding = ft_mag > ft_max;
        if (sliding) {
            const Vec3 capped = ft_mag > 0.0 ? ft * (ft_max / ft_mag) : Vec3{};
            if (kt > 0.0) c.add_slip_energy(norm(ft - capped) * ft_max / kt);
            ft = capped;
        }
        c.set_history_vec(shear_force_x, ft);
        const Vec3 ft_damping = sliding ? Vec3{} : -2.0 * std::sqrt(5.0 / 6.0) * beta_ * std::sqrt(kt * m) * vt;

        c.set_force(fn * n + ft + ft_damping);
        c.set_strain_energy(0.4 * fn_elastic * d + (kt > 0.0 ? 0.5 * dot(ft, ft) / kt : 0.0));
        c.add_dashpot_energy(-((fn - fn_elastic) * vn + dot(ft_damping, vt)) * c.dt());

        // Step 5: a stable timestep. kn vanishes at first touch, so the
        // Rayleigh-wave time of the smaller ball bounds the step as well.
        c.set_stiffness(std::max(kn, kt));
        c.set_dt_limit(0.2 * rayleigh_time(c));
    }

    static double damping_ratio(double e) {
        const double ln_e = std::log(e);
        return -ln_e / std::sqrt(ln_e * ln_e + M_PI * M_PI);
    }

private:
    static double shear_modulus(const double* p) { return p[youngs_modulus] / (2.0 * (1.0 + p[poisson_ratio])); }

    // pi R sqrt(rho/G)/(0.1631 nu + 0.8766) for the smaller ball; density
    // from mass and radius (a disc of unit thickness in 2D).
    double rayleigh_time(const Contact& c) const {
        const bool second = !c.with_wall() && c.radius2() < c.radius1();
        const double r = second ? c.radius2() : c.radius1(), m = second ? c.mass2() : c.mass1();
        const double volume = c.dim() == 2 ? M_PI * r * r : 4.0 / 3.0 * M_PI * r * r * r;
        return rayleigh_factor_ * r * std::sqrt(m / volume);
    }

    double E_eff_, G_eff_, rayleigh_factor_, beta_, fric_;
};

// The material (abi.h plab_material_desc): the properties of one group's
// solid, declared as the model declares them, so that a scene can state them
// once per group ("materials": {"glass": {"groups": ["beads"], "E": 6.3e10,
// "nu": 0.22, "fric": 0.4}}) and a rule between two materials mixes them.
struct ElasticSolid {
    static constexpr const char* name = "hertz_elastic_solid";
    static constexpr const char* doc = "an elastic solid for the Hertz contact: Young's modulus, Poisson's ratio, friction";
    static constexpr plab_property_desc properties[] = {
        Hertz::properties[Hertz::youngs_modulus], Hertz::properties[Hertz::poisson_ratio], Hertz::properties[Hertz::fric]};
};

} // namespace tutorial
