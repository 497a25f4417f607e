// Unresolved fluid–particle coupling of SPH fluid and DEM solids (thesis
// §4.1–4.2, eqs. 52, 68–75, 81–82). Two parts, one library:
//
//  pass `fluid_particle_drag` (phase RATES_DONE, stage 30: after the SPH
//  density, EOS and wall pressure of this cycle) over the active fluid–solid
//  pairs of the `fluid_particle` model:
//    * voidage of each fluid particle, ε_f = 1 - Σ_p V_p W_fp (eq. 52 in its
//      discrete form, as the thesis code sums it), floored at `min_voidage`;
//    * at each solid, Shepard interpolation with V_f = m_f/ρ_f (eqs. 68, 71,
//      82): S_p = Σ V_f W_pf, ε_p, ū_f and p̄;
//    * the total fluid force on the solid, drag K(ε_p, Re)(ū_f - v_p)
//      (eqs. 69–73, drag_law.hpp) plus buoyancy, stored in per-body fields.
//  contact model `fluid_particle` (force stage), assigned to fluid × solid:
//    * hands each solid's fluid force out over its fluid neighbours in
//      proportion to V_f W_pf / S_p (eq. 81): the pair force on the solid is
//      F_p V_f W_pf / S_p and the fluid particle receives its opposite, so
//      momentum is exchanged pair by pair and conserved to round-off, and
//      the shares add up to F_p on the solid.
//
// Buoyancy (`buoyancy`): 0, -V_p ∇p with the SPH gradient
// Σ V_f (p_f - p̄) ∇_p W_pf (the p̄ subtraction removes the error of a
// truncated kernel near a wall); 1, thesis eq. 75, -ε_p ρ_f V_p g. The
// reaction of either goes back to the fluid with the drag (eq. 81 returns
// "F_p^b"), which is Newton's third law for the pressure the solid displaces.
//
// The pair force acts through the centres: the model cancels the moment the
// host would add at the contact point (an unresolved solid feels no drag
// torque).
#include <plab/coupling/drag_law.hpp>

#include <plab/sph/kernels.hpp>
#include <plab/sph/material.hpp>

#include <plab/pass.hpp>

#include <cmath>
#include <limits>
#include <vector>

namespace {

using plab::Vec3;
using plab::coupling::DragInput;
using plab::coupling::Drag2d;
using plab::sph::Kernel;
using plab::sph::KernelKind;

constexpr double inf = std::numeric_limits<double>::infinity();

// The voidage and Shepard sums use the fluid's kernel, and the drag its
// density: the SPH package's material (sph_fluid), which a scene material of
// the fluid gives as it gives the sph model.
using plab::sph::FluidMaterial;
// drag_2d and buoyancy by index (Drag2d; 0 pressure gradient, 1 eq. 75)
constexpr const char* drag_2d_names[] = {"cylinder", "thesis"};
constexpr const char* buoyancy_names[] = {"pressure_gradient", "hydrostatic"};

// Per-body fields shared by the pass (writes) and the model (reads).
constexpr plab_field_desc solid_volume_field = plab::field_desc("fp_solid_volume", "m3", 0.0);  // V_p on solids, 0 elsewhere
constexpr plab_field_desc shepard_field = plab::field_desc("fp_shepard", "1", 0.0);             // S_p, eq. 82
constexpr plab_field_desc force_x_field = plab::field_desc("fp_force_x", "N", 0.0);             // fluid force on the solid
constexpr plab_field_desc force_y_field = plab::field_desc("fp_force_y", "N", 0.0);
constexpr plab_field_desc force_z_field = plab::field_desc("fp_force_z", "N", 0.0);
constexpr plab_field_desc drag_coefficient_field = plab::field_desc("fp_drag_coefficient", "N s/m", 0.0);  // K = |F_d|/|w|
constexpr plab_field_desc density_field = plab::field_desc("sph_density", "kg/m3", 1000.0);

struct FluidParticleDrag {
    static constexpr const char* name = "fluid_particle_drag";
    static constexpr const char* doc =
        "Unresolved SPH-DEM coupling (thesis 4.1): fluid voidage from the solids in its kernel (eq. 52), "
        "Shepard-interpolated voidage, fluid velocity and pressure at each solid (eqs. 68, 71, 82), Ergun / Wen-Yu "
        "drag (eqs. 69-73) and buoyancy (-V grad p, or eq. 75); the `fluid_particle` model returns the force to the "
        "fluid (eq. 81). Runs after sph_eos and sph_wall_pressure.";
    static constexpr uint32_t phase = PLAB_PHASE_RATES_DONE;
    static constexpr uint32_t stage = 30;  // after sph_density_integration (0), sph_eos (10), sph_wall_pressure (20)
    using material = FluidMaterial;

