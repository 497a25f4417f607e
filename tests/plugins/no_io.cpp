// A model description without PLAB_IO_DECLARED (a C plug-in that left `io`
// zero): the host must refuse the library, naming the model and the fix.
#include "test_models.hpp"

struct NoIo : SpringBase {
    static constexpr const char* name = "no_io";
    using SpringBase::SpringBase;
    void law(const plab::Contact& c) const { c.set_force(k * c.overlap() * c.normal()); c.set_stiffness(k); }
};

namespace {
plab_contact_model_desc undeclared() {
    plab_contact_model_desc d = *plab::contact_model_desc<NoIo>();
    d.io = 0;
    return d;
}
const plab_contact_model_desc desc = undeclared();
} // namespace

PLAB_PLUGIN(r->register_contact_model(r->host, &desc))
