// The `linear` law declaring every optional input and output: the host then
// packs every input and reads back every output. A scene run with it must
// give bit for bit the state of the same scene with `linear`.
#include <plab/dem/linear_law.hpp>

#include <algorithm>

struct LinearAllIo {
    static constexpr const char* name = "linear_all_io";
    static constexpr const char* doc = "linear, declaring every optional column (test)";
    static constexpr const char* timestep_rule = "sqrt(m / sum k)";
    static constexpr uint32_t range_kind = PLAB_RANGE_GAP;
    static constexpr uint32_t io = PLAB_IO_KNOWN_BITS & ~PLAB_IO_DECLARED;
    static constexpr plab_property_desc properties[] = {
        plab::linear_law::kn,        plab::linear_law::ks,      plab::linear_law::fric, plab::linear_law::dp_nratio,
        plab::linear_law::dp_sratio, plab::linear_law::dp_mode, plab::linear_law::rgap,
    };
    static constexpr plab_history_desc history[] = {plab::linear_law::shear_force_x, plab::linear_law::shear_force_y,
                                                    plab::linear_law::shear_force_z};
    static double activity_range(const double* p) { return p[6]; }
    explicit LinearAllIo(const double* p) : law_{p[0], p[1], p[2], p[3], p[4], int(p[5]), p[6]} {}
    void law(const plab::Contact& c) const {
        double strain = 0;
        c.set_force(plab::linear_law::apply(law_, c, 0, strain));
        c.set_strain_energy(strain);
        c.set_stiffness(std::max(law_.kn, law_.ks));
    }
    plab::linear_law::Params law_;
};
PLAB_PLUGIN(plab::add_contact_model<LinearAllIo>(r))
