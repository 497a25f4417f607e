// Material calibration of bonded packings: from E, ν and the ultimate
// strength to contact and bond stiffnesses and bond strengths.
#pragma once

#include "json_reader.hpp"

namespace plab {

// 2D hexagonal packing in plane stress (thesis eqs. 36–46). `n` holds E, nu,
// sigma_ult, radius, and optionally thickness (1 m) and pb_rmul (1).
// Returns the linear_pbond properties kn, ks, pb_kn, pb_ks, pb_ten, pb_coh.
json hexagonal_2d_calibration(const Node& n, int dim);

} // namespace plab
