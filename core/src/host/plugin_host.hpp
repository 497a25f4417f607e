// The plug-in host: finds shared libraries, checks their ABI version, and
// keeps the models and passes they register. Libraries stay loaded as long as
// the host lives; every world holds the host, so no model outlives its code.
#pragma once

#include <plab/abi.h>

#include <list>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace boost::dll { class shared_library; }

namespace plab {

struct LoadedLibrary {
    std::string path;
    std::unique_ptr<boost::dll::shared_library> lib;
    std::vector<std::string> models, passes;
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
    // to a file; throws PluginError naming what was tried.
    std::string resolve(const std::string& name_or_path, const std::string& relative_to = "") const;
    // Load a library once (idempotent by canonical path); throws PluginError.
    const LoadedLibrary& load(const std::string& path);
    // Every library file in the search path.
    std::vector<std::string> discover() const;

    const plab_contact_model_desc* model(const std::string& name) const;
    const plab_pass_desc* pass(const std::string& name) const;
    std::vector<std::string> model_names() const;
    std::vector<std::string> pass_names() const;
    const std::string& library_of_model(const std::string& name) const { return model_lib_.at(name); }
    const std::string& library_of_pass(const std::string& name) const { return pass_lib_.at(name); }
    // Checkpoint hooks of a pass with private state; nullptr: stateless.
    const plab_pass_state_hooks* pass_state(const std::string& name) const;
    const std::vector<LoadedLibrary>& libraries() const { return libs_; }

    // registrar callbacks (C ABI)
    int register_model(const plab_contact_model_desc* d);
    int register_pass(const plab_pass_desc* d);
    int register_pass_state(const plab_pass_state_hooks* h);

private:
    std::vector<std::string> dirs_;
    std::vector<LoadedLibrary> libs_;
    std::map<std::string, const plab_contact_model_desc*> models_;
    std::map<std::string, const plab_pass_desc*> passes_;
    std::map<std::string, std::string> model_lib_, pass_lib_;
    std::map<std::string, const plab_pass_state_hooks*> pass_state_;
    std::string loading_;               // library being initialised
    std::uint32_t loading_version_ = 0; // its plug-in ABI version
    // descriptions of plug-ins older than ABI 4, copied up to `flags` and
    // completed with zeros (their own struct ends before it)
    std::list<plab_contact_model_desc> upgraded_;
    std::vector<std::string> problems_; // registration problems of `loading_`
};

// Checks a property list: names, units, ranges, defaults inside ranges.
// Returns the problems found (empty: well-formed).
std::vector<std::string> check_properties(const plab_property_desc* p, uint32_t n);
// Checks a contact model description; returns the problems found.
std::vector<std::string> check_model_desc(const plab_contact_model_desc& d);

// "[min, max)" style text of a property's valid range.
std::string range_text(const plab_property_desc& p);
bool in_range(const plab_property_desc& p, double v);

} // namespace plab
