// Measurements of the coupled scenes (thesis §7: the settling disc, the
// two-phase dam break, the breakable plate): a per-body field over a group
// (the disc's voidage and fluid force), the balls outside a box (grains that
// left the tank), the pieces a bonded group is in, and the first bond break.
// None keeps state that a restart would lose: each is read from the world
// and its bond-break log.
#include "measurement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <unordered_map>
#include <vector>

namespace plab {

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// group_field: a per-body field (voidage, fp_force_y, ...) reduced over the
// group's balls, "reduce" mean (default), max, min or sum; NaN for an empty
// group. The disc of a sedimentation scene is a group of one.
Measurement group_field(const Node& with, const World& w) {
    with.allow_keys({"group", "field", "reduce"});
    const int group = measured_group(with, w);
    const std::string name = with.at("field").string();
    const int field = w.fields.index(name);
    if (field < 0) {
        std::string known;
        for (const auto& f : w.fields.names()) known += (known.empty() ? "" : ", ") + f;
        with.at("field").fail("no per-body field \"" + name + "\"; fields in this scene: " + (known.empty() ? "none" : known));
    }
    const std::string op = with.has("reduce") ? with.at("reduce").choice({"mean", "max", "min", "sum"}) : "mean";
    return [group, field, op](const World& x) {
        const std::vector<double>& v = x.fields.column(field);
        double acc = op == "max" ? -kInf : op == "min" ? kInf : 0.0;
        std::size_t n = 0;
        for (std::size_t i = 0; i < x.bodies.size(); ++i) {
            if (x.bodies.group[i] != group) continue;
            acc = op == "max" ? std::max(acc, v[i]) : op == "min" ? std::min(acc, v[i]) : acc + v[i];
            ++n;
        }
        if (n == 0) return kNaN;
        return op == "mean" ? acc / double(n) : acc;
    };
}

// count_outside: how many of the group's centres lie outside the box
// [min, max] now (grains that left the tank) [-].
Measurement count_outside(const Node& with, const World& w) {
    with.allow_keys({"group", "min", "max"});
    const int group = measured_group(with, w);
    const Vec lo = with.at("min").vec(w.dim), hi = with.at("max").vec(w.dim);
    return [group, lo, hi, dim = w.dim](const World& x) {
        double n = 0;
        for (std::size_t i = 0; i < x.bodies.size(); ++i) {
            if (x.bodies.group[i] != group) continue;
            const Vec& p = x.bodies.position[i];
            bool out = false;
            for (int c = 0; c < dim; ++c) out = out || p[c] < lo[c] || p[c] > hi[c];
            n += out;
        }
        return n;
    };
}

// The pieces of one group: balls joined by intact bonds (any model that
// keeps bonds, its ball-ball rows), found by union-find; `extra` adds the
// bonds between body indices that the log says broke later (to replay it).
struct Pieces {
    int count = 0, largest = 0;
};

Pieces pieces_of(const World& w, int group, const std::vector<std::pair<std::size_t, std::size_t>>& extra = {}) {
    std::vector<std::size_t> parent(w.bodies.size());
    std::iota(parent.begin(), parent.end(), std::size_t(0));
    const auto root = [&](std::size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    const auto join = [&](std::size_t i, std::size_t j) { parent[root(i)] = root(j); };
    for (std::size_t m = 0; m < w.model_count(); ++m) {
        const ContactTable c = w.model(m).balls();
        for (std::size_t k = 0; k < c.size(); ++k)
            if (c.bonded(k)) join(c.end1(k), c.end2(k));
    }
    for (const auto& [i, j] : extra)
        if (i < parent.size() && j < parent.size()) join(i, j);
    std::vector<int> size(w.bodies.size(), 0);
    Pieces p;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        if (w.bodies.group[i] != group) continue;
        const int s = ++size[root(i)];
        p.count += s == 1;
        p.largest = std::max(p.largest, s);
    }
    return p;
}

// fragments / largest_fragment: the number of pieces of the group joined by
// intact bonds (1: whole) and the balls in the largest [-].
Measurement fragments(const Node& with, const World& w) {
    with.allow_keys({"group"});
    const int group = measured_group(with, w);
    return [group](const World& x) { return double(pieces_of(x, group).count); };
}

Measurement largest_fragment(const Node& with, const World& w) {
    with.allow_keys({"group"});
    const int group = measured_group(with, w);
    return [group](const World& x) { return double(pieces_of(x, group).largest); };
}

// The two ends of every bond-break log entry, as body indices (none, -1,
// for a body no longer in the world).
std::vector<std::pair<std::size_t, std::size_t>> broken_pairs(const World& w) {
    std::unordered_map<BodyId, std::size_t> index;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) index[w.bodies.id[i]] = i;
    const auto at = [&](BodyId id) { const auto it = index.find(id); return it == index.end() ? std::size_t(-1) : it->second; };
    std::vector<std::pair<std::size_t, std::size_t>> out;
    for (const BondBreak& b : w.bond_breaks) out.emplace_back(at(b.id1), at(b.id2));
    return out;
}

