// A material, "probe_solid" (abi.h plab_material_desc, ABI 2.1), with a model
// and a pass that take their shared properties from it: the model declares
// the material's k and a property of its own, c, that the material does not
// have; the pass declares the material's fric. Both register the material
// (add_contact_model, add_pass), the second time alike.
#include <plab/pass.hpp>

#include <limits>

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr plab_property_desc k = plab::prop::number("k", "stiffness", "N/m", 1e5, 0.0, 1e12, PLAB_MIN_EXCLUSIVE, "spring",
                                                    PLAB_MIX_HARMONIC);
constexpr plab_property_desc fric = plab::prop::number("fric", "friction", "1", 0.0, 0.0, inf, PLAB_MAX_EXCLUSIVE, "Coulomb",
                                                       PLAB_MIX_MIN);

struct ProbeSolid {
    static constexpr const char* name = "probe_solid";
    static constexpr const char* doc = "test material";
    static constexpr plab_property_desc properties[] = {k, fric};
};

struct MaterialSpring {
    static constexpr const char* name = "material_spring";
    static constexpr const char* doc = "test spring whose k a scene material gives";
    static constexpr const char* timestep_rule = "sqrt(m/k)";
    static constexpr uint32_t range_kind = PLAB_RANGE_GAP;
    static constexpr uint32_t io = 0;
    using material = ProbeSolid;
    static constexpr plab_property_desc properties[] = {
        plab::prop::number("c", "dashpot", "N s/m", 0.0, 0.0, inf, PLAB_MAX_EXCLUSIVE, "not the material's", PLAB_MIX_MAX),
        k};
    static double activity_range(const double*) { return 0.0; }
    explicit MaterialSpring(const double* p) : k_(p[1]) {}
    void law(const plab::Contact& c) const {
        c.set_force(k_ * c.overlap() * c.normal());
        c.set_stiffness(k_);
    }
    double k_;
};

struct MaterialPass {
    static constexpr const char* name = "material_pass";
    static constexpr const char* doc = "test pass whose fric a scene material gives";
    static constexpr uint32_t phase = PLAB_PHASE_POST_FORCE, stage = 0;
    using material = ProbeSolid;
    static constexpr plab_property_desc properties[] = {fric};
    static constexpr plab_field_desc fields[] = {plab::field_desc("material_pass_fric", "1", 0.0)};
    explicit MaterialPass(const double* p) : fric_(p[0]) {}
    void run(const plab_pass_view& v) const {
        for (uint32_t i = 0; i < v.body_count; ++i) v.fields[0][i] = fric_;
    }
    double fric_;
};

} // namespace

PLAB_PLUGIN(plab::add_contact_model<MaterialSpring>(r) != 0 ? 1 : plab::add_pass<MaterialPass>(r))
