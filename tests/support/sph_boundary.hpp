// A block of fixed SPH boundary balls (thesis §2.2.4), as a scene's `bodies`
// entry: radius db/2 at spacing db, mass rest_density db², every degree of
// freedom fixed, group "boundary".
#pragma once

#include <nlohmann/json.hpp>

namespace plab::testing_support {

inline nlohmann::json boundary_block(double x0, double y0, double x1, double y1, double db,
                                     double rest_density = 1000.0) {
    return {{"type", "lattice"}, {"group", "boundary"}, {"packing", "square"},
            {"box", {{"min", {x0, y0}}, {"max", {x1, y1}}}}, {"radius", db / 2}, {"spacing", db},
            {"mass", rest_density * db * db}, {"fix", {"all"}}};
}

} // namespace plab::testing_support
