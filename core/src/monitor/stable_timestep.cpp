// The nominal stable step: before any contact exists (balls falling into a
// box) the automatic step must still be safe, so each assigned group pair is
// asked, through one synthetic touching contact between its lightest balls,
// what stiffness or step limit it will bring.
#include "monitor/monitor.hpp"

#include <plab_host/errors.hpp>

#include "forces/tangential_history.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace plab {

namespace {

struct Probe {
    double mass = kInf, radius = 0, inertia = 0;
    bool any = false;
};

// The probe's force must be finite with the undeclared inputs NaN, and the
// undeclared outputs must still hold their NaN sentinels.
template <class Outputs>
void check_declared_io(const ModelInstance& inst, const double* force, const Outputs& outputs) {
    const std::string who = "contact model '" + inst.model + "' ";
    if (!(std::isfinite(force[0]) && std::isfinite(force[1]) && std::isfinite(force[2])))
        throw PluginError(who + "gives a non-finite force on a nominal touching contact when the inputs its `io` does not "
                                "declare are NaN: its law reads one of them; add it to `io` (abi.h, PLAB_IO_*)");
    for (const auto& o : outputs)
        if (!inst.uses(o.bit) && !std::all_of(o.value, o.value + o.width, [](double v) { return std::isnan(v); }))
            throw PluginError(who + "writes " + o.column + " but its `io` does not declare it; add it to `io` (abi.h, PLAB_IO_*)");
}

StableStep probe_contact(const ModelInstance& inst, int dim, const Probe& a, const Probe& b, bool wall) {
    const double gap = inst.desc->range_kind == PLAB_RANGE_GAP ? std::min(inst.range, 0.0) : 0.0;
    const double dist = inst.desc->range_kind == PLAB_RANGE_DISTANCE ? std::min(inst.range, a.radius + b.radius)
                                                                     : a.radius + b.radius + gap;
    double normal[3] = {1, 0, 0}, zero3[3] = {0, 0, 0}, force[3] = {0, 0, 0}, m1[3] = {0, 0, 0}, m2[3] = {0, 0, 0};
    double mass2 = wall ? kInf : b.mass;
    double eff_mass = wall ? a.mass : a.mass * b.mass / (a.mass + b.mass);
    double eff_radius = wall ? a.radius : a.radius * b.radius / (a.radius + b.radius);
    double r2 = wall ? 0.0 : b.radius, strain = 0, slip = 0, dash = 0, kt = 0, kr = 0, dtl = kInf, dt = 0;
    std::int32_t e1 = 0, e2 = 0;
    std::uint8_t active = 1;
    std::vector<double> history(std::size_t(inst.stride) + 1);
    for (int h = 0; h < inst.stride; ++h) history[h] = inst.desc->history[h].default_value;
    turn_tangential_history(*inst.desc, history.data(), std::size_t(inst.stride), normal, nullptr, 1);  // (as every call)
    // fields: a probe reads each field's default value
    std::vector<double> field_value(inst.fields_read.size() + 1, 0.0);
    std::vector<const double*> cols(inst.fields_read.size() + 1, field_value.data());
    std::vector<double> acc(2 * inst.fields_accumulated.size() + 2, 0.0);
    std::vector<double*> acc1(inst.fields_accumulated.size() + 1, &acc[0]), acc2(inst.fields_accumulated.size() + 1, &acc[1]);
    plab_contact_batch batch{sizeof(plab_contact_batch)};
    batch.dim = uint32_t(dim);
    batch.count = 1;
    batch.end2_is_wall = wall;
    batch.history_stride = uint32_t(inst.stride);
    batch.dt = dt;
    batch.end1 = &e1; batch.end2 = &e2; batch.active = &active;
    batch.normal = normal; batch.gap = &gap; batch.distance = &dist;
    batch.rel_velocity = zero3; batch.rel_angular_velocity = zero3;
    batch.radius1 = &a.radius; batch.radius2 = &r2; batch.mass1 = &a.mass; batch.mass2 = &mass2;
    batch.eff_mass = &eff_mass; batch.eff_radius = &eff_radius;
    batch.body_fields = cols.data();
    batch.history = history.data();
    batch.force = force; batch.moment1 = m1; batch.moment2 = m2;
    batch.strain_energy = &strain; batch.slip_energy = &slip; batch.dashpot_energy = &dash;
    batch.stiffness_translational = &kt; batch.stiffness_rotational = &kr; batch.dt_limit = &dtl;
    batch.accumulate1 = acc1.data(); batch.accumulate2 = acc2.data();
    double released = 0;
    batch.break_energy = &released;
    batch.stage = PLAB_STAGE_FORCES;
    // a model that declares its optional inputs and outputs (abi.h, PLAB_IO_*)
    // gets NaN in the others, as in a packed batch, and NaN sentinels in the
    // outputs it does not write: a mistake in the declaration shows here
    const double nan = std::numeric_limits<double>::quiet_NaN();
    double nan3[3] = {nan, nan, nan}, r1 = a.radius, m1_in = a.mass;
    if (!inst.uses(PLAB_IO_REL_ANGULAR_VELOCITY)) batch.rel_angular_velocity = nan3;
    if (!inst.uses(PLAB_IO_RADII)) { r1 = nan; r2 = nan; }
    if (!inst.uses(PLAB_IO_MASSES)) { m1_in = nan; mass2 = nan; }
    if (!inst.uses(PLAB_IO_EFF_MASS)) eff_mass = nan;
    if (!inst.uses(PLAB_IO_EFF_RADIUS)) eff_radius = nan;
    batch.radius1 = &r1;
    batch.mass1 = &m1_in;
    const struct { std::uint32_t bit; double* value; int width; const char* column; } outputs[] = {
        {PLAB_IO_MOMENTS, m1, 3, "moment1"}, {PLAB_IO_MOMENTS, m2, 3, "moment2"},
        {PLAB_IO_STIFFNESS_ROTATIONAL, &kr, 1, "stiffness_rotational"}, {PLAB_IO_DT_LIMIT, &dtl, 1, "dt_limit"},
        {PLAB_IO_BREAK_ENERGY, &released, 1, "break_energy"}};
    for (const auto& o : outputs)
        if (!inst.uses(o.bit)) std::fill_n(o.value, o.width, nan);
    if (inst.desc->compute(inst.state, inst.props.data(), &batch) != 0)
        throw PluginError("contact model '" + inst.model + "' failed on a nominal touching contact");
    check_declared_io(inst, force, outputs);
    for (const auto& o : outputs)  // what the host takes for an output the model does not write
        if (!inst.uses(o.bit)) std::fill_n(o.value, o.width, o.bit == PLAB_IO_DT_LIMIT ? kInf : 0.0);
    StableStep out;
    auto consider = [&](double dt_candidate, const std::string& why) {
        if (dt_candidate < out.critical) out = {dt_candidate, why};
    };
    if (kt > 0) consider(std::sqrt(a.mass / kt), "model " + inst.model + ": sqrt(m/k) of one contact");
    if (!wall && kt > 0) consider(std::sqrt(b.mass / kt), "model " + inst.model + ": sqrt(m/k) of one contact");
    const double kr_a = kr + kt * a.radius * a.radius;
    if (kr_a > 0) consider(std::sqrt(a.inertia / kr_a), "model " + inst.model + ": sqrt(I/k_r) of one contact");
    consider(dtl, "model " + inst.model + ": its step limit");
    if (kt <= 0 && !(dtl < kInf))
        throw PluginError("contact model '" + inst.model + "' reports no stable timestep for a touching contact: its law must call set_stiffness() or "
                          "set_dt_limit() for every active contact — c.set_stiffness(k) with the contact's stiffness "
                          "in N/m, or c.set_dt_limit(dt) in s when the stiffness vanishes at first touch (as Hertz's does)");
    return out;
}

} // namespace

