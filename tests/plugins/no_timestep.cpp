// A model that never reports a stiffness or step limit.
#include "test_models.hpp"
struct NoTimestep : SpringBase {
    static constexpr const char* name = "no_timestep";
    using SpringBase::SpringBase;
    void law(const plab::Contact& c) const { c.set_force(k * c.overlap() * c.normal()); }
};
PLAB_PLUGIN(plab::add_contact_model<NoTimestep>(r))
