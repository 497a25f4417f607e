// Pebble fill (pebble_fill.hpp): the surface as distance and inside tests,
// the lattice of candidate pebbles, the surface samples in a k-d tree, and
// the greedy cover over them.
#include "pebble_fill.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <string>

namespace plab {

namespace {

#ifdef PLAB_FUZZ_BUDGETS
constexpr double kBudget = 1.0 / 50;  // the sanitized fuzz build runs ~100x slower: the same paths, smaller
#else
constexpr double kBudget = 1;
#endif
constexpr double kMaxInside = 5e4 * kBudget;   // lattice points inside the shape (each costs a distance to the surface)
constexpr double kMaxLattice = 5e5 * kBudget;  // lattice points in the bounding box (outside ones are mostly skipped)
constexpr double kMaxSamples = 2e5 * kBudget;  // surface samples (the cover and the deviation visit each)
constexpr std::size_t kLeafSize = 16;

std::string number(double x) {
    std::ostringstream s;
    s.precision(6);
    s << x;
    return s.str();
}
std::string metres(double x) { return number(x) + " m"; }

[[noreturn]] void refuse(const std::string& why) { throw std::invalid_argument("pebble fill: " + why); }

double segment_distance(const Vec& p, const Vec& a, const Vec& b) {
    const Vec ab = b - a;
    const double length2 = ab.squaredNorm();
    const double t = length2 > 0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
    return (p - (a + t * ab)).norm();
}

// One element of the surface: a triangle, or in 2D an edge a -> b (c = b).
// The bounding sphere (centre, reach) lets a distance query skip it.
struct Element {
    Vec a, b, c;
    Vec normal = Vec::Zero();  // unit; zero for an edge or a degenerate triangle
    bool edge = false;         // 2D
    Vec centre = Vec::Zero();
    double reach = 0;
};

// The distance from a point to the surface, and on which side it is when
// that is plain: when the nearest point lies well inside a face (2D: an
// edge), the segment to it crosses no other part of the surface, so the
// face's side is the point's. Near an edge or a corner, 0: not known.
struct Nearest {
    double distance = kInf;
    int side = 0;  // +1 outside, -1 inside, 0 not known
};
constexpr double kWellInside = 1e-6;  // barycentric margin from a face's edges

Nearest edge_nearest(const Element& e, const Vec& p) {
    const Vec ab = e.b - e.a;
    const double length2 = ab.squaredNorm();
    const double t = length2 > 0 ? (p - e.a).dot(ab) / length2 : 0.0;
    const double left = ab.x() * (p.y() - e.a.y()) - ab.y() * (p.x() - e.a.x());  // the material's side
    const bool plain = t > kWellInside && t < 1 - kWellInside && left != 0;
    return {(p - (e.a + std::clamp(t, 0.0, 1.0) * ab)).norm(), plain ? (left > 0 ? -1 : 1) : 0};
}

// To a triangle: to its plane where p projects inside it, otherwise to the
// nearest of its edges.
Nearest element_nearest(const Element& e, const Vec& p) {
    if (e.edge) return edge_nearest(e, p);
    if (e.normal != Vec::Zero()) {
        const double height = (p - e.a).dot(e.normal);
        const Vec q = p - height * e.normal;
        const double wa = e.normal.dot((e.c - e.b).cross(q - e.b)), wb = e.normal.dot((e.a - e.c).cross(q - e.c)),
                     wc = e.normal.dot((e.b - e.a).cross(q - e.a));  // twice the areas opposite each corner
        if (wa >= 0 && wb >= 0 && wc >= 0) {
            const bool plain = std::min({wa, wb, wc}) > kWellInside * (wa + wb + wc) && height != 0;
            return {std::abs(height), plain ? (height > 0 ? 1 : -1) : 0};
        }
    }
    return {std::min({segment_distance(p, e.a, e.b), segment_distance(p, e.b, e.c), segment_distance(p, e.c, e.a)}), 0};
}

// Solid angle of the triangle abc seen from p, signed by its orientation
// (Van Oosterom and Strackee's formula).
double solid_angle(const Vec& p, const Element& e) {
    const Vec a = e.a - p, b = e.b - p, c = e.c - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double det = a.dot(b.cross(c));
    const double div = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    return 2 * std::atan2(det, div);
}

// The body surface, for the distance and inside tests the lattice needs.
class Surface {
public:
    Surface(const std::vector<Triangle>& triangles, int dim);
    Nearest nearest(const Vec& p) const;
    bool inside(const Vec& p) const;
    double enclosed() const { return enclosed_; }  // volume, 2D area
    Vec lo() const { return lo_; }
    Vec hi() const { return hi_; }
    const std::vector<Element>& elements() const { return elements_; }
    int dim() const { return dim_; }

private:
    int dim_;
    std::vector<Element> elements_;
    double enclosed_ = 0;
    Vec lo_ = Vec::Constant(kInf), hi_ = Vec::Constant(-kInf);
    mutable std::size_t hint_ = 0;  // the element nearest the last query: lattice neighbours share it
};

Surface::Surface(const std::vector<Triangle>& triangles, int dim) : dim_(dim) {
    for (const Triangle& t : triangles) {
        Element e{t[0], t[1], dim == 2 ? t[1] : t[2]};
        e.edge = dim == 2;
        if (dim == 2) e.a.z() = e.b.z() = e.c.z() = 0;
        if (!e.a.allFinite() || !e.b.allFinite() || !e.c.allFinite()) refuse("a surface vertex is not finite");
        const Vec n = (e.b - e.a).cross(e.c - e.a);
        const double longest2 = std::max({(e.b - e.a).squaredNorm(), (e.c - e.b).squaredNorm(), (e.a - e.c).squaredNorm()});
        if (dim == 3 && n.norm() > 1e-14 * longest2) e.normal = n.normalized();  // slivers: their edges only
        e.centre = (e.a + e.b + e.c) / 3;
        e.reach = std::max({(e.a - e.centre).norm(), (e.b - e.centre).norm(), (e.c - e.centre).norm()});
        for (const Vec* v : {&e.a, &e.b, &e.c}) lo_ = lo_.cwiseMin(*v), hi_ = hi_.cwiseMax(*v);
        enclosed_ += dim == 2 ? 0.5 * (e.a.x() * e.b.y() - e.b.x() * e.a.y()) : e.a.dot(e.b.cross(e.c)) / 6;
        elements_.push_back(e);
    }
}

// Brute force over the elements, skipping those whose bounding sphere is
// farther than the nearest found so far (started from the last query's).
Nearest Surface::nearest(const Vec& p) const {
    Nearest best = element_nearest(elements_[hint_], p);
    for (std::size_t i = 0; i < elements_.size(); ++i) {
        const Element& e = elements_[i];
        const double skip = best.distance + e.reach;
        if (i == hint_ || (p - e.centre).squaredNorm() >= skip * skip) continue;
        const Nearest n = element_nearest(e, p);
        if (n.distance < best.distance) best = n, hint_ = i;
    }
    return best;
}

// 3D: the generalised winding number (the solid angles over 4 pi), which
// degrades gracefully on a mesh with small gaps. 2D: the polygon's winding
// number by signed crossings of the ray to +x.
bool Surface::inside(const Vec& p) const {
    if (dim_ == 3) {
        double total = 0;
        for (const Element& e : elements_) total += solid_angle(p, e);
        return total > 2 * kPi;
    }
    int winding = 0;
    for (const Element& e : elements_) {
        const double side = (e.b.x() - e.a.x()) * (p.y() - e.a.y()) - (p.x() - e.a.x()) * (e.b.y() - e.a.y());
        if (e.a.y() <= p.y() && e.b.y() > p.y() && side > 0) ++winding;
        if (e.a.y() > p.y() && e.b.y() <= p.y() && side < 0) --winding;
    }
    return winding > 0;
}

// ---- Surface samples ----

struct Samples {
    std::vector<Vec> points;
    double covering = 0;  // every surface point is within this of a point
};

// How many pieces an element is cut into so that its samples come within
// `spacing` of every point of it: a triangle cut into n^2 copies of itself
// at 1/n is within L/(n sqrt 3) of their corners (L its longest edge; of
// the three angles a point makes with the corners one is >= 120 degrees);
// an edge in n pieces within length / 2n.
double pieces(const Element& e, int dim, double spacing) {
    if (dim == 2) return std::max(1.0, std::ceil((e.b - e.a).norm() / (2 * spacing)));
    const double longest = std::max({(e.b - e.a).norm(), (e.c - e.b).norm(), (e.a - e.c).norm()});
    return std::max(1.0, std::ceil(longest / (std::sqrt(3.0) * spacing)));
}

double sample_count(const Surface& s, double spacing) {
    double count = 0;
    for (const Element& e : s.elements()) {
        const double n = pieces(e, s.dim(), spacing);
        count += s.dim() == 2 ? n + 1 : (n + 1) * (n + 2) / 2;
    }
    return count;
}

Samples sample_surface(const Surface& s, double spacing) {
    const double count = sample_count(s, spacing);
    if (count > kMaxSamples)
        refuse("the surface needs about " + std::to_string(std::llround(count)) + " samples at tolerance " +
               metres(2 * spacing) + ", more than " + std::to_string(std::llround(kMaxSamples)) +
               ": use a tolerance of at least " + metres(2 * spacing * std::pow(count / kMaxSamples, 1.0 / (s.dim() - 1))));
    Samples out;
    for (const Element& e : s.elements()) {
        const int n = int(pieces(e, s.dim(), spacing));
        const Vec u = (e.b - e.a) / n, v = (e.c - e.a) / n;
        for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= (s.dim() == 2 ? 0 : n - i); ++j) out.points.push_back(e.a + i * u + j * v);
        const double longest = s.dim() == 2 ? 0.5 * u.norm() : std::max({u.norm(), v.norm(), (v - u).norm()}) / std::sqrt(3.0);
        out.covering = std::max(out.covering, longest);
    }
    return out;
}

// The samples in a k-d tree of boxes, for the samples near a pebble.
class SampleTree {
public:
    explicit SampleTree(const std::vector<Vec>& points);
    // Calls f(index) for each sample within `reach` of `centre` (and a few beyond).
    template <class F> void visit(const Vec& centre, double reach, F f) const;

private:
    struct Node {
        Vec lo, hi;
        std::size_t begin, end;  // into order_
        std::size_t left = 0, right = 0;  // children; 0: a leaf
    };
    std::size_t build(std::size_t begin, std::size_t end);
    const std::vector<Vec>& points_;
    std::vector<std::size_t> order_;
    std::vector<Node> nodes_;
};

SampleTree::SampleTree(const std::vector<Vec>& points) : points_(points), order_(points.size()) {
    for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = i;
    build(0, order_.size());
}

// Halves [begin, end) at the median along the box's longest side.
std::size_t SampleTree::build(std::size_t begin, std::size_t end) {
    Node node{Vec::Constant(kInf), Vec::Constant(-kInf), begin, end};
    for (std::size_t k = begin; k < end; ++k) node.lo = node.lo.cwiseMin(points_[order_[k]]), node.hi = node.hi.cwiseMax(points_[order_[k]]);
    const std::size_t at = nodes_.size();
    nodes_.push_back(node);
    if (end - begin <= kLeafSize) return at;
    int axis;
    (node.hi - node.lo).maxCoeff(&axis);
    const std::size_t mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](std::size_t i, std::size_t j) {
        return points_[i][axis] < points_[j][axis] || (points_[i][axis] == points_[j][axis] && i < j);
    });
    const std::size_t left = build(begin, mid);
    const std::size_t right = build(mid, end);
    nodes_[at].left = left, nodes_[at].right = right;
    return at;
}

