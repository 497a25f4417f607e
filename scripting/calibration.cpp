#include "calibration.hpp"

#include <cmath>
#include <sstream>

namespace plab {

json hexagonal_2d_calibration(const Node& n, int dim) {
    n.allow_keys({"method", "E", "nu", "sigma_ult", "radius", "thickness", "pb_rmul"});
    if (dim != 2)
        n.at("method").fail("the hexagonal_2d calibration (thesis eqs. 36-46) is derived for 2D plane stress; "
                            "give kn, ks, pb_kn, pb_ks, pb_ten and pb_coh explicitly in a 3D scene");
    const double E = n.at("E").positive();
    const Node nu_node = n.at("nu");
    if (nu_node.value().is_number() && nu_node.value().get<double>() >= 1.0 / 3.0) {
        std::ostringstream s;
        s << "value " << nu_node.value().get<double>()
          << " of Poisson's ratio is outside the valid range [0, 1/3) of the hexagonal calibration: the shear "
             "stiffness Ks = E t (1 - 3 nu) / (sqrt(3) (1 - nu^2)) (thesis eq. 37) and the shear strength (eq. 44) "
             "would be zero or negative, because a hexagonal packing of discs cannot have nu >= 1/3; use nu < 1/3 "
             "or give kn, ks, pb_kn, pb_ks, pb_ten and pb_coh explicitly";
        nu_node.fail(s.str());
    }
    const double nu = nu_node.number(0.0, 1.0 / 3.0, false, true);
    const double sigma_ult = n.at("sigma_ult").positive();
    const double radius = n.at("radius").positive();
    const double thickness = n.number_or("thickness", 1.0, 0.0, kInf, true, true);
    const double rmul = n.number_or("pb_rmul", 1.0, 0.0, kInf, true, true);

    const double Kn = E * thickness / (std::sqrt(3.0) * (1.0 - nu));                         // eq. 36
    const double Ks = E * thickness * (1.0 - 3.0 * nu) / (std::sqrt(3.0) * (1.0 - nu * nu));  // eq. 37
    const double area = 2.0 * rmul * radius * thickness;                                     // eq. 39
    // eq. 38 with the particles' own stiffness 1 % of the bond's (eq. 42)
    json p;
    p["pb_kn"] = Kn / (1.01 * area);
    p["pb_ks"] = Ks / (1.01 * area);
    p["kn"] = 0.01 * Kn / 1.01;
    p["ks"] = 0.01 * Ks / 1.01;
    p["pb_ten"] = sigma_ult * (std::sqrt(3.0) - nu / std::sqrt(3.0)) / (4.0 * (1.0 - nu));  // eqs. 43, 45
    p["pb_coh"] = sigma_ult * (1.0 - 3.0 * nu) / (4.0 * (1.0 - nu));                        // eqs. 44, 46
    p["pb_rmul"] = rmul;
    return p;
}

} // namespace plab
