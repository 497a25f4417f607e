// Packing of rows whose geometry the host wrote into the table's columns
// (forces/packed_batch.hpp pack_table_rows): ball–wall rows, whose features
// resolve_wall_features() settles over a ball's rows together; ball–ball
// rows of a model that sums body fields in the force stage; the rates
// stage. The model gets them as it gets every batch, active rows only and
// the inputs it declares; what it writes goes back to the columns, where
// the reduction and the other readers find it (scatter_rows, accumulate).
#include "forces/packed_batch.hpp"
#include "forces/row_lists.hpp"

#include <algorithm>

namespace plab {

namespace {
// The optional inputs a model declares (OptionalInputs), copied from the
// columns of table row k to packed row a.
void copy_optional_inputs(const OptionalInputs& in, const ContactSet& s, std::size_t k, DenseBatch& d, std::size_t a) {
    if (in.spin) copy3(d.rel_angular_velocity, a, s.rel_angular_velocity.data(), k);
    if (in.radii) { d.radius1[a] = s.radius1[k]; d.radius2[a] = s.radius2[k]; }
    if (in.masses) { d.mass1[a] = s.mass1[k]; d.mass2[a] = s.mass2[k]; }
    if (in.eff_mass) d.eff_mass[a] = s.eff_mass[k];
    if (in.eff_radius) d.eff_radius[a] = s.eff_radius[k];
}
} // namespace

namespace {
// The history of the rows of [begin, end) out of range back to the model's
// declared defaults: a separated contact is forgotten.
void forget_inactive_rows(const ModelInstance& inst, ContactSet& s, std::size_t begin, std::size_t end) {
    const std::size_t stride = std::size_t(inst.stride);
    if (stride == 0) return;
    std::uint8_t inactive[kContactBatch];
    std::uint32_t row[kContactBatch];
    for (std::size_t k = begin; k < end; ++k) inactive[k - begin] = s.active[k] == 0;
    const std::size_t n = list_flagged_rows(inactive, end - begin, std::uint32_t(begin), row);
    for (std::size_t r = 0; r < n; ++r)
        for (std::size_t h = 0; h < stride; ++h) s.history[row[r] * stride + h] = inst.desc->history[h].default_value;
}
} // namespace

void pack_table_rows(const ModelInstance& inst, ContactSet& s, std::size_t begin, std::size_t end, DenseBatch& d) {
    forget_inactive_rows(inst, s, begin, end);
    const std::size_t n = list_flagged_rows(s.active.data() + begin, end - begin, std::uint32_t(begin), d.row);
    d.rows = d.row;
    d.distances = d.distance;
    d.count = std::uint32_t(n);
    d.poison_unread(inst);
    const OptionalInputs optional(inst);
    for (std::size_t a = 0; a < n; ++a) {
        const std::size_t k = d.row[a];
        d.end1[a] = s.end1[k];
        d.end2[a] = s.end2[k];
        copy3(d.normal, a, s.normal.data(), k);
        copy3(d.rel_velocity, a, s.rel_velocity.data(), k);
        d.gap[a] = s.gap[k];
        d.distance[a] = s.distance[k];
        copy_optional_inputs(optional, s, k, d, a);
    }
    gather_history(d.history.data(), s.history.data(), d.row, n, std::size_t(inst.stride));
    // every output starts from zero (dt limit: no limit), as in the columns
    for (double* v : {d.force, d.moment1, d.moment2}) std::fill_n(v, 3 * n, 0.0);
    for (double* v : {d.strain, d.slip, d.dashpot, d.k_t, d.k_r, d.break_energy}) std::fill_n(v, n, 0.0);
    std::fill_n(d.dt_limit, n, kInf);
}

void unpack_table_rows(const ModelInstance& inst, ContactSet& s, const DenseBatch& d, bool sums) {
    const std::size_t n_fields = sums ? inst.fields_accumulated.size() : 0;
    for (std::size_t a = 0; a < d.count; ++a) {
        const std::size_t k = d.row[a];
        copy3(s.force.data(), k, d.force, a);
        copy3(s.moment1.data(), k, d.moment1, a);
        copy3(s.moment2.data(), k, d.moment2, a);
        s.strain[k] = d.strain[a];
        s.slip[k] = d.slip[a];
        s.dashpot[k] = d.dashpot[a];
        s.k_t[k] = d.k_t[a];
        s.k_r[k] = d.k_r[a];
        s.dt_limit[k] = d.dt_limit[a];
        s.break_energy[k] = d.break_energy[a];
        for (std::size_t f = 0; f < n_fields; ++f) {
            s.acc1[f][k] = d.accumulated.end1[f][a];
            s.acc2[f][k] = d.accumulated.end2[f][a];
        }
    }
    scatter_history(s.history.data(), d.history.data(), d.row, d.count, std::size_t(inst.stride));
}

} // namespace plab
