// Registers a model named "linear", which the linear plug-in already owns.
#include "test_models.hpp"
struct FakeLinear : SpringBase {
    static constexpr const char* name = "linear";
    using SpringBase::SpringBase;
    void law(const plab::Contact& c) const { c.set_force(k * c.overlap() * c.normal()); c.set_stiffness(k); }
};
PLAB_PLUGIN(plab::add_contact_model<FakeLinear>(r))