template <class F> void SampleTree::visit(const Vec& centre, double reach, F f) const {
    const double reach2 = reach * reach * (1 + 1e-9);  // a margin: the caller decides exactly
    std::vector<std::size_t> stack{0};
    while (!stack.empty()) {
        const Node& n = nodes_[stack.back()];
        stack.pop_back();
        const Vec gap = (n.lo - centre).cwiseMax(centre - n.hi).cwiseMax(0.0);
        if (gap.squaredNorm() > reach2) continue;
        if (n.left == 0) {
            for (std::size_t k = n.begin; k < n.end; ++k) f(order_[k]);
        } else {
            stack.push_back(n.left), stack.push_back(n.right);
        }
    }
}

// ---- Candidate pebbles ----

// A cubic (2D: square) lattice through the bounding box's centre, so that a
// symmetric shape gets a symmetric lattice.
struct Lattice {
    Vec origin;
    double spacing;
    std::array<long, 3> half{0, 0, 0};  // points at origin + spacing * (-half .. half) per axis
    double points() const { return double(2 * half[0] + 1) * double(2 * half[1] + 1) * double(2 * half[2] + 1); }
};

// Spacing `threshold` / 2, so that a corner of a box along the lattice's
// axes, wherever the lattice falls, has a lattice point whose inscribed
// sphere comes within `threshold` of it (one whose offsets from the corner
// lie in [m, m + spacing) with m <= spacing: within 2 spacings), if
// min_radius lets so small a pebble be. Coarsened for the point budgets.
Lattice make_lattice(const Surface& s, double threshold) {
    Lattice l{(s.lo() + s.hi()) / 2, threshold / 2};
    if (s.dim() == 2) l.origin.z() = 0;
    l.spacing = std::max(l.spacing, std::pow(s.enclosed() / kMaxInside, 1.0 / s.dim()));
    for (;; l.spacing *= 1.1) {
        for (int c = 0; c < s.dim(); ++c) l.half[c] = long(std::floor((s.hi()[c] - l.origin[c]) / l.spacing));
        if (l.points() <= kMaxLattice) return l;
    }
}

