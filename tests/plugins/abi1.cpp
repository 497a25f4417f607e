// A library as every plug-in built before ABI 2 was: its version function
// returns 7, the last version of ABI 1. The host must refuse it by its
// version, before calling init (which would abort the test program).
#include <cstdint>
#include <cstdlib>

extern "C" __attribute__((visibility("default"))) uint32_t plab_plugin_abi_version(void) { return 7u; }
extern "C" __attribute__((visibility("default"))) int plab_plugin_init(const void*) { std::abort(); }
