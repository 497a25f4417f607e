// The skeleton is a damped linear spring: the smallest model that is worth
// testing against an analytical result (contact time pi sqrt(m/k)).
#include "new_model.hpp"

#include <plab_host/errors.hpp>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace fs = std::filesystem;

namespace plab {

namespace {

const char* cmake_template = R"~(# Contact model @NAME@, built out of tree against the installed ParticleLab SDK:
#   cmake -S . -B build -DCMAKE_PREFIX_PATH=/where/plab/is/installed
#   cmake --build build && (cd build && ctest --output-on-failure)
#   PLAB_PLUGIN_PATH=$PWD/build plab plugins --describe @NAME@
cmake_minimum_required(VERSION 3.20)
project(@NAME@_model LANGUAGES CXX)

find_package(ParticleLab REQUIRED)
plab_add_contact_model(@NAME@ @NAME@.cpp)   # -> build/plab_@NAME@.so

enable_testing()
find_package(Catch2 2 REQUIRED)
add_executable(@NAME@_test @NAME@_test.cpp)
target_link_libraries(@NAME@_test PRIVATE plab::api Catch2::Catch2)
target_compile_features(@NAME@_test PRIVATE cxx_std_17)
add_test(NAME @NAME@_law COMMAND @NAME@_test)

# plab loads the library: the host checks the ABI version and the description.
add_test(NAME @NAME@_loads_in_plab COMMAND ${PLAB_EXECUTABLE} plugins --describe @NAME@)
set_tests_properties(@NAME@_loads_in_plab PROPERTIES ENVIRONMENT PLAB_PLUGIN_PATH=${PLAB_PLUGIN_OUTPUT_DIR})
)~";

const char* header_template = R"~(// `@NAME@` — a damped linear spring (start here and change the law):
//   F_n = k d + 2 beta sqrt(m* k) (-v_n),  no tension unless `tension`, no tangential force.
// docs/writing-a-contact-model.md in ParticleLab walks through every part.
#pragma once

#include <plab/contact_model.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

struct @CLASS@ {
    static constexpr const char* name = "@NAME@";
    static constexpr const char* doc = "Damped linear normal spring, no tension by default (skeleton from plab new-model).";
    static constexpr const char* timestep_rule = "per ball sqrt(m / sum k) over its contacts";
    static constexpr uint32_t range_kind = PLAB_RANGE_GAP;
    // What the law reads besides normal, gap, relative velocity, history and
    // dt, and writes besides force, energies and stiffness (abi.h PLAB_IO_*):
    // the host packs only these for it.
    static constexpr uint32_t io = PLAB_IO_EFF_MASS;

    // Every property, by kind (plab/contact_model.hpp, plab::prop): number
    // (scene key, name, SI unit, default, valid range, flags, doc, and how
    // two materials' values mix in a contact between them: for a property
    // the model takes from a material, `using material = ...;`, see
    // docs/writing-a-contact-model.md), integer, boolean, choice (named
    // values: the law gets the name's index) and group (a group of the
    // scene by name: the law gets its index).
    enum Prop : int { stiffness, damping_ratio, tension, prop_count };
    static constexpr plab_property_desc properties[] = {
        plab::prop::number("k", "normal stiffness", "N/m", 1e6, 0.0, std::numeric_limits<double>::infinity(),
                           PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE, "F_n = k d",
                           PLAB_MIX_HARMONIC),  // two materials' k1, k2: 2 k1 k2 / (k1 + k2)
        plab::prop::number("beta", "critical damping ratio", "1", 0.0, 0.0, 1.0, PLAB_MAX_EXCLUSIVE,
                           "dashpot 2 beta sqrt(m* k)", PLAB_MIX_ARITHMETIC),
        plab::prop::boolean("tension", "dashpot may pull", false,
                            "false: the normal force is kept >= 0; true: the dashpot may pull the balls together"),
    };

    // Active while the balls touch (surface gap <= 0).
    static double activity_range(const double*) { return 0.0; }

    explicit @CLASS@(const double* p) : k_(p[stiffness]), beta_(p[damping_ratio]), tension_(p[tension] != 0) {}

    // The law for one contact; the adapter loops it over the host's batch.
    void law(const plab::Contact& c) const {
        const plab::Vec3 n = c.normal();  // from end 1 to end 2
        const double vn = dot(c.rel_velocity(), n);
        const double f = k_ * c.overlap() - 2.0 * beta_ * std::sqrt(c.eff_mass() * k_) * vn;
        const double fn = tension_ ? f : std::max(0.0, f);
        c.set_force(fn * n);                           // the force on end 2
        c.set_strain_energy(0.5 * k_ * c.overlap() * c.overlap());
        c.set_stiffness(k_);                           // the host's stable step sqrt(m/k)
    }

private:
    double k_, beta_;
    bool tension_;
};
)~";