struct Candidates {
    std::vector<Pebble> pebbles;  // in lattice order (the greedy's last tie-break)
    double largest = 0;           // the largest inscribed radius met
    std::size_t inside = 0;       // lattice points inside
};

// One lattice row along x. A point whose neighbour in the row is farther
// than a spacing from the surface is on the neighbour's side (the segment
// between them crosses no surface); nearer the surface, the nearest face
// tells the side, and only where that is an edge or a corner does the
// winding number. Outside points far from the surface need no distance
// either (it drops by at most a spacing per point).
void probe_row(const Surface& s, const Lattice& l, long j, long k, const PebbleFillOptions& o, Candidates& out) {
    const double step = l.spacing * (1 + 1e-9);
    bool known = false, inside = false;
    double clear = 0;  // a lower bound on the previous point's distance to the surface
    for (long i = -l.half[0]; i <= l.half[0]; ++i) {
        const Vec p = l.origin + l.spacing * Vec(double(i), double(j), double(k));
        const bool same_side = known && clear > step;
        if (same_side && !inside) {
            clear -= l.spacing;
            continue;
        }
        const Nearest n = s.nearest(p);
        clear = n.distance;
        if (!same_side) inside = n.side != 0 ? n.side < 0 : s.inside(p);
        known = true;
        if (!inside) continue;
        ++out.inside;
        out.largest = std::max(out.largest, clear);
        if (clear > 0 && clear >= o.min_radius) out.pebbles.push_back({p, std::min(clear, o.max_radius)});
    }
}

