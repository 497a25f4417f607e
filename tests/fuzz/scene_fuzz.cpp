// libFuzzer target: a scene as bytes → JSON → the scene loader and its
// validator (plug-ins, generators, walls, contact-model rules, passes,
// timestep, histories, commands). Bad input must end in an InputError (or a
// PluginError for a plug-in that is refused) with a message; anything else —
// a crash, a sanitizer report, another exception type, a hang or a huge
// allocation — is a finding, to be fixed and kept as a regression test in
// tests/scene/scene_errors_test.cpp.
#include "simulation.hpp"

#include <spdlog/spdlog.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::shared_ptr<plab::PluginHost> host = [] {
        spdlog::set_level(spdlog::level::off);
        return std::make_shared<plab::PluginHost>();
    }();
    const plab::json scene = plab::json::parse(data, data + size, nullptr, false);
    if (scene.is_discarded()) return 0;  // not JSON: read_scene_file's message, not the loader's job
    try {
        plab::Simulation sim(scene, ".", host);
    } catch (const plab::InputError&) {
    } catch (const plab::PluginError&) {
    }
    return 0;
}
