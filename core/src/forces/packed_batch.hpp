// The active rows of one batch of ball–ball candidates, packed densely for
// the contact model. A Verlet list holds about two candidates per contact;
// handing the model only the rows in contact, in short columns that stay in
// cache, spares the host writing (and the model reading back) the inputs and
// outputs of every candidate row in full-length columns. `row` leads back to
// the persistent contact row, which keeps the history and what readers of
// the contact columns need (ForcePipeline::force_sweep(); the force only on the
// steps that read it, World::contact_forces_wanted).
#pragma once

#include "forces/geometry.hpp"
#include "forces/force_pipeline.hpp"

#include <cstring>
#include <iterator>
#include <limits>
#include <memory>

namespace plab {

// Where a packed batch's rows add to the body fields their model
// accumulates: per field, a column for end 1 and one for end 2, zeroed for
// the packed rows by bind().
struct AccumulatedColumns {
    static constexpr std::size_t kMax = ReadFields::kMax;  // (World::add_instance refuses more)
    std::vector<double> values;              // 2 x fields x kContactBatch
    double* end1[kMax];
    double* end2[kMax];
    // The columns of n_fields fields, rows [0, n) zeroed.
    void bind(std::size_t n_fields, std::size_t n) {
        if (values.size() < 2 * n_fields * kContactBatch) values.resize(2 * n_fields * kContactBatch);
        for (std::size_t f = 0; f < n_fields; ++f) {
            end1[f] = values.data() + 2 * f * kContactBatch;
            end2[f] = end1[f] + kContactBatch;
            std::fill_n(end1[f], n, 0.0);
            std::fill_n(end2[f], n, 0.0);
        }
    }
};

struct DenseBatch {
    static constexpr std::size_t N = kContactBatch;
    std::uint32_t count = 0;  // active rows packed
    std::uint32_t row[N];     // persistent row of each packed one
    std::int32_t end1[N], end2[N];
    std::uint8_t active[N];   // all 1: only active rows are packed
    // inputs
    double normal[3 * N], gap[N], distance[N], rel_velocity[3 * N], rel_angular_velocity[3 * N];
    double radius1[N], radius2[N], mass1[N], mass2[N], eff_mass[N], eff_radius[N];
    double point[3 * N];  // contact point, for the readers of a set that is not packed
    double arm1[3 * N], arm2[3 * N];  // point - x_i, point - x_j: the moments r x F, without a second gather of x
    std::vector<double> history;  // count x stride, copied in and back
    // outputs, zeroed for the packed rows only
    double force[3 * N], moment1[3 * N], moment2[3 * N];
    double strain[N], slip[N], dashpot[N], k_t[N], k_r[N], dt_limit[N], break_energy[N];
    // Where the packed rows' persistent rows and centre distances are read:
    // row and distance, or, on the centre-force path, the lists that
    // mark_ball_rows_in_range() made, read in place rather than copied
    // (pack_centre_rows; the copy was 3 % of an SPH step).
    const std::uint32_t* rows = row;
    const double* distances = distance;

    // the body-field sums of the packed rows (accumulate1/2, abi.h)
    AccumulatedColumns accumulated;

