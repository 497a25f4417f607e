#include "detection/detection_checkpoint.hpp"

namespace plab {

void save_detection(const DetectionState& d, const StiffnessSums& summed, CheckpointWriter& out) {
    out.section("detection");
    out.u8(d.neighbours.invalidated());
    out.u8(d.prepared);
    out.vecs(d.neighbours.position_at_build());
    out.f64(d.neighbours.wall_motion());
    out.column(summed.translational());
    out.column(summed.rotational());
    out.column(d.pass_contacts.end1_column());
    out.column(d.pass_contacts.end2_column());
    out.column(d.pass_contacts.wall_column());
}

void load_detection(const DetectionState& d, StiffnessSums& stiffness, std::size_t body_count, CheckpointReader& in) {
    in.section("detection");
    NeighbourLists::Saved lists;
    lists.invalidated = in.u8() != 0;
    d.prepared = in.u8() != 0;
    lists.position_at_build = in.vecs();
    lists.wall_motion = in.f64();
    const bool reference_missing = !lists.invalidated && lists.position_at_build.size() != body_count;
    std::vector<double> k_trans = in.column<double>();
    std::vector<double> k_rot = in.column<double>();
    stiffness.restore(std::move(k_trans), std::move(k_rot));
    d.pass_contacts.end1_column() = in.column<std::int32_t>();
    d.pass_contacts.end2_column() = in.column<std::int32_t>();
    d.pass_contacts.wall_column() = in.column<std::uint8_t>();
    d.neighbours.restore(std::move(lists));
    if (reference_missing) in.fail("the neighbour-list reference positions do not match the bodies");
    if (d.prepared && (stiffness.translational().size() != body_count || stiffness.rotational().size() != body_count))
        in.fail("the stiffness sums do not match the bodies");
}

} // namespace plab