Candidates find_candidates(const Surface& s, const Lattice& l, const PebbleFillOptions& o) {
    Candidates out;
    for (long k = -l.half[2]; k <= l.half[2]; ++k)
        for (long j = -l.half[1]; j <= l.half[1]; ++j) probe_row(s, l, j, k, o, out);
    return out;
}

// ---- The greedy cover ----

// Which samples the pebbles placed so far bring within `threshold` of
// their union: a sample s is covered by pebble (c, r) when |s - c| - r is.
class Cover {
public:
    Cover(const Samples& s, double threshold)
        : points_(s.points), tree_(s.points), covered_(s.points.size(), 0), remaining_(s.points.size()), threshold_(threshold) {}
    std::size_t gain(const Pebble& p) const {
        std::size_t n = 0;
        tree_.visit(p.centre, p.radius + threshold_, [&](std::size_t k) { n += !covered_[k] && covers(p, k); });
        return n;
    }
    void take(const Pebble& p) {
        tree_.visit(p.centre, p.radius + threshold_, [&](std::size_t k) {
            if (covered_[k] || !covers(p, k)) return;
            covered_[k] = 1;
            --remaining_;
        });
    }
    std::size_t remaining() const { return remaining_; }

private:
    bool covers(const Pebble& p, std::size_t k) const { return (points_[k] - p.centre).norm() - p.radius <= threshold_; }
    const std::vector<Vec>& points_;
    SampleTree tree_;
    std::vector<char> covered_;
    std::size_t remaining_;
    double threshold_;
};

// A candidate's offer: how many uncovered samples it would cover (as last
// counted: gains only fall as pebbles are placed). The best: the largest
// gain, then radius, then the earliest candidate.
struct Offer {
    std::size_t gain;
    double radius;
    std::size_t index;
    bool operator<(const Offer& o) const {
        if (gain != o.gain) return gain < o.gain;
        if (radius != o.radius) return radius < o.radius;
        return index > o.index;
    }
};

