// The active rows of one batch of ball–ball candidates, packed densely for
// the contact model. A Verlet list holds about two candidates per contact;
// handing the model only the rows in contact, in short columns that stay in
// cache, spares the host writing (and the model reading back) the inputs and
// outputs of every candidate row in full-length columns. `row` leads back to
// the persistent contact row, which keeps the history and what readers of
// the contact columns need (force_sweep, docs/architecture.md).
#pragma once

#include "world.hpp"

#include <memory>

namespace plab {

struct DenseBatch {
    static constexpr std::size_t N = kContactBatch;
    std::uint32_t count = 0;  // active rows packed
    std::uint32_t row[N];     // persistent row of each packed one
    std::int32_t end1[N], end2[N];
    std::uint8_t active[N];   // all 1: only active rows are packed
    // inputs
    double normal[3 * N], gap[N], distance[N], rel_velocity[3 * N], rel_angular_velocity[3 * N];
    double radius1[N], radius2[N], mass1[N], mass2[N], eff_mass[N], eff_radius[N];
    double point[3 * N];  // contact point, for the moments r x F and the readers
    std::vector<double> history;  // count x stride, copied in and back
    // outputs, zeroed for the packed rows only
    double force[3 * N], moment1[3 * N], moment2[3 * N];
    double strain[N], slip[N], dashpot[N], k_t[N], k_r[N], dt_limit[N], break_energy[N];

    DenseBatch() { std::fill_n(active, N, std::uint8_t(1)); }
    // this thread's scratch: allocated on its first use, then reused every cycle
    static DenseBatch& for_this_thread(std::size_t history_stride) {
        thread_local std::unique_ptr<DenseBatch> d;
        if (!d) d = std::make_unique<DenseBatch>();
        if (d->history.size() < N * history_stride) d->history.resize(N * history_stride);
        return *d;
    }
};

// Calls the model once on the packed rows; returns its status.
int call_model_dense(const ModelInstance& inst, DenseBatch& d, int dim, double dt, const double* const* read_cols);

} // namespace plab
