// The plug-in host: finds shared libraries, checks their ABI version, and
// keeps the models, passes and materials they register (as copies of their
// descriptions, checked against the struct sizes this host needs). Libraries stay loaded as long as
// the host lives; every world holds the host, so no model outlives its code.
#pragma once

#include <plab/abi.h>

#include <memory>
#include <string>
#include <vector>

namespace boost::dll { class shared_library; }

namespace plab {

struct LoadedLibrary {
    std::string path;
    std::unique_ptr<boost::dll::shared_library> lib;
    std::vector<std::string> models, passes;
    std::vector<std::string> materials;  // it registers (first, or alike after another library)
};

class PluginHost {
public:
    PluginHost();
    ~PluginHost();
    PluginHost(const PluginHost&) = delete;
    PluginHost& operator=(const PluginHost&) = delete;

    // Search path: PLAB_PLUGIN_PATH folders (colon-separated) first, then the
    // built-in plug-ins (bin/../lib/plab/plugins beside an installed plab,
    // else the build folder), then any folder added here (e.g. the scene's).
    void add_search_dir(const std::string& dir, bool front = false);
    const std::vector<std::string>& search_dirs() const { return dirs_; }

    // Resolve a plug-in reference (a name like "linear", or a path to a .so)
    // to a file; throws PluginError naming what was tried. The name of a
    // library merged into another resolves to that one (merged_into).
    std::string resolve(const std::string& name_or_path, const std::string& relative_to = "") const;
    // The library a former library name is now part of ("sph_passes" ->
    // "sph"), or "" for any other name.
    static std::string merged_into(const std::string& name);
    // Load a library once (idempotent by canonical path); throws PluginError.
    const LoadedLibrary& load(const std::string& path);
    // Every library file in the search path.
    std::vector<std::string> discover() const;

    const plab_contact_model_desc* model(const std::string& name) const;
    const plab_pass_desc* pass(const std::string& name) const;
    std::vector<std::string> model_names() const;
    std::vector<std::string> pass_names() const;
    const std::string& library_of_model(const std::string& name) const;
    const std::string& library_of_pass(const std::string& name) const;
    // A material (abi.h plab_material_desc) by name; nullptr: not registered.
    // Its library: the first that registered it.
    const plab_material_desc* material(const std::string& name) const;
    const std::string& library_of_material(const std::string& name) const;
    // Checkpoint hooks of a pass with private state; nullptr: stateless.
    const plab_pass_state_hooks* pass_state(const std::string& name) const;
    const std::vector<LoadedLibrary>& libraries() const { return libs_; }

    // registrar callbacks (C ABI)
    int register_model(const plab_contact_model_desc* d);
    int register_pass(const plab_pass_desc* d);
    int register_pass_state(const plab_pass_state_hooks* h);
    int register_material(const plab_material_desc* d);

private:
    // A model or pass of that name already registered: a problem noted, true.
    bool name_taken(const std::string& name, const char* kind);
    std::vector<std::string> dirs_;
    std::vector<LoadedLibrary> libs_;
    // what the libraries registered: the host's copies of their descriptions
    // (abi.h: each struct read by its own size), by name, with the library
    // of each (plugin_host.cpp)
    struct Registry;
    std::unique_ptr<Registry> registry_;
    std::string loading_;                         // library being initialised
    std::vector<std::string> loading_materials_;  // the materials it registers
    // the problems of a model's or pass's `material` (abi.h): registered,
    // and each of its properties that the material declares declared alike
    std::vector<std::string> check_material_use(const char* material, const plab_property_desc* p, uint32_t n) const;
    std::vector<std::string> problems_; // registration problems of `loading_`
};

// Checks a property list: sizes, kinds, names, units, ranges, choices,
// mixing rules, defaults inside ranges. Returns the problems found (empty:
// well-formed).
std::vector<std::string> check_properties(const plab_property_desc* p, uint32_t n);
// Checks a contact model description; returns the problems found.
std::vector<std::string> check_model_desc(const plab_contact_model_desc& d);
// The material's description of the property `key`; nullptr when the
// material (may be nullptr) does not declare it.
const plab_property_desc* material_property(const plab_material_desc* m, const char* key);
// How two descriptions of one property differ in what the host checks and
// the law reads (kind, unit, default, range, flags, mixing, choices; not
// name or doc), e.g. "default 998 against 1000"; "" when they do not.
std::string declaration_difference(const plab_property_desc& a, const plab_property_desc& b);

// "[min, max)" style text of a property's valid range; for a bool "true or
// false", a choice "one of a, b, c", a group "a group name" (", or none").
std::string range_text(const plab_property_desc& p);
// v is a valid value of p as the plug-in sees it (a choice's index, a
// bool's 0/1, a group index or -1 where none is allowed).
bool in_range(const plab_property_desc& p, double v);
// Names of the kinds and mixing rules ("number", "harmonic", ...);
// "unknown" for a value abi.h does not define.
const char* kind_name(uint32_t kind);
const char* mixing_name(uint32_t mixing);

} // namespace plab
