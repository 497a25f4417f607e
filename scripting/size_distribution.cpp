#include "size_distribution.hpp"

#include "metrics.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

namespace plab {

namespace {

// A standard normal deviate by Box–Muller from the seeded generator (the
// std:: distributions differ between libraries).
double standard_normal(Rng& rng) {
    const double u1 = 1.0 - rng.uniform(0.0, 1.0);  // (0, 1]
    const double u2 = rng.uniform(0.0, 1.0);
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

// r in [a, b] with density ∝ r^-p (the number density of an even mass spread, p = dim).
double draw_power(Rng& rng, double a, double b, double p) {
    if (!(b > a)) return a;
    const double u = rng.uniform(0.0, 1.0), q = 1.0 - p;
    return std::pow(std::pow(a, q) + u * (std::pow(b, q) - std::pow(a, q)), 1.0 / q);
}

// ∫_a^b r^-p dr / (b - a): the number per unit mass fraction of a bin.
double number_per_mass(double a, double b, double p) {
    if (!(b > a)) return std::pow(a, -p);
    const double q = 1.0 - p;
    return (std::pow(b, q) - std::pow(a, q)) / (q * (b - a));
}

} // namespace

SizeDistribution::SizeDistribution(const Node& n, int dim, const std::string& scene_dir) {
    const std::string kind = n.at("distribution").choice({"uniform", "normal", "lognormal", "discrete", "sieve"});
    if (kind == "discrete") {
        read_discrete(n, dim);
        return;
    }
    if (kind == "sieve") {
        read_sieve(n, dim, scene_dir);
        return;
    }
    if (kind == "uniform") {
        n.allow_keys({"distribution", "min", "max"});
        kind_ = Kind::uniform;
    } else if (kind == "normal") {
        n.allow_keys({"distribution", "mean", "std", "min", "max"});
        kind_ = Kind::normal;
        centre_ = n.at("mean").positive();
        spread_ = n.at("std").positive();
    } else {
        n.allow_keys({"distribution", "median", "sigma", "min", "max"});
        kind_ = Kind::lognormal;
        centre_ = std::log(n.at("median").positive());
        spread_ = n.at("sigma").positive();
    }
    lo_ = n.at("min").positive();
    hi_ = n.at("max").positive();
    if (!(hi_ > lo_)) n.at("max").fail("max must exceed min = " + std::to_string(lo_) + " m");
    if (kind_ != Kind::uniform) {  // the truncation must keep a fair share of the distribution
        const double a = ((kind_ == Kind::normal ? lo_ : std::log(lo_)) - centre_) / spread_;
        const double b = ((kind_ == Kind::normal ? hi_ : std::log(hi_)) - centre_) / spread_;
        if (b < -4 || a > 4)
            n.at(b < -4 ? "max" : "min").fail("the range [min, max] lies more than 4 standard deviations from the "
                                              "distribution's centre: almost no radius would be drawn in it");
    }
}

void SizeDistribution::read_discrete(const Node& n, int dim) {
    n.allow_keys({"distribution", "radii", "fractions", "by"});
    kind_ = Kind::table;
    const Node radii = n.at("radii"), fractions = n.at("fractions");
    radii.expect_array();
    fractions.expect_array();
    if (radii.size() == 0 || radii.size() != fractions.size())
        fractions.fail("expected one fraction per radius (" + std::to_string(radii.size()) + " radii)");
    const bool by_mass = n.string_or("by", "number") == "mass";
    if (n.has("by")) n.at("by").choice({"number", "mass"});
    double total = 0, sum = 0;
    std::vector<double> weight;
    for (std::size_t k = 0; k < radii.size(); ++k) {
        const double r = radii.at(k).positive(), f = fractions.at(k).number(0.0, 1.0);
        sum += f;
        weight.push_back(by_mass ? f / std::pow(r, dim) : f);
        edges_lo_.push_back(r);
        edges_hi_.push_back(r);
    }
    if (std::fabs(sum - 1.0) > 1e-9) {
        std::ostringstream s;
        s << "the fractions add up to " << sum << "; they must add up to 1";
        fractions.fail(s.str());
    }
    for (double w : weight) cumulative_.push_back(total += w);
    for (double& c : cumulative_) c /= total;
    lo_ = *std::min_element(edges_lo_.begin(), edges_lo_.end());
    hi_ = *std::max_element(edges_hi_.begin(), edges_hi_.end());
}

void SizeDistribution::read_sieve(const Node& n, int dim, const std::string& scene_dir) {
    n.allow_keys({"distribution", "file", "diameter_column", "passing_column"});
    kind_ = Kind::table;
    power_ = dim;
    json ref = {{"file", n.at("file").string()}, {"x_column", n.at("diameter_column").value()},
                {"y_column", n.at("passing_column").value()}};
    const auto curve = reference_curve(Node(ref, n.path()), scene_dir);
    if (curve.size() < 2) n.at("file").fail("a gradation needs two sieves or more");
    const double scale = curve.back().second > 1.0 + 1e-9 ? 0.01 : 1.0;  // percent passing
    if (std::fabs(curve.back().second * scale - 1.0) > 1e-6 || curve.front().second != 0.0)
        n.at("file").fail("the curve must pass 0 at its smallest sieve and all (1, or 100 %) at its largest");
    double total = 0;
    for (std::size_t k = 0; k + 1 < curve.size(); ++k) {
        const double a = 0.5 * curve[k].first, b = 0.5 * curve[k + 1].first;
        const double mass = (curve[k + 1].second - curve[k].second) * scale;
        if (!(b > a) || mass < 0) n.at("file").fail("sieve diameters must rise and the fraction passing must not fall");
        if (mass == 0) continue;
        edges_lo_.push_back(a);
        edges_hi_.push_back(b);
        cumulative_.push_back(total += mass * number_per_mass(a, b, power_));
    }
    for (double& c : cumulative_) c /= total;
    lo_ = edges_lo_.front();
    hi_ = edges_hi_.back();
}

double SizeDistribution::draw(Rng& rng) const {
    switch (kind_) {
    case Kind::uniform: return rng.uniform(lo_, hi_);
    case Kind::normal:
    case Kind::lognormal:
        for (;;) {  // truncated: drawn again outside [min, max] (the constructor checked it keeps a fair share)
            const double z = centre_ + spread_ * standard_normal(rng);
            const double r = kind_ == Kind::normal ? z : std::exp(z);
            if (r >= lo_ && r <= hi_) return r;
        }
    case Kind::table: break;
    }
    const double u = rng.uniform(0.0, 1.0);
    const std::size_t k = std::size_t(std::lower_bound(cumulative_.begin(), cumulative_.end(), u) - cumulative_.begin());
    const std::size_t bin = std::min(k, cumulative_.size() - 1);
    return draw_power(rng, edges_lo_[bin], edges_hi_[bin], power_);
}

std::vector<double> SizeDistribution::draw(long count, Rng& rng) const {
    std::vector<double> r(static_cast<std::size_t>(count));
    for (double& x : r) x = draw(rng);
    std::sort(r.begin(), r.end(), std::greater<>());
    return r;
}

} // namespace plab
