#include "measurement.hpp"

namespace plab {

int measured_group(const Node& with, const World& w) {
    const std::string g = with.at("group").string();
    const int group = w.find_group(g);
    if (group < 0) {
        std::string known;
        for (const auto& n : w.group_names()) known += (known.empty() ? "" : ", ") + n;
        with.at("group").fail("unknown group \"" + g + "\"; groups in this scene: " + known);
    }
    return group;
}

const std::map<std::string, MeasurementInfo>& measurements() {
    static const std::map<std::string, MeasurementInfo> all = [] {
        std::map<std::string, MeasurementInfo> m;
        register_sph_measurements(m);
        register_coupling_measurements(m);
        register_bonded_measurements(m);
        register_structure_measurements(m);
        register_granular_measurements(m);
        return m;
    }();
    return all;
}

} // namespace plab