    enum Prop : int {
        fluid_group, solid_group, smoothing_length, kernel, rest_density, mu, drag_2d, buoyancy, min_voidage, gx, gy, gz,
        prop_count
    };
    static constexpr plab_property_desc properties[] = {
        plab::prop::group("fluid_group", "group of the SPH fluid", "the fluid balls the solids are coupled to"),
        plab::prop::group("solid_group", "group of the solid particles", "the DEM balls the fluid drags"),
        plab::sph::fluid::smoothing_length,
        plab::sph::fluid::kernel,
        plab::sph::fluid::rest_density,  // rho_f of the drag law (eq. 70) and the eq. 75 buoyancy
        plab::prop::number("mu", "fluid dynamic viscosity mu_f", "Pa s", 1e-3, 0.0, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE,
         "in the Ergun branch and the Reynolds number (eqs. 70, 73)"),
        plab::prop::choice("drag_2d", "2D reading of the drag law", drag_2d_names, 0,
         "cylinder: 1/2 Cd rho A eps^-1.65 |w| w with A = d and a cylinder's Cd; thesis: eq. 70 on the disc area "
         "with a sphere's Cd (drag_law.hpp); no effect in 3D"),
        plab::prop::choice("buoyancy", "buoyancy law", buoyancy_names, 0,
         "pressure_gradient: -V_p grad p from the SPH pressure; hydrostatic: thesis eq. 75, -eps_p rho_f V_p g"),
        plab::prop::number("min_voidage", "lower bound of the fluid voidage", "1", 0.2, 0.0, 1.0,
         PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE, "eq. 52 can go below zero where a large solid sits in a small kernel"),
        plab::prop::number("gravity_x", "gravity, x", "m/s2", 0.0, -inf, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE, "the scene's gravity (eq. 75)"),
        plab::prop::number("gravity_y", "gravity, y", "m/s2", 0.0, -inf, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE, "the scene's gravity (eq. 75)"),
        plab::prop::number("gravity_z", "gravity, z", "m/s2", 0.0, -inf, inf, PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE, "the scene's gravity (eq. 75)"),
    };
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");

    enum Field : int { voidage, solid_volume, shepard, force_x, force_y, force_z, drag_coeff, density, pressure };
    static constexpr plab_field_desc fields[] = {
        plab::field_desc("voidage", "1", 1.0), solid_volume_field, shepard_field, force_x_field, force_y_field, force_z_field,
        drag_coefficient_field, density_field, plab::field_desc("sph_pressure", "Pa", 0.0)};

    explicit FluidParticleDrag(const double* p)
        : fluid_(int(p[fluid_group])), solid_(int(p[solid_group])), kind_(KernelKind(int(p[kernel]))),
          h_(p[smoothing_length]), rho_f_(p[rest_density]), mu_(p[mu]), law_2d_(Drag2d(int(p[drag_2d]))),
          thesis_buoyancy_(int(p[buoyancy]) == 1), min_voidage_(p[min_voidage]), g_{p[gx], p[gy], p[gz]} {}

    void run(const plab_pass_view& v) {
        const Kernel W{kind_, int(v.dim), h_};
        mark_solids(v);
        fluid_voidage(v, W);
        shepard_sums(v, W);
        for (uint32_t i = 0; i < v.body_count; ++i)
            if (v.group[i] == solid_) solid_force(v, i);
    }

private:
    struct Pair { int32_t fluid, solid; double r; Vec3 from_fluid; };  // from_fluid = x_solid - x_fluid

    Vec3 at(const double* col, int32_t i) const { return {col[3 * i], col[3 * i + 1], col[3 * i + 2]}; }
    double fluid_volume(const plab_pass_view& v, int32_t f) const {
        const double rho = v.fields[density][f];
        return v.mass[f] / (rho > 0 ? rho : rho_f_);
    }

