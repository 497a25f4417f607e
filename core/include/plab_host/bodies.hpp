// Balls (2D discs of unit thickness, 3D spheres) as structure-of-arrays.
// A body's index may change; its id never does (contacts are keyed by id).
#pragma once

#include <plab_host/types.hpp>

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace plab {

struct BallSpec {
    Vec position = Vec::Zero();
    Vec velocity = Vec::Zero();
    Vec angular_velocity = Vec::Zero();
    double radius = 0;
    double density = 0;
    int group = 0;
    std::uint8_t fixity = 0;
    double local_damping = 0;
    double viscous_damping = 0;
};

// The per-body loops work on fixed blocks of bodies; a sum over the bodies
// is taken per block and the blocks added in order, so it does not depend on
// the thread count.
constexpr std::size_t kBodyBlock = 1024;
inline std::size_t body_blocks(std::size_t bodies) { return (bodies + kBodyBlock - 1) / kBodyBlock; }

// A periodic cell (LAMMPS's periodic box, PFC's periodic space): along a
// periodic axis a ball that leaves [lo, hi) comes back on the other side
// (positions wrapped at each rebuild of the lists), and a pair is seen at
// its minimum image. The cell is at least twice the largest candidate
// cut-off wide along such an axis, so the minimum image is the only one in
// range and contacts stay keyed by the ids of their ends alone.
//
// A sheared cell (Lees & Edwards 1972, simple shear at rate shear_rate,
// flow along x, gradient along y, both periodic): the image of the cell
// above moves along x at +shear_rate L_y and has slid by shear_offset
// (= shear_rate L_y t modulo L_x), so an image across the y boundary is
// shifted along x by -/+ shear_offset and its velocity by -/+ shear_rate L_y.
struct PeriodicCell {
    std::array<bool, 3> periodic{{false, false, false}};
    Vec lo = Vec::Zero(), hi = Vec::Zero();
    double shear_rate = 0;    // 1/s, d v_x / d y; 0: no shear
    double shear_offset = 0;  // m, in [0, L_x): how far the cell above has slid along x
    bool sheared = false;     // a Lees–Edwards cell (set with the rate, even a zero rate)
    bool any() const { return periodic[0] || periodic[1] || periodic[2]; }
    double length(int c) const { return hi[c] - lo[c]; }
    // The offset at time t (from the time, not accumulated: a restart or a
    // rewind to the last good state gets the same bits).
    void slide_to(double t) {
        if (sheared) shear_offset = std::fmod(std::fmod(shear_rate * length(1) * t, length(0)) + length(0), length(0));
    }
    // How many cells up (along y) xj lies from xi's minimum image: the
    // image is xj moved down by that many cells (0 without shear).
    double rows_up(const Vec& xi, const Vec& xj) const {
        return sheared ? std::nearbyint((xj[1] - xi[1]) / length(1)) : 0.0;
    }
    // xj moved by whole cell lengths along the periodic axes (and, across
    // a sheared y boundary, by the offset along x) to the image nearest xi
    // (xj itself along the others).
    Vec image(const Vec& xi, const Vec& xj) const {
        Vec y = xj;
        if (sheared) {
            const double k = rows_up(xi, xj);
            y[1] -= length(1) * k;
            y[0] -= shear_offset * k;
        }
        for (int c = 0; c < 3; ++c)
            if (periodic[c]) y[c] -= length(c) * std::nearbyint((y[c] - xi[c]) / length(c));
        return y;
    }
    // Ball j's velocity vj at the image of xj nearest xi.
    Vec image_velocity(const Vec& xi, const Vec& xj, const Vec& vj) const {
        if (!sheared) return vj;
        Vec v = vj;
        v[0] -= shear_rate * length(1) * rows_up(xi, xj);
        return v;
    }
    // x back inside [lo, hi) along the periodic axes; a sheared cell moves
    // x along by the offset per cell crossed along y (and the velocity v,
    // when given, by the image's velocity).
    Vec wrap(const Vec& x, Vec* v = nullptr) const {
        Vec y = x;
        if (sheared) {
            const double k = std::floor((x[1] - lo[1]) / length(1));
            y[0] -= shear_offset * k;
            if (v) (*v)[0] -= shear_rate * length(1) * k;
        }
        for (int c = 0; c < 3; ++c) {
            if (!periodic[c]) continue;
            y[c] -= length(c) * std::floor((y[c] - lo[c]) / length(c));
            if (y[c] >= hi[c] || y[c] < lo[c]) y[c] = lo[c];  // (round-off at the upper face)
        }
        return y;
    }
    // The flow velocity of simple shear at x, zero at the middle of the
    // cell: a ball's velocity less this is its peculiar (fluctuating) velocity.
    double affine_velocity(const Vec& x) const { return sheared ? shear_rate * (x[1] - 0.5 * (lo[1] + hi[1])) : 0.0; }
};

struct Bodies {
    int dim = 3;
    PeriodicCell cell;  // the space the balls live in (no periodic axis: unbounded)
    std::vector<BodyId> id;
    std::vector<Vec> position, velocity, angular_velocity;
    std::vector<Vec> force, moment;                  // total, after the force pass
    // user loads: empty until a load is applied (most scenes apply none; 48 B
    // per ball, and as much again in the last-good snapshot)
    std::vector<Vec> applied_force, applied_moment;
    // a change of mass or inertia after World::prepare() needs
    // World::mark_dirty(): the kicks use 1/m and 1/I cached there
    std::vector<double> radius, mass, inertia, local_damping;
    std::vector<double> viscous_damping;  // 1/s: F = -c m v, M = -c I w (mass-proportional)
    std::vector<int> group;
    std::vector<std::uint8_t> fixity;
    // the clump whose pebble the ball is (-1: a free ball); empty while the
    // world has no clump (plab_host/clumps.hpp)
    std::vector<std::int32_t> clump;
    BodyId next_id = 0;

    std::size_t size() const { return id.size(); }

    // Mass and moment of inertia from radius and density (thesis §3.1.2):
    // disc of unit thickness I = m R²/2, sphere I = 2 m R²/5.
    static double mass_of(int dim, double radius, double density);
    static double inertia_of(int dim, double radius, double mass);

    BodyId add(const BallSpec& s);
    // Keeps the bodies whose `gone` flag is 0, in their order (ids stay);
    // returns each old index's new one, -1 for a body removed. World's
    // remove_bodies() renumbers what refers to body indices.
    std::vector<std::int32_t> remove(const std::vector<std::uint8_t>& gone);
    bool has_applied_loads() const { return !applied_force.empty(); }
    void enable_applied_loads();  // zero loads for every body, from here on kept
    // Every column's block down to its size: add() grows them by doubling,
    // which leaves up to half of each empty once the bodies are made.
    void trim();
    // DOFs that can never move in this dimension (2D: z, rx, ry).
    std::uint8_t implicit_fixity() const { return dim == 2 ? (dof_z | dof_rx | dof_ry) : 0; }
    // The rotations this dimension lets a body have (2D: about z).
    std::uint8_t rotation_dofs() const { return plab::rotation_dofs(dim); }
};

} // namespace plab
