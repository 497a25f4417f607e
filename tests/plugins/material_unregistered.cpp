// A model that names a material no library registers (its description
// filled by hand, so that the adapter does not register it): refused.
#include "test_models.hpp"

namespace {
struct LoneSpring : SpringBase {
    static constexpr const char* name = "lone_spring";
    using SpringBase::SpringBase;
    void law(const plab::Contact& c) const { c.set_force(k * c.overlap() * c.normal()); c.set_stiffness(k); }
};
plab_contact_model_desc naming_material() {
    plab_contact_model_desc d = *plab::contact_model_desc<LoneSpring>();
    d.material = "nowhere_solid";
    return d;
}
const plab_contact_model_desc desc = naming_material();
} // namespace

PLAB_PLUGIN(r->register_contact_model(r->host, &desc))
