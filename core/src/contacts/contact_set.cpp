#include "contacts/contact_set.hpp"

#include <algorithm>

#include "common/buffers.hpp"

namespace plab {

bool ContactSet::keeps(std::uint32_t io_bit) const {
    if (!packed || !model) return true;
    // no moment, no stiffness; step limits per batch (PackedTable::limits, forces/packed_tables.hpp)
    if (model->flags & PLAB_MODEL_FORCE_AT_CENTRES) return false;
    return io_bit == 0 || (model->io & io_bit);
}

void ContactSet::resize_columns(std::size_t n, int n_acc) {
    forces_zero = false;  // (dt_limit below holds zeros, not kInf)
    fill(active, n, std::uint8_t(0));
    fill(interior, with_wall ? n : 0, std::uint8_t(1));
    fill(force, 3 * n, 0.0);
    // outputs the model writes; the others not kept at all (keeps())
    const struct { std::vector<double>* col; std::size_t width; std::uint32_t bit; } outputs[] = {
        {&moment1, 3, PLAB_IO_MOMENTS}, {&moment2, 3, PLAB_IO_MOMENTS}, {&k_t, 1, 0},
        {&k_r, 1, PLAB_IO_STIFFNESS_ROTATIONAL}, {&dt_limit, 1, PLAB_IO_DT_LIMIT}};
    for (const auto& o : outputs) {
        if (keeps(o.bit)) fill(*o.col, o.width * n, 0.0);
        else release(*o.col);
    }
    // what only the model reads, or only per-batch sums need: none when packed
    const std::size_t m = packed ? 0 : n;
    for (auto* v : {&normal, &point, &rel_velocity, &rel_angular_velocity}) fill(*v, 3 * m, 0.0);
    for (auto* v : {&gap, &distance, &radius1, &radius2, &mass1, &mass2, &eff_mass, &eff_radius, &strain, &slip,
                    &dashpot, &break_energy})
        fill(*v, m, 0.0);
    if (packed)  // not kept at all
        for (auto* v : {&normal, &point, &rel_velocity, &rel_angular_velocity, &gap, &distance, &radius1, &radius2,
                        &mass1, &mass2, &eff_mass, &eff_radius, &strain, &slip, &dashpot, &break_energy})
            release(*v);
    acc1.resize(std::size_t(n_acc));
    acc2.resize(std::size_t(n_acc));
    for (auto* acc : {&acc1, &acc2})
        for (auto& a : *acc) fill(a, n, 0.0);
}

std::vector<std::pair<const char*, std::vector<double>*>> ContactSet::double_columns() {
    return {{"normal", &normal}, {"gap", &gap}, {"distance", &distance}, {"rel_velocity", &rel_velocity},
            {"rel_angular_velocity", &rel_angular_velocity}, {"point", &point}, {"radius1", &radius1},
            {"radius2", &radius2}, {"mass1", &mass1}, {"mass2", &mass2}, {"eff_mass", &eff_mass},
            {"eff_radius", &eff_radius}, {"force", &force}, {"moment1", &moment1}, {"moment2", &moment2},
            {"strain", &strain}, {"slip", &slip}, {"dashpot", &dashpot}, {"k_t", &k_t}, {"k_r", &k_r},
            {"dt_limit", &dt_limit}, {"break_energy", &break_energy}};
}

void ContactSet::release_columns() {
    release(active);
    // a wall set's normal and interior flags say which face of a facet each
    // row's ball is on: carry_history() carries them to the new rows
    if (!with_wall) release(interior);
    for (auto& [name, col] : double_columns())
        if (!with_wall || col != &normal) release(*col);
    release(batch_energy);
    for (auto* acc : {&acc1, &acc2})
        for (auto& a : *acc) release(a);
}

void renumber_ends(ContactSet& s, const std::vector<std::int32_t>& new_index, std::size_t stride) {
    const bool sides = s.with_wall && s.normal.size() == 3 * s.size() && s.interior.size() == s.size();
    std::size_t kept = 0;
    for (std::size_t k = 0; k < s.size(); ++k) {
        const std::int32_t i = new_index[std::size_t(s.end1[k])];
        const std::int32_t j = s.with_wall ? s.end2[k] : new_index[std::size_t(s.end2[k])];
        if (i < 0 || j < 0) continue;
        s.end1[kept] = i;
        s.end2[kept] = j;
        std::copy_n(s.history.begin() + k * stride, stride, s.history.begin() + kept * stride);
        if (sides) {
            std::copy_n(s.normal.begin() + 3 * k, 3, s.normal.begin() + 3 * kept);
            s.interior[kept] = s.interior[k];
        }
        ++kept;
    }
    s.end1.resize(kept);
    s.end2.resize(kept);
    s.history.resize(kept * stride);
    if (sides) {
        s.normal.resize(3 * kept);
        s.interior.resize(kept);
    }
    s.release_columns();
}

} // namespace plab
