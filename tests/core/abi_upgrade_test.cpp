// Plug-ins built against an older ABI keep loading (abi.h: versions only
// append to what a plug-in fills): a contact model of ABI 3 has no `flags`,
// and the host must not read past the end of its description.
#include "simulation.hpp"

#include <host/plugin_host.hpp>

#include <catch2/catch.hpp>

using namespace plab;

TEST_CASE("a contact model built against ABI 3 loads with no flags and pushes two overlapping balls apart", "[host]") {
    const std::string lib = std::string(PLAB_TEST_PLUGIN_DIR) + "/abi_v3_model.so";
    PluginHost host;
    REQUIRE_NOTHROW(host.load(lib));  // its trailing bytes are 0xFF: read as flags, they would be refused
    const plab_contact_model_desc* d = host.model("abi_v3_spring");
    REQUIRE(d != nullptr);
    CHECK(d->flags == 0u);

    json scene = {{"dimension", 2},
                  {"plugins", {lib}},
                  {"bodies", {{{"type", "ball"}, {"position", {0, 0}}, {"radius", 0.01}, {"density", 1000}},
                              {{"type", "ball"}, {"position", {0.0199, 0}}, {"radius", 0.01}, {"density", 1000}}}},
                  {"contact_models", {{{"groups", {"*", "*"}}, {"model", "abi_v3_spring"}}}}};
    Simulation sim(scene);
    sim.set_quiet(true);
    sim.cycle(50);
    const World& w = sim.world();
    CHECK(w.bodies.velocity[0].x() < 0);  // repelled, equal and opposite
    CHECK(w.bodies.velocity[1].x() == Approx(-w.bodies.velocity[0].x()).epsilon(1e-12));
}