    // V_p on solids (the model's way to tell the ends apart), 0 elsewhere;
    // the fluid–solid pairs of this cycle.
    void mark_solids(const plab_pass_view& v) {
        double* vol = v.fields[solid_volume];
        for (uint32_t i = 0; i < v.body_count; ++i)
            vol[i] = v.group[i] == solid_ ? plab::coupling::solid_volume(int(v.dim), v.radius[i]) : 0.0;
        pairs_.clear();
        for (uint32_t k = 0; k < v.contact_count; ++k) {
            if (v.contact_end2_is_wall[k]) continue;
            int32_t f = v.contact_end1[k], s = v.contact_end2[k];
            if (v.group[f] == solid_) std::swap(f, s);
            if (v.group[f] != fluid_ || v.group[s] != solid_) continue;
            const Vec3 from_fluid = plab::separation(v, f, s);  // (also across a periodic boundary)
            pairs_.push_back({f, s, plab::norm(from_fluid), from_fluid});
        }
    }

    // eq. 52: ε_f = 1 - Σ_p V_p W_fp.
    void fluid_voidage(const plab_pass_view& v, const Kernel& W) const {
        double* eps = v.fields[voidage];
        for (uint32_t i = 0; i < v.body_count; ++i) eps[i] = 1.0;
        for (const Pair& p : pairs_) eps[p.fluid] -= v.fields[solid_volume][p.solid] * W.value(p.r);
        for (uint32_t i = 0; i < v.body_count; ++i) eps[i] = std::max(eps[i], min_voidage_);
    }

    // eqs. 68, 71, 82 and the pressure gradient, summed per solid.
    void shepard_sums(const plab_pass_view& v, const Kernel& W) {
        sums_.assign(v.body_count, Sums{});
        for (const Pair& p : pairs_) {
            const double vw = fluid_volume(v, p.fluid) * W.value(p.r);
            Sums& s = sums_[p.solid];
            s.weight += vw;
            s.voidage += v.fields[voidage][p.fluid] * vw;
            s.velocity += at(v.velocity, p.fluid) * vw;
            s.pressure += v.fields[pressure][p.fluid] * vw;
        }
        // ∇p at the solid: Σ V_f (p_f - p̄) ∇_p W_pf, ∇_p W = dW/dr (x_p - x_f)/r
        for (const Pair& p : pairs_) {
            Sums& s = sums_[p.solid];
            if (s.weight <= 0 || p.r <= 0) continue;
            const double p_mean = s.pressure / s.weight;
            s.grad_p += p.from_fluid * (fluid_volume(v, p.fluid) * (v.fields[pressure][p.fluid] - p_mean) *
                                        W.derivative(p.r) / p.r);
        }
    }

    // eqs. 69–75: the fluid's force on solid i.
    void solid_force(const plab_pass_view& v, uint32_t i) const {
        const Sums& s = sums_[i];
        v.fields[shepard][i] = s.weight;
        Vec3 f{};
        double K = 0;
        if (s.weight > 0) {
            const double eps = s.voidage / s.weight;
            v.fields[voidage][i] = eps;
            const Vec3 slip = s.velocity / s.weight - at(v.velocity, int32_t(i));
            DragInput in;
            in.dim = int(v.dim);
            in.law_2d = law_2d_;
            in.voidage = eps;
            in.rho_f = rho_f_;
            in.mu = mu_;
            in.d = 2 * v.radius[i];
            K = plab::coupling::drag_coefficient(in, plab::norm(slip));
            f = K * slip;
            const double vol = v.fields[solid_volume][i];
            f += thesis_buoyancy_ ? Vec3{g_[0], g_[1], g_[2]} * (-eps * rho_f_ * vol) : s.grad_p * (-vol);
        }
        v.fields[force_x][i] = f.x;
        v.fields[force_y][i] = f.y;
        v.fields[force_z][i] = f.z;
        v.fields[drag_coeff][i] = K;
    }

    struct Sums { double weight = 0, voidage = 0, pressure = 0; Vec3 velocity{}, grad_p{}; };

