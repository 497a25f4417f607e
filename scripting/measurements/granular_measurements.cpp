// Measurements of a granular deposit: the slope of a heap's flank, its
// angle of repose (the angle_of_repose case); the stress from the contacts;
// the velocity gradient of a sheared cell's flow (the periodic_shear case).
#include "measurement.hpp"

#include "../generators.hpp"
#include "../servo.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace plab {

namespace {

// The least-squares slope dy/dx of points (x, y); NaN for fewer than three.
double fitted_slope(const std::vector<double>& x, const std::vector<double>& y) {
    const std::size_t n = x.size();
    if (n < 3) return std::nan("");
    double mx = 0, my = 0;
    for (std::size_t k = 0; k < n; ++k) { mx += x[k]; my += y[k]; }
    mx /= double(n);
    my /= double(n);
    double sxy = 0, sxx = 0;
    for (std::size_t k = 0; k < n; ++k) {
        sxy += (x[k] - mx) * (y[k] - my);
        sxx += (x[k] - mx) * (x[k] - mx);
    }
    return sxy / sxx;
}

// heap_angle: the angle of a heap's flank to the horizontal, degrees: the
// surface (each vertical strip's highest ball top, centre + radius) in
// strips of `strip_width` from x_min to x_max, fitted by a straight line. In
// 3D the highest ball of a strip over all z: the profile through a conical
// heap's apex. Only balls with centres between `y_min` and `y_max` (both
// optional) are the heap's, not grains still in a hopper above it or fallen
// past its base; with `y_min` (the base's level) a strip without a ball
// reads y_min, the bare base. NaN while fewer than three strips have a
// surface.
Measurement heap_angle(const Node& with, const World& w) {
    with.allow_keys({"group", "x_min", "x_max", "strip_width", "y_min", "y_max"});
    const int group = measured_group(with, w);
    const double lo = with.at("x_min").number(), hi = with.at("x_max").number();
    if (!(hi > lo)) with.at("x_max").fail("the flank [x_min, x_max] is empty: x_max must exceed x_min = " + std::to_string(lo));
    const double width = with.at("strip_width").number();
    if (!(width > 0) || !(width <= (hi - lo) / 3))
        with.at("strip_width").fail("strip width " + std::to_string(width) + " m is outside (0, (x_max - x_min) / 3]: "
                                    "a line is fitted to three strips or more");
    const double y_min = with.has("y_min") ? with.at("y_min").number() : -kInf;
    const double y_max = with.has("y_max") ? with.at("y_max").number() : kInf;
    if (!(y_max > y_min)) with.at("y_max").fail("y_max must exceed y_min = " + std::to_string(y_min));
    const std::size_t strips = std::size_t((hi - lo) / width);
    return [group, lo, width, strips, y_min, y_max](const World& x) {
        std::vector<double> top(strips, y_min);
        for (std::size_t i = 0; i < x.bodies.size(); ++i) {
            const double y = x.bodies.position[i].y();
            if (x.bodies.group[i] != group || y < y_min || y > y_max) continue;
            const double s = (x.bodies.position[i].x() - lo) / width;
            if (!(s >= 0) || s >= double(strips)) continue;
            double& t = top[std::size_t(s)];
            t = std::max(t, y + x.bodies.radius[i]);
        }
        std::vector<double> xs, ys;
        for (std::size_t s = 0; s < strips; ++s)
            if (top[s] > -kInf) { xs.push_back(lo + (double(s) + 0.5) * width); ys.push_back(top[s]); }  // (none empty with y_min)
        return std::atan(std::fabs(fitted_slope(xs, ys))) * 180.0 / M_PI;
    };
}

// velocity_gradient: the least-squares slope d v_x / d y of the group's
// balls' velocities against their heights, each ball taken inside the cell
// (a sheared cell's wrap moves its x velocity with it): the flow's shear
// rate, the imposed one when the mean profile is the linear profile of
// simple shear, less when the flow bands or slips at the boundary.
Measurement velocity_gradient(const Node& with, const World& w) {
    with.allow_keys({"group"});
    const int group = measured_group(with, w);
    return [group](const World& x) {
        std::vector<double> ys, vs;
        for (std::size_t i = 0; i < x.bodies.size(); ++i) {
            if (x.bodies.group[i] != group) continue;
            Vec v = x.bodies.velocity[i];
            ys.push_back(x.bodies.cell.wrap(x.bodies.position[i], &v).y());
            vs.push_back(v.x());
        }
        return fitted_slope(ys, vs);
    };
}

// The region a contact stress is taken in: a box [lo, hi], or the space
// between pairs of parallel walls (a sample between its platens, whose
// volume changes as they move).
struct StressRegion {
    Box box{Vec::Zero(), Vec::Zero()};
    std::vector<std::pair<int, int>> walls;  // when set: the region between each pair
};

// The region's volume now (2D: area x 1 m), and whether a contact point
// lies in it. Between walls, points up to 1 % of the walls' distance
// beyond either wall count: a wall contact's point lies half its overlap
// inside the wall.
struct Slab {
    Vec origin;  // a point of wall a
    Vec across;  // a's unit normal towards b over their distance: (x - origin) . across is 0 at a, 1 at b
};
struct RegionNow {
    double volume = 1;
    std::vector<Slab> slabs;  // between walls
    Box box{Vec::Zero(), Vec::Zero()};
    int dim = 3;
    bool contains(const Vec& c) const {
        if (slabs.empty()) {
            for (int d = 0; d < dim; ++d)
                if (c[d] < box.lo[d] || c[d] > box.hi[d]) return false;
            return true;
        }
        for (const Slab& slab : slabs) {
            const double s = (c - slab.origin).dot(slab.across);
            if (s < -0.01 || s > 1.01) return false;
        }
        return true;
    }
};

RegionNow region_now(const World& x, const StressRegion& r) {
    RegionNow now;
    now.dim = x.dim;
    now.box = r.box;
    if (r.walls.empty()) {
        for (int d = 0; d < x.dim; ++d) now.volume *= r.box.hi[d] - r.box.lo[d];
        return now;
    }
    for (const auto& [a, b] : r.walls) {
        const Facet& fa = x.walls.facets[std::size_t(x.walls.walls[std::size_t(a)].facets[0])];
        const Facet& fb = x.walls.facets[std::size_t(x.walls.walls[std::size_t(b)].facets[0])];
        const Vec towards = fb.a - fa.a;  // (the distance is along a's normal, whatever the facets' vertices)
        const double d = wall_distance(x, a, b);
        Vec n = wall_normal(x, a);
        if (n.dot(towards) < 0) n = -n;
        now.volume *= d;
        now.slabs.push_back({fa.a, n / d});
    }
    return now;
}

// The stress in a region from the contacts whose point lies in it (Love–
// Weber, as PFC's measurement logic): sigma = -(1/V) sum_c l_c (x) f_c,
// tension positive, with f_c the force on end 2 and l_c the branch from end
// 1's centre to end 2's (ball–ball) or to the wall's surface (ball–wall:
// the wall is outside the volume, which the walls then bound exactly: a
// packing at rest between walls gives their stress). In a periodic cell
// the branch is the minimum image's and a contact point outside the cell
// counts at its image, so a box equal to the cell gives the stress of the
// cell, every contact once.
Eigen::Matrix3d contact_stress_in(const World& x, const StressRegion& region) {
    const RegionNow now = region_now(x, region);
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    for (std::size_t m = 0; m < x.model_count(); ++m)
        for (const ContactTable& t : {x.model(m).balls(), x.model(m).walls()})
            for (std::size_t k = 0; k < t.size(); ++k) {
                if (!t.active(k) || !now.contains(x.bodies.cell.wrap(t.point(k)))) continue;
                const Vec from = x.bodies.position[t.end1(k)];
                const Vec l = t.with_wall() ? Vec(t.normal(k) * (t.gap(k) + t.end_radius(k, false)))
                                            : Vec(x.bodies.cell.image(from, x.bodies.position[t.end2(k)]) - from);  // (the minimum-image branch)
                sum -= l * t.force(k).transpose();
            }
    return sum / now.volume;
}

// The region of a contact_stress: "min" and "max", or "walls" (dim pairs).
StressRegion read_stress_region(const Node& with, const World& w) {
    StressRegion r;
    if (with.has("walls") == (with.has("min") || with.has("max")))
        with.fail("a contact stress is taken in a box (min, max) or between walls (walls: pairs of wall names), one of the two");
    if (with.has("walls")) {
        const Node pairs = with.at("walls");
        pairs.expect_array();
        if (pairs.size() != std::size_t(w.dim))
            pairs.fail("expected " + std::to_string(w.dim) + " pairs of walls in " + std::to_string(w.dim) + "D (one per direction), got " +
                       std::to_string(pairs.size()));
        for (std::size_t i = 0; i < pairs.size(); ++i) r.walls.push_back(read_wall_pair(pairs.at(i), w));
        return r;
    }
    r.box = Box{with.at("min").vec(w.dim), with.at("max").vec(w.dim)};
    for (int d = 0; d < w.dim; ++d)
        if (!(r.box.lo[d] < r.box.hi[d])) with.at("max").fail("the box's max must exceed its min in every direction");
    return r;
}

// contact_stress: one component of contact_stress_in() (the symmetric part
// for a shear component), or the pressure -trace / dim.
Measurement contact_stress(const Node& with, const World& w) {
    with.allow_keys({"min", "max", "walls", "component"});
    const StressRegion region = read_stress_region(with, w);
    const Node cn = with.at("component");
    const std::string comp = w.dim == 2 ? cn.choice({"xx", "yy", "xy", "pressure"})
                                        : cn.choice({"xx", "yy", "zz", "xy", "xz", "yz", "pressure"});
    const int i = comp == "pressure" ? -1 : comp[0] - 'x', j = comp == "pressure" ? -1 : comp[1] - 'x';
    const int dim = w.dim;
    return [region, i, j, dim](const World& x) {
        const Eigen::Matrix3d s = contact_stress_in(x, region);
        if (i < 0) return -s.trace() / dim;
        return 0.5 * (s(i, j) + s(j, i));
    };
}

// kinetic_stress: the kinetic (Reynolds) part of the stress in a box,
// sigma = -(1/V) sum_i m_i v'_i (x) v'_i over the balls whose centre (taken
// inside the cell) lies in it, tension positive, with v' the velocity less
// a sheared cell's flow (the peculiar velocity; the velocity itself in any
// other space): what the contact stress leaves out in a dilute flow.
Measurement kinetic_stress(const Node& with, const World& w) {
    with.allow_keys({"min", "max", "component"});
    const Box box{with.at("min").vec(w.dim), with.at("max").vec(w.dim)};
    for (int d = 0; d < w.dim; ++d)
        if (!(box.lo[d] < box.hi[d])) with.at("max").fail("the box's max must exceed its min in every direction");
    const Node cn = with.at("component");
    const std::string comp = w.dim == 2 ? cn.choice({"xx", "yy", "xy", "pressure"})
                                        : cn.choice({"xx", "yy", "zz", "xy", "xz", "yz", "pressure"});
    const int i = comp == "pressure" ? -1 : comp[0] - 'x', j = comp == "pressure" ? -1 : comp[1] - 'x';
    const int dim = w.dim;
    double volume = 1;
    for (int d = 0; d < dim; ++d) volume *= box.hi[d] - box.lo[d];
    return [box, i, j, dim, volume](const World& x) {
        Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
        for (std::size_t b = 0; b < x.bodies.size(); ++b) {
            Vec v = x.bodies.velocity[b];
            const Vec c = x.bodies.cell.wrap(x.bodies.position[b], &v);
            bool inside = true;
            for (int d = 0; d < dim; ++d) inside &= c[d] >= box.lo[d] && c[d] <= box.hi[d];
            if (!inside) continue;
            v.x() -= x.bodies.cell.affine_velocity(c);
            sum -= x.bodies.mass[b] * v * v.transpose();
        }
        sum /= volume;
        if (i < 0) return -sum.trace() / dim;
        return sum(i, j);
    };
}

// wall_distance: the distance between two parallel planar walls, e.g. a
// sample's height between its platens (axial strain).
Measurement wall_distance_between(const Node& with, const World& w) {
    with.allow_keys({"walls"});
    const auto [a, b] = read_wall_pair(with.at("walls"), w);
    return [a = a, b = b](const World& x) { return wall_distance(x, a, b); };
}

} // namespace