    DenseBatch() { std::fill_n(active, N, std::uint8_t(1)); }
    // The optional inputs (PLAB_IO_*) a model does not read are not packed:
    // their columns hold NaN instead, so a law that reads one anyway gives a
    // non-finite force, which the host reports by model name. `poisoned`
    // marks the columns that hold NaN in every row; one scene usually has
    // one model per batch kind, so the NaN are written once.
    std::uint32_t poisoned = 0;
    void poison_unread(const ModelInstance& inst) {
        const struct { std::uint32_t bit; double* cols[2]; std::size_t width; } inputs[] = {
            {PLAB_IO_REL_ANGULAR_VELOCITY, {rel_angular_velocity, nullptr}, 3},
            {PLAB_IO_RADII, {radius1, radius2}, 1},
            {PLAB_IO_MASSES, {mass1, mass2}, 1},
            {PLAB_IO_EFF_MASS, {eff_mass, nullptr}, 1},
            {PLAB_IO_EFF_RADIUS, {eff_radius, nullptr}, 1},
        };
        for (const auto& in : inputs) {
            if (inst.uses(in.bit)) { poisoned &= ~in.bit; continue; }
            if (poisoned & in.bit) continue;
            for (double* c : in.cols)
                if (c) std::fill_n(c, in.width * N, std::numeric_limits<double>::quiet_NaN());
            poisoned |= in.bit;
        }
    }
    // this thread's scratch: allocated on its first use, then reused every cycle
    static DenseBatch& for_this_thread(std::size_t history_stride) {
        thread_local std::unique_ptr<DenseBatch> d;
        if (!d) d = std::make_unique<DenseBatch>();
        if (d->history.size() < N * history_stride) d->history.resize(N * history_stride);
        return *d;
    }
};

// A vector into row a of a 3-wide column, and row a of one into row k of another.
inline void put(double* col, std::size_t a, const Vec& v) {
    col[3 * a] = v.x(); col[3 * a + 1] = v.y(); col[3 * a + 2] = v.z();
}
inline void copy3(double* to, std::size_t k, const double* from, std::size_t a) {
    to[3 * k] = from[3 * a]; to[3 * k + 1] = from[3 * a + 1]; to[3 * k + 2] = from[3 * a + 2];
}

// The packed rows' forces to the set's column: all of them on a step whose
// forces are read (World::contact_forces_wanted); on another, only a batch
// with a non-finite force, which the NaN diagnostic looks for there.
inline void write_forces(ContactSet& s, const DenseBatch& d, bool read) {
    if (!read) {
        // the largest exponent field, all ones only for an inf or a NaN (an
        // integer max takes a vector of values at a time; a test per value did not)
        constexpr std::uint64_t kExponent = 0x7ff0000000000000ull;
        std::uint64_t top = 0;
        for (std::size_t i = 0; i < 3 * std::size_t(d.count); ++i) {
            std::uint64_t b;
            std::memcpy(&b, &d.force[i], sizeof b);
            top = std::max(top, b & kExponent);
        }
        if (top != kExponent) return;
    }
    for (std::size_t a = 0; a < d.count; ++a) copy3(s.force.data(), d.rows[a], d.force, a);
}

// The optional inputs of a packed row that its model reads (abi.h,
// PLAB_IO_*; DenseBatch::poison_unread() fills the others with NaN), written
// by both packers with fill_pair_constants()'s arithmetic.
struct OptionalInputs {
    bool spin, radii, masses, eff_mass, eff_radius;
    explicit OptionalInputs(const ModelInstance& inst)
        : spin(inst.uses(PLAB_IO_REL_ANGULAR_VELOCITY)), radii(inst.uses(PLAB_IO_RADII)),
          masses(inst.uses(PLAB_IO_MASSES)), eff_mass(inst.uses(PLAB_IO_EFF_MASS)),
          eff_radius(inst.uses(PLAB_IO_EFF_RADIUS)) {}
    void put_row(DenseBatch& d, std::size_t a, const Vec& rel_spin, double ri, double rj, double mi, double mj) const {
        if (spin) put(d.rel_angular_velocity, a, rel_spin);
        if (radii) { d.radius1[a] = ri; d.radius2[a] = rj; }
        if (masses) { d.mass1[a] = mi; d.mass2[a] = mj; }
        if (eff_mass) d.eff_mass[a] = mi * mj / (mi + mj);
        if (eff_radius) d.eff_radius[a] = ri * rj / (ri + rj);
    }
};

// The history of packed rows, in from the set's rows row[a] (gather) or back
// out to them (scatter), in loops of their own: the packers' main loops keep
// fewer values live, and a model's usual stride (3: a shear force) copies
// without a loop per row (Stride 0: the stride given).
template <std::size_t Stride>
void gather_history_rows(double* dense, const double* set, const std::uint32_t* row, std::size_t n, std::size_t stride) {
    const std::size_t w = Stride ? Stride : stride;
    for (std::size_t a = 0; a < n; ++a)
        for (std::size_t h = 0; h < w; ++h) dense[a * w + h] = set[row[a] * w + h];
}
template <std::size_t Stride>
void scatter_history_rows(double* set, const double* dense, const std::uint32_t* row, std::size_t n, std::size_t stride) {
    const std::size_t w = Stride ? Stride : stride;
    for (std::size_t a = 0; a < n; ++a)
        for (std::size_t h = 0; h < w; ++h) set[row[a] * w + h] = dense[a * w + h];
}
inline void gather_history(double* dense, const double* set, const std::uint32_t* row, std::size_t n, std::size_t stride) {
    if (stride == 3) gather_history_rows<3>(dense, set, row, n, 3);
    else gather_history_rows<0>(dense, set, row, n, stride);
}
inline void scatter_history(double* set, const double* dense, const std::uint32_t* row, std::size_t n, std::size_t stride) {
    if (stride == 3) scatter_history_rows<3>(set, dense, row, n, 3);
    else scatter_history_rows<0>(set, dense, row, n, stride);
}

// Points a batch view at rows [o, ...) of a set of contact columns with the
// ABI's names: a ContactSet (std::vector columns) or a DenseBatch (arrays).
template <class Columns>
void bind_rows(plab_contact_batch& b, Columns& c, std::size_t o, double* history) {
    b.end1 = std::data(c.end1) + o;
    b.end2 = std::data(c.end2) + o;
    b.active = std::data(c.active) + o;
    b.normal = std::data(c.normal) + 3 * o;
    b.gap = std::data(c.gap) + o;
    b.distance = std::data(c.distance) + o;
    b.rel_velocity = std::data(c.rel_velocity) + 3 * o;
    b.rel_angular_velocity = std::data(c.rel_angular_velocity) + 3 * o;
    b.radius1 = std::data(c.radius1) + o;
    b.radius2 = std::data(c.radius2) + o;
    b.mass1 = std::data(c.mass1) + o;
    b.mass2 = std::data(c.mass2) + o;
    b.eff_mass = std::data(c.eff_mass) + o;
    b.eff_radius = std::data(c.eff_radius) + o;
    b.history = history;
    b.force = std::data(c.force) + 3 * o;
    b.moment1 = std::data(c.moment1) + 3 * o;
    b.moment2 = std::data(c.moment2) + 3 * o;
    b.strain_energy = std::data(c.strain) + o;
    b.slip_energy = std::data(c.slip) + o;
    b.dashpot_energy = std::data(c.dashpot) + o;
    b.stiffness_translational = std::data(c.k_t) + o;
    b.stiffness_rotational = std::data(c.k_r) + o;
    b.dt_limit = std::data(c.dt_limit) + o;
    b.break_energy = std::data(c.break_energy) + o;
}

// What a model call is for: its stage (PLAB_STAGE_*) and whether end 2 of
// the rows is a wall facet.
struct BatchCall {
    std::uint32_t stage = PLAB_STAGE_FORCES;
    bool to_wall = false;
};

// Calls the model once on the packed rows, their tangential history first
// turned into their contact planes (forces/tangential_history.hpp); returns
// its status.
int call_model(const ModelInstance& inst, DenseBatch& d, int dim, double dt, const ReadFields& fields,
                     BatchCall call = {});

// The active rows of [begin, end) of a table whose geometry is in its
// columns (ball–wall rows; ball–ball rows of a model that sums body fields
// in the force stage; the rates stage), packed into d: the geometry and the
// inputs the model declares, its history, its outputs zeroed
// (forces/table_batch.cpp). The history of the rows out of range goes back
// to its declared defaults (a separated contact is forgotten).
void pack_table_rows(const ModelInstance& inst, ContactSet& s, std::size_t begin, std::size_t end, DenseBatch& d);
// Back to the table's columns: history, the outputs (the neutral value of
// one the model does not declare) and, where `sums`, the body-field sums.
void unpack_table_rows(const ModelInstance& inst, ContactSet& s, const DenseBatch& d, bool sums);

// The loop over a batch's rows in range that both packers share (d.rows and
// d.distances, as the range test listed them): each row's ends, radii and
// gap; then its kinematics, which kinematics(a, i, j, ri, dist, gap) writes
// into d, returning the relative spin; then the optional inputs and the
// overlap check. True when a row overlaps beyond max_overlap.
template <class Kinematics>
bool pack_rows(const Bodies& B, const ContactSet& s, const OptionalInputs& optional, double max_overlap,
               std::size_t n_active, DenseBatch& d, Kinematics&& kinematics) {
    bool exceeded = false;
    for (std::size_t a = 0; a < n_active; ++a) {
        const std::size_t k = d.rows[a];
        const std::int32_t i = s.end1[k], j = s.end2[k];
        // radii and masses from the bodies (in cache) rather than the set's
        // long columns, with fill_pair_constants()'s arithmetic
        const double ri = B.radius[i], rj = B.radius[j], dist = d.distances[a];
        const double gap = surface_gap(dist, ri, rj);
        d.gap[a] = gap;
        d.end1[a] = i;
        d.end2[a] = j;
        const Vec rel_spin = kinematics(a, i, j, ri, dist, gap);
        optional.put_row(d, a, rel_spin, ri, rj, B.mass[i], B.mass[j]);
        exceeded |= -gap > max_overlap * std::min(ri, rj);
    }
    return exceeded;
}

} // namespace plab
