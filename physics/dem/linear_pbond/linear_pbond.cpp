// The `linear_pbond` contact model — thesis §3.2.2 and §3.3 (eqs. 38–50),
// like PFC's `linearpbond`: the linear law (eqs. 21–29) in parallel with a
// finite-size bond of radius R̄ = λ min(R1, R2) that carries force and moment.
// Bond forces and moments grow incrementally with the relative motion and
// turn with the contact plane. The bond breaks in tension when σ ≥ σc, else
// in shear when τ ≥ τc (checked in that order, §3.3.3); a broken bond never
// carries load again and the contact behaves as `linear`.
#include <plab/dem/linear_law.hpp>

#include <algorithm>
#include <cmath>

namespace {

using plab::Contact;
using plab::Vec3;

constexpr double inf = std::numeric_limits<double>::infinity();

struct LinearPBond {
    static constexpr const char* name = "linear_pbond";
    static constexpr const char* doc =
        "Linear contact (kn, ks, fric, dashpots) in parallel with a parallel bond of radius pb_rmul*min(R1,R2) "
        "carrying force and moment (thesis eqs. 38-50; PFC linearpbond). The bond breaks in tension when "
        "sigma = Fn/A + pb_mcf |Mb| R/I >= pb_ten, else in shear when tau = |Fs|/A + pb_mcf |Mt| R/J >= pb_coh. "
        "2D: A = 2R, I = 2R^3/3 (unit thickness); 3D: A = pi R^2, I = pi R^4/4, J = pi R^4/2.";
    static constexpr const char* timestep_rule =
        "per ball sqrt(m / sum k) with k = max(kn + A pb_kn, ks + A pb_ks), and sqrt(I / sum (k r^2 + pb_kn I_bond))";
    static constexpr uint32_t range_kind = PLAB_RANGE_GAP;
    static constexpr uint32_t io = PLAB_IO_RADII | PLAB_IO_REL_ANGULAR_VELOCITY | PLAB_IO_EFF_MASS | PLAB_IO_MOMENTS |
                                   PLAB_IO_STIFFNESS_ROTATIONAL | PLAB_IO_BREAK_ENERGY;
    // a scene material of its groups gives the linear law's properties (kn, ..., rgap)
    using material = plab::linear_law::Material;

