#include "measurement.hpp"

namespace plab {

const std::map<std::string, MeasurementInfo>& measurements() {
    static const std::map<std::string, MeasurementInfo> all = [] {
        std::map<std::string, MeasurementInfo> m;
        register_sph_measurements(m);
        register_bonded_measurements(m);
        return m;
    }();
    return all;
}

} // namespace plab