const char* source_template = R"~(// The plug-in library: exports the two entry points plab looks for.
#include "@NAME@.hpp"

PLAB_PLUGIN(plab::add_contact_model<@CLASS@>(r))
)~";

const char* test_template = R"~(// @NAME@ against the undamped spring: half a period in contact,
// t_c = pi sqrt(m*/k), and full rebound.
#define CATCH_CONFIG_MAIN
#include "@NAME@.hpp"

#include <plab/testing.hpp>

#include <catch2/catch.hpp>

#include <cmath>

TEST_CASE("@NAME@ pushes touching balls apart with k times the overlap", "[@NAME@]") {
    plab::testing::Probe p(plab::contact_model_desc<@CLASS@>(), {{"k", 2e5}});
    CHECK(p.force(-1e-4).x == Approx(2e5 * 1e-4));
    CHECK(p.force(1e-4).x == 0.0);  // apart: no force
}

TEST_CASE("@NAME@ without damping stays in contact for pi sqrt(m*/k) and rebounds fully", "[@NAME@]") {
    plab::testing::Probe p(plab::contact_model_desc<@CLASS@>(), {{"k", 2e5}});
    const double tc = M_PI * std::sqrt(p.eff_mass() / 2e5);
    const plab::testing::Impact im = p.impact(1.0, tc / 1000);
    CHECK(im.duration == Approx(tc).epsilon(1e-3));
    CHECK(im.restitution == Approx(1.0).epsilon(1e-3));
}
)~";

const char* readme_template = R"~(# Contact model `@NAME@`

Written by `plab new-model @NAME@`: a damped linear spring to start from.
The law is `@CLASS@::law` in `@NAME@.hpp`; `@NAME@.cpp` exports it.

    cmake -S . -B build -DCMAKE_PREFIX_PATH=/where/plab/is/installed
    cmake --build build
    (cd build && ctest --output-on-failure)
    PLAB_PLUGIN_PATH=$PWD/build plab plugins --describe @NAME@

In a scene: `"plugins": ["@NAME@"]` and
`{"groups": ["*", "*"], "model": "@NAME@", "properties": {"k": 1e6, "beta": 0.1, "tension": false}}`
under `contact_models`, with `PLAB_PLUGIN_PATH` pointing at `build/`.
)~";

std::string fill(std::string text, const std::string& name, const std::string& cls) {
    for (const auto& [key, value] : {std::pair<std::string, std::string>{"@NAME@", name}, {"@CLASS@", cls}})
        for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size()))
            text.replace(at, key.size(), value);
    return text;
}

// "my_model" -> "MyModel"
std::string class_name(const std::string& name) {
    std::string cls;
    bool up = true;
    for (char ch : name) {
        if (ch == '_') { up = true; continue; }
        cls += up ? char(std::toupper(static_cast<unsigned char>(ch))) : ch;
        up = false;
    }
    return cls;
}

bool valid_name(const std::string& n) {
    if (n.empty() || !(std::islower(static_cast<unsigned char>(n[0])))) return false;
    for (char ch : n)
        if (!(std::islower(static_cast<unsigned char>(ch)) || std::isdigit(static_cast<unsigned char>(ch)) || ch == '_'))
            return false;
    return true;
}

} // namespace

int cmd_new_model(const std::vector<std::string>& args) {
    if (args.empty() || args.size() > 2)
        throw InputError("command line", "usage: plab new-model NAME [DIR]  (DIR defaults to ./NAME)");
    const std::string name = args[0];
    if (!valid_name(name))
        throw InputError("command line", "model name '" + name +
                                             "' must start with a lower-case letter and hold only a-z, 0-9 and _ "
                                             "(it names the scene's model and the library plab_" + name + ".so)");
    const fs::path dir = args.size() == 2 ? fs::path(args[1]) : fs::path(name);
    std::error_code ec;
    if (fs::exists(dir, ec) && !fs::is_empty(dir, ec))
        throw InputError("command line", "folder " + dir.string() + " exists and is not empty; choose another DIR");
    fs::create_directories(dir);
    const std::string cls = class_name(name);
    const std::pair<std::string, const char*> files[] = {{"CMakeLists.txt", cmake_template},
                                                         {name + ".hpp", header_template},
                                                         {name + ".cpp", source_template},
                                                         {name + "_test.cpp", test_template},
                                                         {"README.md", readme_template}};
    for (const auto& [file, text] : files) {
        std::ofstream out(dir / file);
        out << fill(text, name, cls);
        if (!out) throw InputError("command line", "cannot write " + (dir / file).string());
        std::cout << "wrote " << (dir / file).string() << "\n";
    }
    return 0;
}

} // namespace plab
