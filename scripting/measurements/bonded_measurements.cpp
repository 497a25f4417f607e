// Measurements of bonded structures (parallel bonds, thesis §3.3, §6.2; the
// cantilever cases): where a clamp ends, the fibre stress of a bent beam
// against beam theory, the load at which the first bond would break (the
// lattice is linear until then), and where and how the first bond broke.
#include "measurement.hpp"

#include <plab/abi.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

namespace plab {

namespace {

int group_of(const Node& with, const World& w) {
    const std::string g = with.at("group").string();
    const int group = w.find_group(g);
    if (group < 0) with.at("group").fail("unknown group \"" + g + "\"");
    return group;
}

int index_of(const Node& id_node, const World& w) {
    const long id = id_node.integer(0, long(w.bodies.next_id) - 1);
    for (std::size_t i = 0; i < w.bodies.size(); ++i)
        if (w.bodies.id[i] == BodyId(id)) return int(i);
    id_node.fail("no ball has id " + std::to_string(id));
}

// clamp_line: where the clamped material ends, averaged over the rows — the
// clamp line of the continuum beam the lattice stands for. The clamped balls
// are the group's fully fixed ones; balls whose centres lie within half a
// radius in y are one row, and a row ends at its last clamped centre + radius, m.
Measurement clamp_line(const Node& with, const World& w) {
    with.allow_keys({"group"});
    const int group = group_of(with, w);
    return [group](const World& x) {
        struct End {
            double y, end, r;  // centre height, centre x + radius, radius
            bool operator<(const End& o) const { return y < o.y; }
        };
        std::vector<End> ends;
        for (std::size_t i = 0; i < x.bodies.size(); ++i)
            if (x.bodies.group[i] == group && x.bodies.fixity[i] == dof_all)
                ends.push_back({x.bodies.position[i].y(), x.bodies.position[i].x() + x.bodies.radius[i], x.bodies.radius[i]});
        if (ends.empty()) return std::nan("");
        std::stable_sort(ends.begin(), ends.end());
        double sum = 0, row_y = ends[0].y, row_end = -kInf;
        int rows = 1;
        for (const End& e : ends) {
            if (e.y - row_y > 0.5 * e.r) {  // the next row
                sum += row_end;
                ++rows;
                row_y = e.y;
                row_end = -kInf;
            }
            row_end = std::max(row_end, e.end);
        }
        return (sum + row_end) / rows;
    };
}

// fibre_stress_error: σxx of the balls on the group's top and bottom rows
// with x in [x_from, x_to] against Euler–Bernoulli σ = −M y / I, M = P
// (x_load − x), I = height³/12 per unit thickness, y from the mid-height:
// RMS of the difference over the RMS of −M y / I. Rows and x are the balls'
// positions at the start (the beam deflects); x_load is the loaded ball's
// (load_id) position now. The ball stress (ball_stress() of plab_host/world.hpp, over the
// ball's own area) times area_ratio is the stress of the continuum, whose
// area per ball differs: a hexagonal lattice gives each ball the cell
// 2√3 R², so π/(2√3).
Measurement fibre_stress_error(const Node& with, const World& w) {
    with.allow_keys({"group", "load", "load_id", "height", "x_from", "x_to", "area_ratio"});
    const int group = group_of(with, w);
    const int loaded = index_of(with.at("load_id"), w);
    const double load = with.at("load").number(), inertia = std::pow(with.at("height").positive(), 3) / 12;
    const double x_from = with.at("x_from").number(), x_to = with.at("x_to").number();
    const double area_ratio = with.at("area_ratio").positive();
    double y_min = kInf, y_max = -kInf;
    for (std::size_t i = 0; i < w.bodies.size(); ++i)
        if (w.bodies.group[i] == group) {
            y_min = std::min(y_min, w.bodies.position[i].y());
            y_max = std::max(y_max, w.bodies.position[i].y());
        }
    struct Fibre {
        int index;
        double x, y;  // at the start, y from the mid-height
    };
    auto fibres = std::make_shared<std::vector<Fibre>>();
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        const Vec& p = w.bodies.position[i];
        const double r = w.bodies.radius[i];
        const bool outer = std::fabs(p.y() - y_min) < 0.1 * r || std::fabs(p.y() - y_max) < 0.1 * r;
        if (w.bodies.group[i] == group && outer && p.x() >= x_from && p.x() <= x_to)
            fibres->push_back({int(i), p.x(), p.y() - 0.5 * (y_min + y_max)});
    }
    if (fibres->empty()) with.at("x_from").fail("no ball of the top or bottom row lies in [x_from, x_to]");
    return [=](const World& x) {
        const auto sigma = ball_stress(x);
        const double x_load = x.bodies.position[loaded].x();
        double diff2 = 0, ref2 = 0;
        for (const Fibre& f : *fibres) {
            const double theory = -load * (x_load - f.x) * f.y / inertia;
            diff2 += std::pow(sigma[f.index](0, 0) * area_ratio - theory, 2);
            ref2 += theory * theory;
        }
        return ref2 > 0 ? std::sqrt(diff2 / ref2) : std::nan("");
    };
}

// The model instance with bonds (a bond_state history slot: linear_pbond).
std::size_t bonded_instance(const Node& where, const World& w) {
    for (std::size_t m = 0; m < w.model_count(); ++m) {
        try {
            w.model(m).history_slot("bond_state");
            return m;
        } catch (const std::out_of_range&) {
        }
    }
    where.fail("this scene has no contact model with bonds (linear_pbond)");
}

// linear_first_break: the load at which the first bond would break, by
// linearity — the lattice is linear-elastic until a bond breaks, so under
// the load P applied now a bond at σ/σc of its strength breaks at P σc/σ.
// Per 2D bond (a strip of unit thickness, half-width R̄ = pb_rmul min(R1, R2),
// area A = 2R̄, I = 2R̄³/3): σ = Fn/A + β̄ |M| R̄ / I (eq. 49, β̄ = pb_mcf),
// τ = |Fs| / A (eq. 50; no twist in 2D). criterion: "tension_or_shear"
// (default: whichever comes first), "tension", "shear", or
// "tension_at_centre" (σ with β̄ = 0: the stress on the bond's centre line).
// tensile_strength (Pa, default the model's pb_ten) gives the load under
// another strength rule (the thesis's eq. 43) from the same solve.
// give: "load" (N, default), "x", "y" (m: the bond's contact point) or
// "in_tension" (1, or 0 for shear) of the bond that breaks first.
Measurement linear_first_break(const Node& with, const World& w) {
    with.allow_keys({"load", "criterion", "tensile_strength", "give"});
    if (w.dim != 2) with.fail("linear_first_break takes 2D bonds (eqs. 49-50 without twist); this scene is 3D");
    const double load = with.at("load").number();
    const std::string criterion =
        with.has("criterion") ? with.at("criterion").choice({"tension_or_shear", "tension", "shear", "tension_at_centre"})
                              : "tension_or_shear";
    const std::string give = with.has("give") ? with.at("give").choice({"load", "x", "y", "in_tension"}) : "load";
    const std::size_t bonded = bonded_instance(with, w);
    const ModelView inst = w.model(bonded);
    const int state = inst.history_slot("bond_state"), fn = inst.history_slot("bond_normal_force");
    const int fs = inst.history_slot("bond_shear_force_x"), mz = inst.history_slot("bond_moment_z");
    const double sigma_c = with.number_or("tensile_strength", inst.property("pb_ten"), 0.0, kInf, true, false);
    const double tau_c = inst.property("pb_coh");
    const double rmul = inst.property("pb_rmul"), beta = criterion == "tension_at_centre" ? 0.0 : inst.property("pb_mcf");
    const bool tension = criterion != "shear", shear = criterion == "tension_or_shear" || criterion == "shear";
    return [=](const World& x) {
        const ContactTable s = x.model(bonded).balls();
        double worst = 0;  // the largest use of its strength, σ/σc or τ/τc
        std::size_t first = 0;
        bool first_in_tension = false;
        for (std::size_t k = 0; k < s.size(); ++k) {
            const double* h = s.history(k);
            if (h[state] <= 0) continue;
            const double r_bar = std::min(s.end_radius(k, false), s.end_radius(k, true)) * rmul;
            const double area = 2 * r_bar, inertia = 2 * r_bar * r_bar * r_bar / 3;
            const double sigma = h[fn] / area + beta * std::fabs(h[mz]) * r_bar / inertia;  // eq. 49
            const double tau = std::hypot(h[fs], h[fs + 1]) / area;                          // eq. 50
            const double use_t = tension ? sigma / sigma_c : 0, use_s = shear ? tau / tau_c : 0;
            if (std::max(use_t, use_s) > worst) {
                worst = std::max(use_t, use_s);
                first = k;
                first_in_tension = use_t >= use_s;
            }
        }
        if (worst <= 0) return std::nan("");  // no bond is loaded (yet)
        if (give == "load") return load / worst;
        if (give == "in_tension") return first_in_tension ? 1.0 : 0.0;
        const Vec point = s.point(first);
        return give == "x" ? point.x() : point.y();
    };
}

// first_bond_break: where (x, y, m), when (time, s) and how (in_tension: 1,
// or 0 for shear) the first bond of the run broke; NaN until one has.
Measurement first_bond_break(const Node& with, const World&) {
    with.allow_keys({"give"});
    const std::string give = with.at("give").choice({"x", "y", "time", "in_tension"});
    return [give](const World& x) {
        if (x.bond_breaks.empty()) return std::nan("");
        const BondBreak& b = x.bond_breaks.front();
        if (give == "x") return b.point.x();
        if (give == "y") return b.point.y();
        if (give == "time") return b.time;
        return b.mode == PLAB_BREAK_TENSION ? 1.0 : 0.0;
    };
}

} // namespace

void register_bonded_measurements(std::map<std::string, MeasurementInfo>& into) {
    into["clamp_line"] = {"where the group's fully fixed balls end (last centre + radius), mean over their rows [m]", clamp_line};
    into["fibre_stress_error"] = {
        "RMS of (area_ratio sigma_xx - (-M y / I)) over the RMS of -M y / I on the group's top and bottom rows in "
        "[x_from, x_to]; M = load (x of load_id - x), I = height^3/12 [-]", fibre_stress_error};
    into["linear_first_break"] = {
        "the load (load: applied now) at which the first bond breaks by linearity, eqs. 49-50 (criterion "
        "tension_or_shear, tension, shear, tension_at_centre; tensile_strength, default pb_ten); give load [N], x, y [m] "
        "or in_tension [1/0]",
        linear_first_break};
    into["first_bond_break"] = {"the run's first broken bond: give x, y [m], time [s] or in_tension [1/0]; NaN before",
                                first_bond_break};
}

} // namespace plab
