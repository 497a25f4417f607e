// A library as built against ABI 2.0: it returns version 2.0, its model
// and pass descriptions end before `material` (abi.h, ABI 2.1) and its
// history slot descriptions before `flags` (ABI 2.2). The host must load
// it, reading both as naming no material and the slots as flagged nothing.
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
// A 2.0 history slot description, which ends before `flags`: an array of
// them has that stride, so what follows a slot is the next one's `size`
// (a flag this host does not know, if it read it), and after the last one
// a sentinel with every bit set.
struct History20 {
    uint32_t size;
    const char* name;
    double default_value;
    uint32_t swap_rule;
    const char* doc;
};
static_assert(sizeof(History20) == offsetof(plab_history_desc, flags), "the 2.0 layout");
constexpr uint32_t kHistory20Size = uint32_t(sizeof(History20));
const History20 history_20[] = {
    {kHistory20Size, "shear_force_x", 0.0, PLAB_SWAP_NEGATE, "x"},
    {kHistory20Size, "shear_force_y", 0.0, PLAB_SWAP_NEGATE, "y"},
    {kHistory20Size, "shear_force_z", 0.0, PLAB_SWAP_NEGATE, "z"},
    {0xffffffffu, nullptr, 0.0, 0xffffffffu, nullptr},  // (not a slot: the host must not read it)
};
// the 2.0 structs: this one's, cut before `material`, whose bytes a 2.0
// plug-in does not have (set here to what the host must not read)
plab_contact_model_desc model_20() {
    plab_contact_model_desc d = *plab::contact_model_desc<OldSpring>();
    d.size = uint32_t(offsetof(plab_contact_model_desc, material));
    d.material = "not_read";
    d.history = reinterpret_cast<const plab_history_desc*>(history_20);
    d.history_count = 3;
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