    enum Prop : int { kn, ks, fric, dp_nratio, dp_sratio, dp_mode, rgap, pb_kn, pb_ks, pb_rmul, pb_mcf, pb_ten, pb_coh, prop_count };
    static constexpr plab_property_desc properties[] = {
        // the linear part (eqs. 21–29)
        plab::linear_law::kn,        plab::linear_law::ks,      plab::linear_law::fric, plab::linear_law::dp_nratio,
        plab::linear_law::dp_sratio, plab::linear_law::dp_mode, plab::linear_law::rgap,
        plab::prop::number("pb_kn", "bond normal stiffness", "Pa/m", 1e12, 0.0, inf, PLAB_MAX_EXCLUSIVE, "k̄n, per bond area (eq. 47)"),
        plab::prop::number("pb_ks", "bond shear stiffness", "Pa/m", 1e12, 0.0, inf, PLAB_MAX_EXCLUSIVE, "k̄s, per bond area (eq. 48)"),
        plab::prop::number("pb_rmul", "bond radius multiplier", "1", 1.0, 0.0, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
         "λ: R̄ = λ min(R1, R2)"),
        plab::prop::number("pb_mcf", "moment-contribution factor", "1", 1.0, 0.0, 1.0, 0, "β̄ in the bond stresses (eqs. 49–50)"),
        plab::prop::number("pb_ten", "bond tensile strength", "Pa", inf, 0.0, inf, PLAB_MIN_EXCLUSIVE, "σc (eq. 45); inf: unbreakable"),
        plab::prop::number("pb_coh", "bond shear strength", "Pa", inf, 0.0, inf, PLAB_MIN_EXCLUSIVE, "τc (eq. 46); inf: unbreakable"),
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");

    enum Slot : int {
        shear_force_x, shear_force_y, shear_force_z,  // linear part, on end 2
        bond_state,                                   // 1 bonded, 0 not (the host's persist slot)
        bond_normal_force,                            // tension positive, N
        bond_shear_force_x, bond_shear_force_y, bond_shear_force_z,  // on end 2, N
        bond_moment_x, bond_moment_y, bond_moment_z,  // bending + twisting on end 2, N m
        slot_count
    };
    static constexpr plab_history_desc history[] = {
        plab::linear_law::shear_force_x,
        plab::linear_law::shear_force_y,
        plab::linear_law::shear_force_z,
        plab::history_desc("bond_state", 0.0, PLAB_SWAP_KEEP, "1 bonded, 0 unbonded or broken"),
        plab::history_desc("bond_normal_force", 0.0, PLAB_SWAP_KEEP, "bond normal force, tension positive, N"),
        plab::history_desc("bond_shear_force_x", 0.0, PLAB_SWAP_NEGATE, "bond shear force on end 2, x, N",
                           PLAB_HISTORY_TANGENTIAL),  // (the host turns it with the contact plane)
        plab::history_desc("bond_shear_force_y", 0.0, PLAB_SWAP_NEGATE, "bond shear force on end 2, y, N"),
        plab::history_desc("bond_shear_force_z", 0.0, PLAB_SWAP_NEGATE, "bond shear force on end 2, z, N"),
        plab::history_desc("bond_moment_x", 0.0, PLAB_SWAP_NEGATE, "bond moment on end 2, x, N m"),
        plab::history_desc("bond_moment_y", 0.0, PLAB_SWAP_NEGATE, "bond moment on end 2, y, N m"),
        plab::history_desc("bond_moment_z", 0.0, PLAB_SWAP_NEGATE, "bond moment on end 2, z, N m"),
    };
    static constexpr int persist_slot = bond_state;

    static double activity_range(const double* p) { return p[rgap]; }

    explicit LinearPBond(const double* p)
        : linear_{p[kn], p[ks], p[fric], p[dp_nratio], p[dp_sratio], int(p[dp_mode]), p[rgap]},
          kn_bar_(p[pb_kn]), ks_bar_(p[pb_ks]), lambda_(p[pb_rmul]), mcf_(p[pb_mcf]), ten_(p[pb_ten]), coh_(p[pb_coh]) {}

    void law(const Contact& c) const;

private:
    struct Section {
        double radius, area, inertia, polar;  // R̄, A, I, J
    };
    Section section(const Contact& c) const;
    Vec3 bond(const Contact& c, const Section& s, Vec3& moment, double& strain) const;
    void forget_bond(const Contact& c) const;

    plab::linear_law::Params linear_;
    double kn_bar_, ks_bar_, lambda_, mcf_, ten_, coh_;
};

// Bond cross-section: 2D a strip of unit thickness, 3D a disc (PFC).
LinearPBond::Section LinearPBond::section(const Contact& c) const {
    const double r = lambda_ * std::min(c.radius1(), c.radius2());
    if (c.dim() == 2) return {r, 2.0 * r, 2.0 * r * r * r / 3.0, 0.0};  // eq. 39 with δ = 1
    const double r4 = r * r * r * r;
    return {r, M_PI * r * r, M_PI * r4 / 4.0, M_PI * r4 / 2.0};
}

void LinearPBond::forget_bond(const Contact& c) const {
    for (int s = bond_normal_force; s <= bond_moment_z; ++s) c.history(s) = 0.0;
}

// Incremental bond force and moment (eqs. 47–48 and the moment analogue),
// then the strength checks (eqs. 49–50, §3.3.3). Returns the bond force on
// end 2 and its moment; a broken bond returns zero and marks the history.
Vec3 LinearPBond::bond(const Contact& c, const Section& s, Vec3& moment, double& strain) const {
    const Vec3 n = c.normal();
    const Vec3 v = c.rel_velocity();
    const double dt = c.dt();
    const double vn = plab::dot(v, n);
    const Vec3 vs = v - vn * n;

    double fn = c.history(bond_normal_force) + s.area * kn_bar_ * vn * dt;  // eq. 47, tension positive
    Vec3 fs = c.history_vec(bond_shear_force_x) - s.area * ks_bar_ * dt * vs;  // eq. 48, the stored fs in the plane

    // The stored moment splits into its twist, along the new normal, and its
    // bending part, turned into the new plane with the bending part's own
    // magnitude (not the whole moment's, as a tangential slot would be).
    const Vec3 m_old = c.history_vec(bond_moment_x);
    const Vec3 dtheta = c.rel_angular_velocity() * dt;
    const Vec3 dtheta_twist = plab::dot(dtheta, n) * n;
    Vec3 m_bend = plab::rotate_into_plane(m_old - plab::dot(m_old, n) * n, n) - kn_bar_ * s.inertia * (dtheta - dtheta_twist);
    Vec3 m_twist = c.dim() == 3 ? plab::dot(m_old, n) * n - ks_bar_ * s.polar * dtheta_twist : Vec3{};

    const double sigma = fn / s.area + mcf_ * plab::norm(m_bend) * s.radius / s.inertia;  // eq. 49
    const double tau = plab::norm(fs) / s.area + (c.dim() == 3 ? mcf_ * plab::norm(m_twist) * s.radius / s.polar : 0.0);  // eq. 50
    const double energy = 0.5 * fn * fn / (s.area * kn_bar_) + (ks_bar_ > 0 ? 0.5 * plab::dot(fs, fs) / (s.area * ks_bar_) : 0.0) +
                          (kn_bar_ > 0 ? 0.5 * plab::dot(m_bend, m_bend) / (kn_bar_ * s.inertia) : 0.0) +
                          (c.dim() == 3 && ks_bar_ > 0 ? 0.5 * plab::dot(m_twist, m_twist) / (ks_bar_ * s.polar) : 0.0);
    const int broke = sigma >= ten_ ? PLAB_BREAK_TENSION : (tau >= coh_ ? PLAB_BREAK_SHEAR : 0);
    if (broke) {
        c.history(bond_state) = -broke;  // the host records the break and leaves the contact unbonded
        c.add_break_energy(energy);
        forget_bond(c);
        moment = Vec3{};
        return Vec3{};
    }
    c.history(bond_normal_force) = fn;
    c.set_history_vec(bond_shear_force_x, fs);
    moment = m_bend + m_twist;
    c.set_history_vec(bond_moment_x, moment);
    strain += energy;
    return -fn * n + fs;
}

void LinearPBond::law(const Contact& c) const {
    double strain = 0;
    Vec3 force = plab::linear_law::apply(linear_, c, shear_force_x, strain);
    double k_t = std::max(linear_.kn, linear_.ks), k_r = 0;
    if (c.history(bond_state) > 0 && !c.with_wall()) {
        const Section s = section(c);
        Vec3 moment;
        force += bond(c, s, moment, strain);
        c.set_moment2(moment);
        c.set_moment1(-moment);
        k_t = std::max(linear_.kn + s.area * kn_bar_, linear_.ks + s.area * ks_bar_);
        k_r = kn_bar_ * s.inertia + ks_bar_ * s.polar;
    } else {
        forget_bond(c);
    }
    c.set_force(force);
    c.set_strain_energy(strain);
    c.set_stiffness(k_t, k_r);
}

} // namespace

PLAB_PLUGIN(plab::add_contact_model<LinearPBond>(r))
