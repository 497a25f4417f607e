// A contact model built against ABI 3, whose description ends before the
// `flags` member ABI 4 appended. The bytes after its last member (where a
// newer host would find `flags`) are deliberately not zero: the host must
// take flags = 0 for it and not read them (abi.h, version 4).
#include <plab/abi.h>

#include <cmath>
#include <cstddef>
#include <cstring>
#include <new>

namespace {
// plab_contact_model_desc as ABI 3 declared it
struct ModelDescV3 {
    const char* name;
    const char* doc;
    uint32_t property_count;
    const plab_property_desc* properties;
    uint32_t history_count;
    const plab_history_desc* history;
    uint32_t range_kind;
    const char* timestep_rule;
    double (*activity_range)(const double* props);
    uint32_t fields_read_count;
    const plab_field_desc* fields_read;
    uint32_t fields_accumulated_count;
    const plab_field_desc* fields_accumulated;
    void* (*create)(const double* props);
    void (*destroy)(void* instance);
    int (*compute)(void* instance, const double* props, const plab_contact_batch* batch);
    int32_t persist_slot;
    uint32_t rates_stage;
};
static_assert(offsetof(ModelDescV3, rates_stage) == offsetof(plab_contact_model_desc, rates_stage),
              "the ABI 3 layout is a prefix of the ABI 4 one");

const plab_property_desc props[] = {{"kn", "normal stiffness", "N/m", 1e5, 0.0, INFINITY, PLAB_MIN_EXCLUSIVE, "spring"}};
double range(const double*) { return 0.0; }
int compute(void*, const double* p, const plab_contact_batch* b) {
    for (uint32_t k = 0; k < b->count; ++k) {
        if (!b->active[k]) continue;
        const double f = -p[0] * b->gap[k];  // a linear spring on the overlap
        for (int c = 0; c < 3; ++c) b->force[3 * k + c] = f * b->normal[3 * k + c];
        b->stiffness_translational[k] = p[0];
        b->strain_energy[k] = 0.5 * p[0] * b->gap[k] * b->gap[k];
    }
    return 0;
}

// the description in a buffer of 0xFF bytes: whatever lies beyond its
// members (padding and the next bytes) is not zero
alignas(plab_contact_model_desc) unsigned char storage[sizeof(plab_contact_model_desc) + 16];
const ModelDescV3* make_desc() {
    std::memset(storage, 0xFF, sizeof storage);
    ModelDescV3 d;
    std::memset(&d, 0xFF, sizeof d);
    d.name = "abi_v3_spring";
    d.doc = "linear spring, built against ABI 3";
    d.property_count = 1;
    d.properties = props;
    d.history_count = 0;
    d.history = nullptr;
    d.range_kind = PLAB_RANGE_GAP;
    d.timestep_rule = "sqrt(m/kn)";
    d.activity_range = &range;
    d.fields_read_count = 0;
    d.fields_read = nullptr;
    d.fields_accumulated_count = 0;
    d.fields_accumulated = nullptr;
    d.create = nullptr;
    d.destroy = nullptr;
    d.compute = &compute;
    d.persist_slot = -1;
    d.rates_stage = 0;
    std::memcpy(storage, &d, offsetof(ModelDescV3, rates_stage) + sizeof(uint32_t));
    return reinterpret_cast<const ModelDescV3*>(storage);
}
} // namespace

extern "C" __attribute__((visibility("default"))) uint32_t plab_plugin_abi_version(void) { return 3u; }
extern "C" __attribute__((visibility("default"))) int plab_plugin_init(const plab_registrar* r) {
    return r->register_contact_model(r->host, reinterpret_cast<const plab_contact_model_desc*>(make_desc()));
}
