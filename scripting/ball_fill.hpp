// What the ball generators (generators.cpp) and the inlets (body_flows.cpp)
// share: a generator entry's material, its box, adding one ball, and the
// background grid that places balls without overlap.
#pragma once

#include "generators.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace plab {

class SizeDistribution;

struct Material {
    double radius_lo = 0, radius_hi = 0, density = 0, damping = 0, viscous = 0;
    int group = 0;
    std::uint8_t fixity = 0;
};

// An entry's "radius" (a value, a range [min, max] where `radius_range`,
// or the bounds of `sizes`), "density" (or "mass" where `allow_mass`),
// damping, "group" and "fix"; errors name their paths.
Material read_material(const Node& n, World& w, bool radius_range, bool allow_mass = false,
                       const SizeDistribution* sizes = nullptr);
Box read_box(const Node& n, int dim);
void add(World& w, const Material& m, const Vec& p, double radius, const Vec& v = Vec::Zero(),
         const Vec& spin = Vec::Zero());

// The background grid of a random fill: cells at least a diameter wide
// (a ball's neighbours are then within one cell), and not more cells than
// balls (tiny balls in a big box need no fine grid).
class FillGrid {
public:
    FillGrid(const Box& box, int dim, double largest_radius, long count) : box_(box), dim_(dim) {
        double volume = 1;
        for (int c = 0; c < dim; ++c) volume *= box.hi[c] - box.lo[c];
        cell_ = std::max(2 * largest_radius, std::pow(volume / double(count), 1.0 / dim));
        for (int c = 0; c < dim; ++c) dims_[c] = std::max(1L, long((box.hi[c] - box.lo[c]) / cell_) + 1);
        grid_.resize(std::size_t(dims_[0] * dims_[1] * dims_[2]));
    }
    // A position for a ball of radius r inside the box, from rng; false when the box is too thin for it.
    bool draw_position(Rng& rng, double r, Vec& p) const {
        p = Vec::Zero();
        bool fits = true;
        for (int c = 0; c < dim_; ++c) {
            if (box_.hi[c] - box_.lo[c] < 2 * r) fits = false;
            p[c] = rng.uniform(box_.lo[c] + r, box_.hi[c] - r);
        }
        return fits;
    }
    // A ball already there (a body of the world), which later ones must not overlap.
    void occupy(const Vec& p, double r) {
        const long cx = cell_of(p, 0), cy = cell_of(p, 1), cz = dim_ == 3 ? cell_of(p, 2) : 0;
        grid_[std::size_t((cz * dims_[1] + cy) * dims_[0] + cx)].push_back(int(placed.size()));
        placed.push_back(p);
        radii.push_back(r);
    }
    // Places the ball when it overlaps none placed before.
    bool place(const Vec& p, double r) {
        const long cx = cell_of(p, 0), cy = cell_of(p, 1), cz = dim_ == 3 ? cell_of(p, 2) : 0;
        for (long z = std::max(0L, cz - 1); z <= std::min(dims_[2] - 1, cz + 1); ++z)
            for (long y = std::max(0L, cy - 1); y <= std::min(dims_[1] - 1, cy + 1); ++y)
                for (long x = std::max(0L, cx - 1); x <= std::min(dims_[0] - 1, cx + 1); ++x)
                    for (int q : grid_[std::size_t((z * dims_[1] + y) * dims_[0] + x)])
                        if ((placed[std::size_t(q)] - p).norm() < radii[std::size_t(q)] + r) return false;
        grid_[std::size_t((cz * dims_[1] + cy) * dims_[0] + cx)].push_back(int(placed.size()));
        placed.push_back(p);
        radii.push_back(r);
        return true;
    }
    std::vector<Vec> placed;
    std::vector<double> radii;

private:
    long cell_of(const Vec& p, int c) const { return std::clamp(long((p[c] - box_.lo[c]) / cell_), 0L, dims_[c] - 1); }
    Box box_;
    int dim_;
    double cell_ = 0;
    std::array<long, 3> dims_{1, 1, 1};
    std::vector<std::vector<int>> grid_;
};

} // namespace plab