StableStep Monitor::nominal_timestep() const {
    const int ng = in_.groups.group_count();
    std::vector<Probe> lightest(ng);
    for (std::size_t i = 0; i < in_.bodies.size(); ++i) {
        Probe& p = lightest[in_.bodies.group[i]];
        if (!p.any || in_.bodies.mass[i] < p.mass) p = {in_.bodies.mass[i], in_.bodies.radius[i], in_.bodies.inertia[i], true};
    }
    std::vector<bool> wall_group(ng, false);
    for (const Wall& w : in_.walls.walls) wall_group[w.group] = true;
    StableStep best;
    for (int a = 0; a < ng; ++a)
        for (int b = a; b < ng; ++b) {
            const int inst = in_.groups.assigned(a, b);
            if (inst < 0) continue;
            for (int side = 0; side < 2; ++side) {
                const int ball_g = side ? b : a, other = side ? a : b;
                if (!lightest[ball_g].any) continue;
                StableStep s;
                if (lightest[other].any) s = probe_contact(*in_.instances[inst], in_.dim, lightest[ball_g], lightest[other], false);
                else if (wall_group[other]) s = probe_contact(*in_.instances[inst], in_.dim, lightest[ball_g], Probe{}, true);
                else continue;
                if (s.critical < best.critical) {
                    best = s;
                    best.limited_by.insert(best.limited_by.find(':'), " for groups " + in_.groups.group_name(ball_g) + "-" + in_.groups.group_name(other));
                }
            }
        }
    return best;
}

} // namespace plab
