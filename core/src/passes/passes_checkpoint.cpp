#include "passes/passes_checkpoint.hpp"

#include <string>

namespace plab {

void save_passes(const std::vector<PassInstance>& passes, const PluginHost& host, CheckpointWriter& out) {
    out.section("passes");
    out.u64(passes.size());
    for (const PassInstance& p : passes) {
        out.str(p.desc->name);
        out.column(p.props);
        const plab_pass_state_hooks* hooks = host.pass_state(p.desc->name);
        out.u8(hooks != nullptr);
        if (!hooks) continue;
        std::vector<unsigned char> buf(64);
        std::uint64_t need = hooks->save(p.state, buf.data(), buf.size());
        if (need > buf.size()) {
            buf.resize(need);
            need = hooks->save(p.state, buf.data(), buf.size());
        }
        if (need > buf.size() || need == 0)
            throw CheckpointError(std::string("pass '") + p.desc->name + "' (" + host.library_of_pass(p.desc->name) +
                                  ") failed to save its private state");
        buf.resize(need);
        out.column(buf);
    }
}

void load_passes(std::vector<PassInstance>& passes, const PluginHost& host, CheckpointReader& in) {
    in.section("passes");
    const std::uint64_t n_passes = in.u64();
    if (n_passes != passes.size())
        in.fail("it holds " + std::to_string(n_passes) + " passes, the scene runs " + std::to_string(passes.size()));
    for (PassInstance& p : passes) {
        const std::string name = in.str();
        if (name != p.desc->name) in.fail("pass '" + name + "' where the scene has '" + p.desc->name + "'");
        in.column<double>();  // properties it ran with
        const bool has_state = in.u8() != 0;
        const plab_pass_state_hooks* hooks = host.pass_state(name);
        if (!has_state) {
            if (hooks)
                in.fail("pass '" + name + "' now keeps private state (" + host.library_of_pass(name) +
                        ") but the file has none for it; it was written by an older build of that plug-in");
            continue;
        }
        const std::vector<unsigned char> bytes = in.column<unsigned char>();
        if (!hooks)
            in.fail("the file holds private state of pass '" + name + "' but the loaded library " +
                    host.library_of_pass(name) + " registers no state hooks for it (plab_pass_state_hooks)");
        if (hooks->load(p.state, bytes.data(), bytes.size()) != 0)
            in.fail("pass '" + name + "' (" + host.library_of_pass(name) + ") refused its saved state of " +
                    std::to_string(bytes.size()) + " bytes (written by another version of the plug-in?)");
    }
}

} // namespace plab