// fragmented_at: the time the group first formed at least `pieces` (default
// 2) pieces joined by intact bonds: the time of the break that split it,
// replayed from the bond-break log, so it is exact however rarely it is
// sampled [s]; NaN until then. A group in that many pieces before any
// break (never bonded whole) gives the first sample's time.
Measurement fragmented_at(const Node& with, const World& w) {
    with.allow_keys({"group", "pieces"});
    const int group = measured_group(with, w);
    const int threshold = int(with.has("pieces") ? with.at("pieces").integer(2, 1L << 30) : 2);
    auto found = std::make_shared<double>(kNaN);  // a cache: the log gives the same answer again
    return [group, threshold, found](const World& x) {
        if (!std::isnan(*found) || pieces_of(x, group).count < threshold) return *found;
        // the first break j whose later breaks, restored, leave the group split
        const auto pairs = broken_pairs(x);
        const std::size_t n = pairs.size();
        std::size_t j = 0;
        while (j < n && pieces_of(x, group, {pairs.begin() + long(j) + 1, pairs.end()}).count < threshold) ++j;
        *found = j < n ? x.bond_breaks[j].time : x.time;
        return *found;
    };
}

// first_break: where and how the first bond of the run broke, "report" time
// [s], x, y, z [m] (the contact point) or mode (PLAB_BREAK_TENSION 1,
// PLAB_BREAK_SHEAR 2); NaN before any break.
Measurement first_break(const Node& with, const World&) {
    with.allow_keys({"report"});
    const std::string what = with.at("report").choice({"time", "x", "y", "z", "mode"});
    return [what](const World& x) {
        if (x.bond_breaks.empty()) return kNaN;
        const BondBreak& b = x.bond_breaks.front();
        if (what == "time") return b.time;
        if (what == "mode") return double(b.mode);
        return b.point[what == "x" ? 0 : what == "y" ? 1 : 2];
    };
}

} // namespace

void register_coupling_measurements(std::map<std::string, MeasurementInfo>& into) {
    into["group_field"] = {"a per-body field (voidage, fp_force_y, ...) over the group's balls, reduce mean (default), max, "
                           "min or sum [the field's unit]", group_field};
    into["count_outside"] = {"how many centres of the group lie outside the box [min, max] now [-]", count_outside};
    into["fragments"] = {"pieces of the group joined by intact bonds (1: whole) [-]", fragments};
    into["largest_fragment"] = {"balls in the group's largest piece joined by intact bonds [-]", largest_fragment};
    into["fragmented_at"] = {"time the group first formed `pieces` (default 2) pieces joined by intact bonds, from the "
                             "bond-break log; NaN until then [s]", fragmented_at};
    into["first_break"] = {"the run's first bond break: report time [s], x, y, z [m] or mode (1 tension, 2 shear); NaN "
                           "before it", first_break};
}

} // namespace plab
