// Two models whose `io` declaration (abi.h, PLAB_IO_*) is wrong: one reads
// the effective radius without declaring it, one writes a pure moment
// without declaring it. The host must refuse both before the first step.
#include "test_models.hpp"
struct ReadsUndeclared : SpringBase {
    static constexpr const char* name = "reads_undeclared";
    static constexpr uint32_t io = PLAB_IO_EFF_MASS;  // but the law reads eff_radius
    using SpringBase::SpringBase;
    void law(const plab::Contact& c) const {
        c.set_force(k * c.overlap() * (c.eff_radius() / c.eff_radius()) * c.normal());
        c.set_stiffness(k);
    }
};
struct WritesUndeclared : SpringBase {
    static constexpr const char* name = "writes_undeclared";
    static constexpr uint32_t io = 0;  // declares nothing optional, but writes moment1
    using SpringBase::SpringBase;
    void law(const plab::Contact& c) const {
        c.set_force(k * c.overlap() * c.normal());
        c.set_moment1({0, 0, 1e-3});
        c.set_stiffness(k);
    }
};
PLAB_PLUGIN(plab::add_contact_model<ReadsUndeclared>(r) | plab::add_contact_model<WritesUndeclared>(r))
