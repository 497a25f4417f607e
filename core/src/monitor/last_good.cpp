#include "monitor/last_good.hpp"

#include "common/buffers.hpp"

namespace plab {

namespace {

// The rows of a table whose history differs from the model's defaults: a
// row at its defaults is what the rebuild makes of a new pair.
void keep_rows_with_history(const ModelInstance& inst, const ContactSet& c, std::vector<std::int32_t>& end1,
                            std::vector<std::int32_t>& end2, std::vector<double>& history) {
    const int stride = inst.stride;
    auto fresh = [&](std::size_t k) {
        const double* row = c.history.data() + k * stride;
        bool at_defaults = true;
        for (int h = 0; h < stride; ++h) at_defaults &= row[h] == inst.desc->history[h].default_value;
        return at_defaults;
    };
    std::size_t kept = 0;  // counted first: room for these rows, not up to twice as many (buffers.hpp)
    for (std::size_t k = 0; k < c.size(); ++k) kept += !fresh(k);
    clear_for(end1, kept);
    clear_for(end2, kept);
    clear_for(history, kept * stride);
    for (std::size_t k = 0; k < c.size(); ++k) {
        if (fresh(k)) continue;
        const double* row = c.history.data() + k * stride;
        end1.push_back(c.end1[k]);
        end2.push_back(c.end2[k]);
        history.insert(history.end(), row, row + stride);
    }
}

} // namespace

// Only the motion of the bodies: the force and moment totals follow from the state.
void LastGoodState::keep(const Bodies& bodies, const Clumps& clumps, const Walls& walls, const BodyFields& fields,
                         const Energies& energies, const Clock& clock, std::size_t bond_breaks, const Instances& instances) {
    position_ = bodies.position;
    velocity_ = bodies.velocity;
    angular_velocity_ = bodies.angular_velocity;
    clump_position_ = clumps.position;
    clump_velocity_ = clumps.velocity;
    clump_angular_velocity_ = clumps.angular_velocity;
    clump_angular_momentum_ = clumps.angular_momentum;
    clump_orientation_ = clumps.orientation;
    walls_ = walls;
    fields_ = fields.columns();
    energies_ = energies;
    clock_ = clock;
    bond_breaks_ = bond_breaks;
    tables_.resize(2 * instances.size());  // copied into the last copy's buffers: no allocation
    std::size_t k = 0;
    for (const auto& inst : instances)
        for (const ContactSet* c : {&inst->balls, &inst->walls}) {
            TableRows& t = tables_[k++];
            keep_rows_with_history(*inst, *c, t.end1, t.end2, t.history);
        }
    valid_ = true;
}

void LastGoodState::restore(Bodies& bodies, Clumps& clumps, Walls& walls, BodyFields& fields, Energies& energies,
                            Clock& clock, std::size_t& bond_breaks, Instances& instances) const {
    bodies.position = position_;
    bodies.velocity = velocity_;
    bodies.angular_velocity = angular_velocity_;
    clumps.position = clump_position_;
    clumps.velocity = clump_velocity_;
    clumps.angular_velocity = clump_angular_velocity_;
    clumps.angular_momentum = clump_angular_momentum_;
    clumps.orientation = clump_orientation_;
    walls = walls_;
    fields.set_columns(fields_);
    energies = energies_;
    clock = clock_;
    bond_breaks = bond_breaks_;
    std::size_t k = 0;
    for (auto& inst : instances)
        for (ContactSet* c : {&inst->balls, &inst->walls}) {
            const TableRows& t = tables_[k++];
            c->end1 = t.end1; c->end2 = t.end2; c->history = t.history;  // (the rebuild lays the columns out)
            if (c->with_wall) {  // its side memory (ball_facet_distance) is the rows' before the restore:
                c->normal.clear();  // the restored rows start without it (carry_history)
                c->interior.clear();
            }
        }
}

} // namespace plab