// Lazy greedy: an offer recounted that still beats every other (stale,
// hence optimistic) offer is the best of all, as an eager recount of every
// candidate would find. With nothing covered by any offer, the largest
// candidate, so that the result is a body.
std::vector<Pebble> greedy_cover(const std::vector<Pebble>& candidates, Cover& cover, std::size_t max_count) {
    std::priority_queue<Offer> offers;
    for (std::size_t i = 0; i < candidates.size(); ++i)
        if (const std::size_t n = cover.gain(candidates[i])) offers.push({n, candidates[i].radius, i});
    std::vector<Pebble> placed;
    while (placed.size() < max_count && cover.remaining() > 0 && !offers.empty()) {
        Offer best = offers.top();
        offers.pop();
        best.gain = cover.gain(candidates[best.index]);
        if (best.gain == 0) continue;
        if (!offers.empty() && best < offers.top()) {
            offers.push(best);
            continue;
        }
        cover.take(candidates[best.index]);
        placed.push_back(candidates[best.index]);
    }
    if (placed.empty())
        placed.push_back(*std::max_element(candidates.begin(), candidates.end(),
                                           [](const Pebble& a, const Pebble& b) { return a.radius < b.radius; }));
    return placed;
}

// The largest distance from a sample to the union (pebbles inscribed: the
// samples are outside it, so this is the distance to its surface).
double sampled_deviation(const std::vector<Vec>& samples, const std::vector<Pebble>& pebbles) {
    double worst = 0;
    for (const Vec& s : samples) {
        double gap = kInf;
        for (const Pebble& p : pebbles) gap = std::min(gap, (s - p.centre).norm() - p.radius);
        worst = std::max(worst, gap);
    }
    return worst;
}

void check_options(const PebbleFillOptions& o) {
    if (o.dim != 2 && o.dim != 3) refuse("dim must be 2 or 3, got " + std::to_string(o.dim));
    if (!(o.tolerance > 0) || !std::isfinite(o.tolerance))
        refuse("the tolerance must be positive and finite, got " + metres(o.tolerance));
    if (!(o.min_radius >= 0)) refuse("min_radius must be zero or positive, got " + metres(o.min_radius));
    if (!(o.max_radius > 0)) refuse("max_radius must be positive, got " + metres(o.max_radius));
    if (o.min_radius > o.max_radius)
        refuse("min_radius " + metres(o.min_radius) + " is larger than max_radius " + metres(o.max_radius));
    if (o.max_count == 0) refuse("max_count must be at least 1");
}

void check_candidates(const Candidates& c, const Lattice& l, const PebbleFillOptions& o) {
    if (c.inside == 0)
        refuse("no point of a lattice of spacing " + metres(l.spacing) +
               " falls inside the shape: is it thinner than that, or not closed?");
    if (c.pebbles.empty())
        refuse("no pebble of min_radius " + metres(o.min_radius) + " fits in the shape: the largest that does is " +
               metres(c.largest) + " (found on a lattice of spacing " + metres(l.spacing) + ")");
}

} // namespace

PebbleFill fill_with_pebbles(const std::vector<Triangle>& surface, const PebbleFillOptions& options) {
    check_options(options);
    if (surface.empty()) refuse(options.dim == 2 ? "the boundary has no edges" : "the surface has no triangles");
    const Surface shape(surface, options.dim);
    if (!(shape.enclosed() > 0))
        refuse(std::string(options.dim == 2 ? "the boundary encloses no area (signed area " : "the surface encloses no volume (signed volume ") +
               number(shape.enclosed()) +
               (options.dim == 2 ? " m^2): it must be closed, outside boundaries counter-clockwise"
                                 : " m^3): it must be closed with outward normals (right-hand rule)"));
    // Half the tolerance goes to the gaps between samples, half to the cover.
    const double spacing = options.tolerance / 2, threshold = options.tolerance - spacing;
    Samples samples = sample_surface(shape, spacing);
    samples.covering = std::min(samples.covering, spacing);  // (<= by construction; not an ulp over)
    const Lattice lattice = make_lattice(shape, threshold);
    const Candidates candidates = find_candidates(shape, lattice, options);
    check_candidates(candidates, lattice, options);

    Cover cover(samples, threshold);
    PebbleFill fill;
    fill.pebbles = greedy_cover(candidates.pebbles, cover, options.max_count);
    fill.sampled_deviation = sampled_deviation(samples.points, fill.pebbles);
    fill.deviation = fill.sampled_deviation + samples.covering;
    fill.reached = fill.deviation <= options.tolerance;
    return fill;
}

} // namespace plab
