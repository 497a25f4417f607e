// Measurements of a fluid at rest and in motion (thesis §5.1, Table 1; the
// static tank and dam break cases): a time-averaged pressure against the
// hydrostatic profile, how far particles moved, how close they came to the
// tank's walls.
#include "measurement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

namespace plab {

namespace {

// Heights are measured in the frame of a tank that rises as ½ a t² from
// rest (frame_acceleration a, m/s²), so a tank accelerating upward is judged
// as one at rest under g + a.
double frame_rise(double a, double t) { return 0.5 * a * t * t; }

// hydrostatic_pressure_error: ||p̄ - ρ0 g (H - ȳ)|| / ||ρ0 g (H - ȳ)|| over
// the group's balls that started at or below `exclude_above` (the free
// surface truncates the kernel in the top rows), with p̄ and ȳ averaged over
// the samples from `average_from` on, weighted by the step (filters the
// acoustic ringing, period 2H/c0); before that, of the instantaneous values.
// Recorded every step it is the time average of the thesis's check.
Measurement hydrostatic_pressure_error(const Node& with, const World& w) {
    with.allow_keys({"group", "field", "rest_density", "gravity", "surface_level", "exclude_above", "average_from",
                     "frame_acceleration"});
    const int group = measured_group(with, w);
    const int field = w.fields.index(with.string_or("field", "sph_pressure"));
    if (field < 0) with.fail("this scene has no field \"" + with.string_or("field", "sph_pressure") + "\"");
    const double rho0 = with.at("rest_density").positive(), g = with.at("gravity").positive();
    const double H = with.at("surface_level").number(), top = with.number_or("exclude_above", kInf);
    const double from = with.number_or("average_from", 0.0), a = with.number_or("frame_acceleration", 0.0);
    struct State {
        std::vector<int> judged;  // balls below `top` at the start
        std::vector<double> p_sum, y_sum;
        double window = 0;
    };
    auto s = std::make_shared<State>();
    for (std::size_t i = 0; i < w.bodies.size(); ++i)
        if (w.bodies.group[i] == group && w.bodies.position[i].y() <= top) s->judged.push_back(int(i));
    s->p_sum.assign(s->judged.size(), 0.0);
    s->y_sum.assign(s->judged.size(), 0.0);
    return [s, field, rho0, g, H, from, a](const World& x) {
        const std::vector<double>& p = x.fields.column(field);
        const double rise = frame_rise(a, x.time);
        const bool averaging = x.time >= from && x.step_count > 0;
        if (averaging) s->window += x.last_dt;
        double err2 = 0, ref2 = 0;
        for (std::size_t k = 0; k < s->judged.size(); ++k) {
            const int i = s->judged[k];
            double pk = p[i], yk = x.bodies.position[i].y() - rise;
            if (averaging) {
                s->p_sum[k] += pk * x.last_dt;
                s->y_sum[k] += yk * x.last_dt;
                pk = s->p_sum[k] / s->window;
                yk = s->y_sum[k] / s->window;
            }
            const double exact = rho0 * g * (H - yk);
            err2 += (pk - exact) * (pk - exact);
            ref2 += exact * exact;
        }
        return ref2 > 0 ? std::sqrt(err2 / ref2) : std::nan("");
    };
}

// max_displacement: the largest distance of a ball of the group from where
// it started (in the frame of frame_acceleration), m.
Measurement max_displacement(const Node& with, const World& w) {
    with.allow_keys({"group", "frame_acceleration"});
    const int group = measured_group(with, w);
    const double a = with.number_or("frame_acceleration", 0.0);
    auto start = std::make_shared<std::vector<Vec>>(w.bodies.position);
    auto ids = std::make_shared<std::vector<BodyId>>(w.bodies.id);
    return [start, ids, group, a](const World& x) {
        const Vec rise(0, frame_rise(a, x.time), 0);
        double worst = 0;
        for (std::size_t i = 0; i < x.bodies.size() && i < start->size(); ++i)
            if (x.bodies.group[i] == group && x.bodies.id[i] == (*ids)[i])
                worst = std::max(worst, (x.bodies.position[i] - rise - (*start)[i]).norm());
        return worst;
    };
}

// min_clearance: the smallest distance of a centre of the group from the
// faces of the box [min, max] it should stay in (negative: it left), in the
// frame of frame_acceleration, m; the smallest over every sample so far.
Measurement min_clearance(const Node& with, const World& w) {
    with.allow_keys({"group", "min", "max", "frame_acceleration"});
    const int group = measured_group(with, w);
    const Vec lo = with.at("min").vec(w.dim), hi = with.at("max").vec(w.dim);
    const double a = with.number_or("frame_acceleration", 0.0);
    auto lowest = std::make_shared<double>(kInf);
    return [lowest, group, lo, hi, a, dim = w.dim](const World& x) {
        const Vec rise(0, frame_rise(a, x.time), 0);
        for (std::size_t i = 0; i < x.bodies.size(); ++i) {
            if (x.bodies.group[i] != group) continue;
            const Vec p = x.bodies.position[i] - rise;
            for (int c = 0; c < dim; ++c) *lowest = std::min({*lowest, p[c] - lo[c], hi[c] - p[c]});
        }
        return *lowest;
    };
}

// surface_height: the highest centre (y in 2D, z in 3D) of the group's balls
// whose x lies in [x_min, x_max], m; NaN when none does. With a band one
// spacing wide at the back wall it is the residual column height of a dam
// break, the second quantity Martin & Moyce (1952) measured.
Measurement surface_height(const Node& with, const World& w) {
    with.allow_keys({"group", "x_min", "x_max"});
    const int group = measured_group(with, w);
    const double lo = with.at("x_min").number(), hi = with.at("x_max").number(lo, kInf, true, false);
    return [group, lo, hi, up = w.dim - 1](const World& x) {
        double top = -kInf;
        for (std::size_t i = 0; i < x.bodies.size(); ++i) {
            const Vec& p = x.bodies.position[i];
            if (x.bodies.group[i] == group && p.x() >= lo && p.x() <= hi) top = std::max(top, p[up]);
        }
        return top > -kInf ? top : std::nan("");
    };
}

} // namespace

void register_sph_measurements(std::map<std::string, MeasurementInfo>& into) {
    into["hydrostatic_pressure_error"] = {
        "relative L2 distance of the (time-averaged from average_from) field from rest_density gravity (surface_level - y) "
        "over the group's balls that started below exclude_above [-]", hydrostatic_pressure_error};
    into["max_displacement"] = {"largest distance of a ball of the group from its start [m]", max_displacement};
    into["min_clearance"] = {"smallest distance of a centre of the group inside the box [min, max] so far [m]", min_clearance};
    into["surface_height"] = {"highest centre (y in 2D, z in 3D) of the group's balls with x_min <= x <= x_max; NaN if none [m]",
                              surface_height};
}

} // namespace plab
