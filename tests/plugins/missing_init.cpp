// Reports its version but has no plab_plugin_init.
#include <plab/abi.h>
extern "C" __attribute__((visibility("default"))) uint32_t plab_plugin_abi_version(void) { return PLAB_ABI_VERSION; }
