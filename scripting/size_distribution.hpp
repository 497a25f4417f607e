// The radius distribution of a random fill (issue 36), as DEM users give
// it (LIGGGHTS fix particledistribution/discrete, PFC's size ranges and
// gradation curves): the object form of a generator's "radius",
//   {"distribution": "uniform", "min", "max"}
//   {"distribution": "normal", "mean", "std", "min", "max"}       truncated
//   {"distribution": "lognormal", "median", "sigma", "min", "max"} sigma of ln r, truncated
//   {"distribution": "discrete", "radii": [...], "fractions": [...], "by": "number" | "mass"}
//   {"distribution": "sieve", "file", "diameter_column", "passing_column"}
// The sieve curve is a gradation: the cumulative mass fraction (0-1, or
// percent when its last value exceeds 1) passing each sieve diameter, read
// as a reference CSV is; within each pair of sieves the mass is spread
// evenly over the diameter. Radii are drawn by number from the seeded
// generator (a "by": "mass" fraction, and the sieve's mass fractions,
// weighted by 1/r^3, or 1/r^2 in 2D).
#pragma once

#include "generators.hpp"
#include "json_reader.hpp"

#include <string>
#include <vector>

namespace plab {

class SizeDistribution {
public:
    // `n` is the generator's "radius" object; errors name its paths.
    SizeDistribution(const Node& n, int dim, const std::string& scene_dir);
    double min() const { return lo_; }
    double max() const { return hi_; }
    double draw(Rng& rng) const;
    // `count` radii, largest first (the order a fill places them in).
    std::vector<double> draw(long count, Rng& rng) const;

private:
    enum class Kind { uniform, normal, lognormal, table } kind_;
    double lo_ = 0, hi_ = 0, centre_ = 0, spread_ = 0;  // normal: mean, std; lognormal: ln median, sigma
    // table: bins [edge_k, edge_k+1) by number, each drawn with density ∝ r^-power within
    // (discrete: zero-width bins), their cumulative number fractions
    std::vector<double> edges_lo_, edges_hi_, cumulative_;
    double power_ = 0;
    void read_discrete(const Node& n, int dim);
    void read_sieve(const Node& n, int dim, const std::string& scene_dir);
};

} // namespace plab
