// The contact table of one model instance and one kind (ball–ball or
// ball–wall): candidate pairs with their history and the columns of the
// contact batch. Rows are sorted by the ids of the two ends (contacts/contact_keys.hpp row_key);
// history is carried across rebuilds by that key.
#pragma once

#include <plab_host/contacts.hpp>
#include <plab_host/types.hpp>

#include <plab/abi.h>

#include <cstdint>
#include <utility>
#include <vector>

namespace plab {

constexpr std::size_t kBatchEnergies = 5;  // ContactSet::batch_energy per batch

struct ContactSet {
    bool with_wall = false;
    std::vector<std::int32_t> end1, end2;
    std::vector<double> history;
    // geometry (inputs of the batch). Ball–ball rows packed with their
    // geometry (ForcePipeline::packer_of) keep active, gap, normal and point up to date
    // for every reader; their distance, rel_velocity, rel_angular_velocity,
    // strain, slip, dashpot and break_energy columns are not written (the
    // model gets them packed, forces/packed_batch.hpp) and hold stale values. Those
    // of a PLAB_MODEL_FORCE_AT_CENTRES model (centre_force_batch.cpp) write
    // back force and dt_limit only: moments, stiffness and energies stay
    // zero. A `packed` set (ForcePipeline::packs_balls: so packed, and no
    // rates stage needs all rows' geometry first) does not even allocate distance, rel_velocity,
    // rel_angular_velocity, radius1, radius2, mass1, mass2, eff_mass,
    // eff_radius, strain, slip, dashpot and break_energy, nor gap, normal
    // and point: readers recompute those three from the positions
    // (forces/geometry.hpp row_gap, row_normal, row_point), and take the radii
    // from the bodies (row_end_radius). ~200 B per row less.
    bool packed = false;
    std::vector<std::uint8_t> active, interior;
    std::vector<double> normal, gap, distance, rel_velocity, rel_angular_velocity, point;
    std::vector<double> radius1, radius2, mass1, mass2, eff_mass, eff_radius;
    // outputs
    std::vector<double> force, moment1, moment2, strain, slip, dashpot, k_t, k_r, dt_limit, break_energy;
    std::vector<std::vector<double>> acc1, acc2;
    // per batch of kContactBatch rows: strain, slip, dashpot, bond-break
    // energy and wall power of the active rows (Reduction::scatter_rows)
    std::vector<double> batch_energy;
    bool overlap_exceeded = false;  // an active contact overlaps beyond its model's max_overlap (geometry())
    bool forces_zero = false;       // force zero and no step limit in every row (forces/still_instances.hpp hold_still)

    std::size_t size() const { return end1.size(); }
    void resize_columns(std::size_t n, int n_accumulated);
    void release_columns();  // every per-row column but the ends and history (and a wall set's sides), freed
    // The per-row columns of doubles (all but ends, flags and history), by
    // name: checkpoints save them by name, release_columns() frees them.
    std::vector<std::pair<const char*, std::vector<double>*>> double_columns();

    // The owning model, for its io and flags (abi.h; set once, World::add_instance).
    // A packed set does not keep the output columns its model never writes:
    // a model that declares its io and not PLAB_IO_MOMENTS has no moment
    // columns (48 B per row), and so on; a centre-force model (SPH) keeps
    // only force and dt_limit. Readers take the neutral value of a column
    // not kept, through the *_at() functions below.
    const plab_contact_model_desc* model = nullptr;
    bool keeps(std::uint32_t io_bit) const;  // PLAB_IO_MOMENTS, _STIFFNESS_ROTATIONAL, _DT_LIMIT, or 0 for k_t
};

// The rows of a table whose ends both stay after Bodies::remove (a wall
// row's ball), their ends renumbered, with their history (and a wall row's
// side); every other column is released, for the rebuild that must follow
// (World's remove_bodies marks the world dirty).
void renumber_ends(ContactSet& s, const std::vector<std::int32_t>& new_index, std::size_t history_stride);

// Row k's value of an output column a table may not keep (ContactSet::keeps):
// the neutral value where it is not kept.
inline double k_t_at(const ContactSet& s, std::size_t k) { return s.k_t.empty() ? 0.0 : s.k_t[k]; }
inline double k_r_at(const ContactSet& s, std::size_t k) { return s.k_r.empty() ? 0.0 : s.k_r[k]; }
inline double dt_limit_at(const ContactSet& s, std::size_t k) { return s.dt_limit.empty() ? kInf : s.dt_limit[k]; }
inline Vec moment1_at(const ContactSet& s, std::size_t k) { return s.moment1.empty() ? Vec(Vec::Zero()) : Vec(&s.moment1[3 * k]); }
inline Vec moment2_at(const ContactSet& s, std::size_t k) { return s.moment2.empty() ? Vec(Vec::Zero()) : Vec(&s.moment2[3 * k]); }

} // namespace plab