    int fluid_, solid_;
    KernelKind kind_;
    double h_, rho_f_, mu_;
    Drag2d law_2d_;
    bool thesis_buoyancy_;
    double min_voidage_;
    double g_[3];
    std::vector<Pair> pairs_;
    std::vector<Sums> sums_;
};

struct FluidParticle {
    static constexpr const char* name = "fluid_particle";
    static constexpr const char* doc =
        "Returns the fluid force that the fluid_particle_drag pass computed for each solid to its fluid neighbours in "
        "proportion to V_f W_pf / S_p (thesis eqs. 81-82): equal and opposite pair forces through the centres. "
        "Assign to fluid x solid group pairs; needs the fluid_particle_drag pass.";
    static constexpr const char* timestep_rule =
        "per pair: explicit drag is stable while dt < m/K; half of min(m_solid/K, m_fluid/(K share)) with K the "
        "solid's drag coefficient from the pass; 1e30 s before any drag exists";
    static constexpr uint32_t range_kind = PLAB_RANGE_DISTANCE;
    static constexpr uint32_t io = PLAB_IO_RADII | PLAB_IO_MASSES | PLAB_IO_MOMENTS | PLAB_IO_DT_LIMIT;
    using material = FluidMaterial;

    enum Prop : int { smoothing_length, kernel, prop_count };
    static constexpr plab_property_desc properties[] = {plab::sph::fluid::smoothing_length, plab::sph::fluid::kernel};
    static_assert(sizeof(properties) / sizeof(properties[0]) == prop_count, "one description per property");

    enum Field : int { solid_volume, shepard, force_x, force_y, force_z, drag_coeff, density };
    static constexpr plab_field_desc fields_read[] = {solid_volume_field, shepard_field,          force_x_field,
                                                      force_y_field,      force_z_field,          drag_coefficient_field,
                                                      density_field};

    static double activity_range(const double* p) {
        return plab::sph::support_factor(KernelKind(int(p[kernel]))) * p[smoothing_length];
    }

    explicit FluidParticle(const double* p) : kind_(KernelKind(int(p[kernel]))), h_(p[smoothing_length]) {}

    void law(const plab::Contact& c) const {
        c.set_dt_limit(no_limit);
        if (c.with_wall()) return;
        const bool solid1 = c.field1(solid_volume) > 0, solid2 = c.field2(solid_volume) > 0;
        if (solid1 == solid2) return;  // fluid–fluid or solid–solid: not this model's pair
        const Kernel W{kind_, c.dim(), h_};
        const double r = c.distance();
        const double S = solid1 ? c.field1(shepard) : c.field2(shepard);
        if (r >= W.support() || !(S > 0)) return;
        // eq. 81: the solid's force F_p shared in proportion to V_f W_pf / S_p
        const auto solid_field = [&](int f) { return solid1 ? c.field1(f) : c.field2(f); };
        const double m_f = solid1 ? c.mass2() : c.mass1(), m_s = solid1 ? c.mass1() : c.mass2();
        const double rho_f = solid1 ? c.field2(density) : c.field1(density);
        const double share = (m_f / rho_f) * W.value(r) / S;
        const Vec3 on_solid = Vec3{solid_field(force_x), solid_field(force_y), solid_field(force_z)} * share;
        const Vec3 f2 = solid1 ? -on_solid : on_solid;  // force on end 2
        c.set_force(f2);
        cancel_arm_moments(c, f2);
        const double K = solid_field(drag_coeff);
        if (K > 0) c.set_dt_limit(0.5 * std::min(m_s / K, m_f / (K * share)));
    }

private:
    static constexpr double no_limit = 1e30;  // finite: the host reads +inf as "no step reported"

    // The host adds (point - x) × f at each end; cancel it so the pair force
    // acts through both centres. point - x1 = n (r + r1 - r2)/2 and
    // point - x2 = n (r1 - r2 - r)/2, with r the centre distance.
    static void cancel_arm_moments(const plab::Contact& c, const Vec3& f2) {
        const Vec3 n = c.normal();
        const double r = c.distance(), r1 = c.radius1(), r2 = c.radius2();
        const Vec3 arm1 = n * (0.5 * (r + r1 - r2)), arm2 = n * (0.5 * (r1 - r2 - r));
        c.set_moment1(plab::cross(arm1, f2));   // end 1 receives -f2, the host adds arm1 × (-f2)
        c.set_moment2(-plab::cross(arm2, f2));  // end 2 receives f2, the host adds arm2 × f2
    }

    KernelKind kind_;
    double h_;
};

} // namespace

PLAB_PLUGIN(plab::add_pass<FluidParticleDrag>(r) != 0 ? 1 : plab::add_contact_model<FluidParticle>(r))