void register_granular_measurements(std::map<std::string, MeasurementInfo>& into) {
    into["heap_angle"] = {"angle of a heap's flank to the horizontal: a line fitted to the highest ball top of each strip of "
                          "strip_width from x_min to x_max, of the balls with y_min <= y <= y_max (optional; an empty strip reads y_min) [degrees]",
                          heap_angle};
    into["contact_stress"] = {"stress in the box [min, max], or between walls: [[a, b], ...] (one pair of parallel walls per "
                              "direction; the volume follows them), from the contacts whose point lies in it, "
                              "-(1/V) sum of branch (x) force (Love-Weber; tension positive; a wall contact's branch ends on "
                              "the wall's surface): component xx, yy, zz, xy, xz, yz (symmetric part) or pressure (-trace/dim) [Pa]",
                              contact_stress};
    into["kinetic_stress"] = {"kinetic stress in the box [min, max]: -(1/V) sum of m v' (x) v' over the balls whose centre lies "
                              "in it, v' the velocity less a sheared cell's flow (tension positive): component xx, yy, zz, xy, "
                              "xz, yz or pressure (-trace/dim) [Pa]",
                              kinetic_stress};
    into["velocity_gradient"] = {"least-squares slope d v_x / d y of the group's balls' x velocities against their heights in "
                                  "the cell: a sheared cell's flow rate (the imposed domain.shear.rate for a linear mean profile) [1/s]",
                                  velocity_gradient};
    into["wall_distance"] = {"distance between two parallel planar walls, walls: [a, b] (their names), along a's normal [m]",
                             wall_distance_between};
}

} // namespace plab
