// A model whose description claims a `size` smaller than plab_contact_model_desc
// (as a plug-in built against headers with a shorter struct would): the host
// must refuse it, naming the library, without reading past that size.
#include "test_models.hpp"

#include <cstring>

struct SmallDesc : SpringBase {
    static constexpr const char* name = "small_desc";
    using SpringBase::SpringBase;
    void law(const plab::Contact& c) const { c.set_force(k * c.overlap() * c.normal()); c.set_stiffness(k); }
};

namespace {
plab_contact_model_desc shortened() {
    plab_contact_model_desc d = *plab::contact_model_desc<SmallDesc>();
    d.size = uint32_t(offsetof(plab_contact_model_desc, flags));  // ends before flags and io
    return d;
}
const plab_contact_model_desc desc = shortened();
} // namespace

PLAB_PLUGIN(r->register_contact_model(r->host, &desc))
