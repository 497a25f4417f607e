// A pass library built against ABI 1 (before the pass diagnostic existed):
// the host still loads and runs it (abi.h: versions only append).
#include <plab/abi.h>

namespace {
const plab_field_desc fields[] = {{"abi_v1_count", "1", 0.0}};
int run(void*, const double*, const plab_pass_view* v) {
    for (uint32_t i = 0; i < v->body_count; ++i) v->fields[0][i] += 1.0;  // cycles seen
    return 0;
}
const plab_pass_desc desc = {"abi_v1_counter", "counts the cycles it ran per body", PLAB_PHASE_POST_FORCE, 0, 0,
                             nullptr, 1, fields, nullptr, nullptr, &run};
} // namespace

extern "C" __attribute__((visibility("default"))) uint32_t plab_plugin_abi_version(void) { return 1u; }
extern "C" __attribute__((visibility("default"))) int plab_plugin_init(const plab_registrar* r) {
    return r->register_pass(r->host, &desc);
}
