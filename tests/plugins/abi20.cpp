// A library as built against ABI 2.0: it returns version 2.0 and its model
// and pass descriptions end before `material` (abi.h, ABI 2.1). The host
// must load it, reading both as naming no material.
#include "test_models.hpp"

#include <plab/pass.hpp>

#include <cstddef>

namespace {
struct OldSpring : SpringBase {
    static constexpr const char* name = "abi20_spring";
    using SpringBase::SpringBase;
    void law(const plab::Contact& c) const { c.set_force(k * c.overlap() * c.normal()); c.set_stiffness(k); }
};
struct OldPass {
    static constexpr const char* name = "abi20_pass";
    static constexpr const char* doc = "test pass";
    static constexpr uint32_t phase = PLAB_PHASE_POST_FORCE, stage = 0;
    static constexpr plab_field_desc fields[] = {plab::field_desc("abi20_field", "1", 0.0)};
    explicit OldPass(const double*) {}
    void run(const plab_pass_view&) const {}
};
// the 2.0 structs: this one's, cut before `material`, whose bytes a 2.0
// plug-in does not have (set here to what the host must not read)
plab_contact_model_desc model_20() {
    plab_contact_model_desc d = *plab::contact_model_desc<OldSpring>();
    d.size = uint32_t(offsetof(plab_contact_model_desc, material));
    d.material = "not_read";
    return d;
}
plab_pass_desc pass_20() {
    plab_pass_desc d = *plab::pass_desc<OldPass>();
    d.size = uint32_t(offsetof(plab_pass_desc, material));
    d.material = "not_read";
    return d;
}
const plab_contact_model_desc model = model_20();
const plab_pass_desc pass = pass_20();
} // namespace

extern "C" PLAB_EXPORT uint32_t plab_plugin_abi_version(void) { return 2u << 16; }
extern "C" PLAB_EXPORT int plab_plugin_init(const plab_registrar* r) {
    return r->register_contact_model(r->host, &model) != 0 ? 1 : r->register_pass(r->host, &pass);
}
