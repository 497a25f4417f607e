// `linear_lubrication`: the `linear` contact (thesis eqs. 21–29) between
// solid particles immersed in a fluid, plus the lubrication force between
// their wet surfaces while they are close (thesis eq. 76, §4.1):
//   F_l = -3π μ_f d_ij² / (8 s) (v_ij·n) n,  s = |x_ij| - d_ij,  active while |x_ij| <= 2 d_ij
// Reading of eq. 76 (its text defines "2d_ij = (d_i + d_j)/2"): d_ij is the
// mean diameter (d_i + d_j)/2, so s is the surface gap and 3π μ d²/(8 s) is
// Reynolds' squeeze-film resistance of two equal spheres (6π μ a*² / s with
// the reduced radius a* = d/4); the cut-off |x_ij| <= 2 d_ij is a gap of one
// mean diameter. The force diverges as s -> 0, and the contact itself is the
// linear spring's: the gap is floored at `lub_min_gap` (the roughness scale),
// which also keeps the force finite in overlap. Only the normal approach is
// resisted (eq. 76 has no tangential part). In 2D the formula is applied
// unchanged to the unit-thickness discs, as the thesis (PFC2D) does: the
// sphere's coefficient, not the (stronger, s^-3/2) one of two cylinders.
// The grains of a scene thus still interact with the `linear` law (same
// header, same properties); this model adds eq. 76 on top, for the one
// group pair a scene may assign it to.
#include <plab/dem/linear_law.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace {

using plab::Contact;
using plab::Vec3;

constexpr double inf = std::numeric_limits<double>::infinity();

struct LinearLubrication {
    static constexpr const char* name = "linear_lubrication";
    static constexpr const char* doc =
        "Linear spring-dashpot contact with Coulomb friction (thesis eqs. 21-29) plus the lubrication force between "
        "wet particles (thesis eq. 76): -3 pi mu d^2/(8 s) (v.n) n for surface gaps s up to one mean diameter d, "
        "s floored at lub_min_gap.";
    static constexpr const char* timestep_rule =
        "as linear (sqrt(m / sum k)); the lubrication damper c = 3 pi mu d^2/(8 s) adds dt < m_eff / c";
    static constexpr uint32_t range_kind = PLAB_RANGE_GAP;
    static constexpr uint32_t io = PLAB_IO_RADII | PLAB_IO_EFF_MASS | PLAB_IO_DT_LIMIT;
    // a scene material of its groups gives the linear law's properties (kn, ..., rgap)
    using material = plab::linear_law::Material;

    enum Prop : int { kn, ks, fric, dp_nratio, dp_sratio, dp_mode, rgap, mu, lub_range, lub_min_gap, prop_count };
    static constexpr plab_property_desc properties[] = {
        plab::linear_law::kn,        plab::linear_law::ks,      plab::linear_law::fric, plab::linear_law::dp_nratio,
        plab::linear_law::dp_sratio, plab::linear_law::dp_mode, plab::linear_law::rgap,
        plab::prop::number("mu", "fluid dynamic viscosity mu_f", "Pa s", 8.9e-4, 0.0, inf, PLAB_MAX_EXCLUSIVE,
         "eq. 76; 0 turns the lubrication off (then this is `linear`)"),
        plab::prop::number("lub_range", "largest surface gap with lubrication", "m", 0.0024, 0.0, inf, PLAB_MAX_EXCLUSIVE,
         "eq. 76's cut-off |x| <= 2 d_ij is a gap of one mean diameter: give the particles' diameter; the force is "
         "also zero beyond one mean diameter of the pair"),
        plab::prop::number("lub_min_gap", "smallest gap in the lubrication force", "m", 1e-5, 0.0, inf,
         PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE, "floor of s in eq. 76 (surface roughness): keeps the force finite"),
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");

    enum Slot : int { shear_force_x, shear_force_y, shear_force_z, slot_count };
    static constexpr plab_history_desc history[] = {
        plab::linear_law::shear_force_x,
        plab::linear_law::shear_force_y,
        plab::linear_law::shear_force_z,
    };

    static double activity_range(const double* p) { return std::max(p[rgap], p[mu] > 0 ? p[lub_range] : p[rgap]); }

    explicit LinearLubrication(const double* p)
        : law_{p[kn], p[ks], p[fric], p[dp_nratio], p[dp_sratio], int(p[dp_mode]), p[rgap]}, mu_(p[mu]),
          range_(p[lub_range]), min_gap_(p[lub_min_gap]) {}

    void law(const Contact& c) const {
        double strain = 0;
        Vec3 f = plab::linear_law::apply(law_, c, shear_force_x, strain);
        c.set_strain_energy(strain);
        c.set_stiffness(std::max(law_.kn, law_.ks));
        const double damping = lubrication_coefficient(c);
        if (damping > 0) {
            const Vec3 n = c.normal();
            const double vn = plab::dot(c.rel_velocity(), n);  // v2 - v1 along n: < 0 approaching
            f += (-damping * vn) * n;                          // eq. 76, on end 2
            c.add_dashpot_energy(damping * vn * vn * c.dt());
            c.set_dt_limit(c.eff_mass() / damping);
        }
        c.set_force(f);
    }

private:
    // 3π μ d_ij² / (8 s) of eq. 76, 0 outside its range.
    double lubrication_coefficient(const Contact& c) const {
        if (!(mu_ > 0) || c.with_wall()) return 0.0;
        const double d = c.radius1() + c.radius2();  // mean diameter (d_i + d_j)/2
        const double s = c.gap();
        if (s > range_ || s > d) return 0.0;
        return 3.0 * M_PI * mu_ * d * d / (8.0 * std::max(s, min_gap_));
    }

    plab::linear_law::Params law_;
    double mu_, range_, min_gap_;
};

} // namespace

PLAB_PLUGIN(plab::add_contact_model<LinearLubrication>(r))
