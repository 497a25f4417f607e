// Claims another ABI version: the host must refuse it before calling init.
#include <plab/abi.h>
extern "C" __attribute__((visibility("default"))) uint32_t plab_plugin_abi_version(void) { return 99u; }
extern "C" __attribute__((visibility("default"))) int plab_plugin_init(const plab_registrar*) { return 0; }
