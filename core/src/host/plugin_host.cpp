#include <plab_host/plugins.hpp>

#include <plab_host/errors.hpp>

#include <boost/dll/runtime_symbol_info.hpp>
#include <boost/dll/shared_library.hpp>

#include <list>
#include <map>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#ifndef PLAB_PLUGIN_DIR
#define PLAB_PLUGIN_DIR ""
#endif
#ifndef PLAB_PLUGIN_DIR_FROM_BIN
#define PLAB_PLUGIN_DIR_FROM_BIN "../lib/plab/plugins"
#endif

namespace fs = std::filesystem;

namespace plab {

namespace {

int cb_register_model(void* host, const plab_contact_model_desc* d) {
    return static_cast<PluginHost*>(host)->register_model(d);
}
int cb_register_pass(void* host, const plab_pass_desc* d) {
    return static_cast<PluginHost*>(host)->register_pass(d);
}
int cb_register_pass_state(void* host, const plab_pass_state_hooks* h) {
    return static_cast<PluginHost*>(host)->register_pass_state(h);
}

// Libraries merged into another: the former name loads the new library
// (the SPH passes joined the sph model in the SPH package's one library).
const std::map<std::string, std::string>& merged_libraries() {
    static const std::map<std::string, std::string> merged = {{"sph_passes", "sph"}};
    return merged;
}

int cb_register_material(void* host, const plab_material_desc* d) {
    return static_cast<PluginHost*>(host)->register_material(d);
}

// The smallest model and pass descriptions this host reads: ABI 2.0's,
// which end before `material` (abi.h); what they lack reads as zero. So
// for a history slot: ABI 2.1's ends before `flags`.
constexpr std::size_t kMinModelDescSize = offsetof(plab_contact_model_desc, material);
constexpr std::size_t kMinPassDescSize = offsetof(plab_pass_desc, material);
constexpr std::size_t kMinHistoryDescSize = offsetof(plab_history_desc, flags);

std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

std::string join(const std::vector<std::string>& v, const char* sep = ", ") {
    std::string out;
    for (const auto& s : v) out += (out.empty() ? "" : sep) + s;
    return out;
}

// The built-in plug-ins: beside an installed plab (bin/../lib/plab/plugins),
// else the build folder they were built into. Only one of the two, so an
// installed plab never mixes in a build tree's libraries.
std::string builtin_plugin_dir() {
    boost::dll::fs::error_code ec;
    const fs::path exe = boost::dll::program_location(ec).string();
    if (!ec) {
        std::error_code fec;
        const fs::path installed = exe.parent_path() / PLAB_PLUGIN_DIR_FROM_BIN;
        if (fs::is_directory(installed, fec)) return installed.lexically_normal().string();
    }
    return PLAB_PLUGIN_DIR;
}

std::string too_small(const std::string& what, const char* type, uint32_t size, std::size_t needed,
                      uint32_t minor = PLAB_ABI_MINOR) {
    return what + " is " + std::to_string(size) + " bytes (its `size`), smaller than the " + std::to_string(needed) +
           " bytes of " + type + " in plug-in ABI " + std::to_string(PLAB_ABI_MAJOR) + "." +
           std::to_string(minor) + "; rebuild it against this ParticleLab's headers";
}

// The host's copy of a plug-in's description array, read with the stride of
// its first element's `size` (abi.h); false (and a problem) when an element
// is smaller than `min_size` (the struct of the oldest minor this host
// reads, `min_minor`: the members it lacks read as zero).
template <class T>
bool copy_array(const T* src, uint32_t n, const std::string& what, const char* type, std::vector<T>& out,
                std::vector<std::string>& bad, std::size_t min_size = sizeof(T), uint32_t min_minor = PLAB_ABI_MINOR) {
    out.clear();
    if (n == 0) return true;
    if (!src) {
        bad.push_back(what + " count is " + std::to_string(n) + " but the array is NULL");
        return false;
    }
    const uint32_t stride = src->size;
    if (stride < min_size) {
        bad.push_back(too_small("each " + what + " description", type, stride, min_size, min_minor));
        return false;
    }
    const char* base = reinterpret_cast<const char*>(src);
    for (uint32_t i = 0; i < n; ++i) {
        const T* e = reinterpret_cast<const T*>(base + std::size_t(i) * stride);
        if (e->size != stride) {
            bad.push_back(what + " #" + std::to_string(i) + " has size " + std::to_string(e->size) + ", the first " +
                          std::to_string(stride) + " (one array, one struct size)");
            return false;
        }
        T c;
        std::memset(&c, 0, sizeof(T));
        std::memcpy(&c, e, std::min<std::size_t>(stride, sizeof(T)));
        c.size = uint32_t(sizeof(T));
        out.push_back(c);
    }
    return true;
}

template <class T> const T* data_or_null(const std::vector<T>& v) { return v.empty() ? nullptr : v.data(); }

// The refusal of a library built for another plug-in ABI (abi.h: version =
// major << 16 | minor; ABI 1 returned 1 to 7).
std::string abi_mismatch(const std::string& path, uint32_t version) {
    const uint32_t major = version >> 16, minor = version & 0xffffu;
    const std::string ours = std::to_string(PLAB_ABI_MAJOR) + "." + std::to_string(PLAB_ABI_MINOR);
    const std::string lib = "plug-in library " + path;
    if (major == 0 && minor >= 1 && minor <= 7)
        return lib + " was built against plug-in ABI 1 (version " + std::to_string(minor) + "); rebuild it against ABI " +
               std::to_string(PLAB_ABI_MAJOR) + " (this ParticleLab's headers: property kinds and struct sizes, "
               "docs/abi-changes.md)";
    if (major == PLAB_ABI_MAJOR)
        return lib + " was built against plug-in ABI " + std::to_string(major) + "." + std::to_string(minor) +
               ", newer than this plab's " + ours + "; use a newer plab or rebuild it against this ParticleLab's headers";
    return lib + " reports plug-in ABI version " + std::to_string(version) + " (major " + std::to_string(major) +
           "), which this plab does not speak (it speaks ABI " + ours + "); rebuild it against this ParticleLab's headers";
}

} // namespace

const char* kind_name(uint32_t kind) {
    switch (kind) {
    case PLAB_KIND_NUMBER: return "number";
    case PLAB_KIND_INTEGER: return "integer";
    case PLAB_KIND_BOOL: return "bool";
    case PLAB_KIND_CHOICE: return "choice";
    case PLAB_KIND_GROUP: return "group";
    default: return "unknown";
    }
}

const char* mixing_name(uint32_t mixing) {
    switch (mixing) {
    case PLAB_MIX_NONE: return "none";
    case PLAB_MIX_HARMONIC: return "harmonic";
    case PLAB_MIX_ARITHMETIC: return "arithmetic";
    case PLAB_MIX_GEOMETRIC: return "geometric";
    case PLAB_MIX_MAX: return "max";
    case PLAB_MIX_MIN: return "min";
    default: return "unknown";
    }
}

std::string range_text(const plab_property_desc& p) {
    switch (p.kind) {
    case PLAB_KIND_BOOL: return "true or false";
    case PLAB_KIND_CHOICE: {
        std::vector<std::string> names;
        for (uint32_t c = 0; p.choices && c < p.choice_count; ++c) names.push_back(p.choices[c] ? p.choices[c] : "?");
        return "one of " + join(names);
    }
    case PLAB_KIND_GROUP: return p.flags & PLAB_GROUP_NONE_ALLOWED ? "a group name, or none" : "a group name";
    default:
        return std::string(p.flags & PLAB_MIN_EXCLUSIVE ? "(" : "[") + fmt(p.min_value) + ", " + fmt(p.max_value) +
               (p.flags & PLAB_MAX_EXCLUSIVE ? ")" : "]") + (p.kind == PLAB_KIND_INTEGER ? ", whole numbers" : "");
    }
}

bool in_range(const plab_property_desc& p, double v) {
    if (std::isnan(v)) return false;
    const bool whole = std::floor(v) == v;
    switch (p.kind) {
    case PLAB_KIND_BOOL: return v == 0.0 || v == 1.0;
    case PLAB_KIND_CHOICE: return whole && v >= 0.0 && v < double(p.choice_count);
    case PLAB_KIND_GROUP: return whole && (v >= 0.0 || (v == -1.0 && (p.flags & PLAB_GROUP_NONE_ALLOWED)));
    default: {
        const bool lo = (p.flags & PLAB_MIN_EXCLUSIVE) ? v > p.min_value : v >= p.min_value;
        const bool hi = (p.flags & PLAB_MAX_EXCLUSIVE) ? v < p.max_value : v <= p.max_value;
        return lo && hi && (p.kind != PLAB_KIND_INTEGER || whole);
    }
    }
}

std::vector<std::string> check_properties(const plab_property_desc* p, uint32_t n) {
    std::vector<std::string> bad;
    if (n > 0 && !p) bad.push_back("property_count > 0 but properties is NULL");
    for (uint32_t i = 0; p && i < n; ++i) {
        const plab_property_desc& q = p[i];
        const std::string key = q.key ? q.key : "#" + std::to_string(i);
        if (!q.key || !*q.key) bad.push_back("property " + key + " has no key");
        if (!q.name || !*q.name) bad.push_back("property " + key + " has no name");
        if (!q.unit || !*q.unit)
            bad.push_back("property " + key + " has no SI unit (use \"1\" for a dimensionless one)");
        if (!q.doc) bad.push_back("property " + key + " has no doc text");
        if (q.flags & ~uint32_t(PLAB_MIN_EXCLUSIVE | PLAB_MAX_EXCLUSIVE | PLAB_GROUP_NONE_ALLOWED))
            bad.push_back("property " + key + " has flags this host does not know (abi.h)");
        if (q.mixing > PLAB_MIX_MIN)
            bad.push_back("property " + key + " has a mixing rule this host does not know (abi.h PLAB_MIX_*)");
        else if (q.mixing != PLAB_MIX_NONE && q.kind != PLAB_KIND_NUMBER &&
                 !(q.kind == PLAB_KIND_INTEGER && (q.mixing == PLAB_MIX_MAX || q.mixing == PLAB_MIX_MIN)))
            bad.push_back("property " + key + " is of kind " + kind_name(q.kind) + ", which cannot mix by " +
                          mixing_name(q.mixing) + " (numbers mix; an integer by max or min only)");
        if ((q.flags & PLAB_GROUP_NONE_ALLOWED) && q.kind != PLAB_KIND_GROUP)
            bad.push_back("property " + key + " has PLAB_GROUP_NONE_ALLOWED but is not of kind group");
        if ((q.choices || q.choice_count) && q.kind != PLAB_KIND_CHOICE)
            bad.push_back("property " + key + " has choices but is not of kind choice");
        switch (q.kind) {
        case PLAB_KIND_NUMBER:
        case PLAB_KIND_INTEGER:
            if (std::isnan(q.min_value) || std::isnan(q.max_value) || q.min_value > q.max_value)
                bad.push_back("property " + key + " has no valid range (min <= max, not NaN)");
            else if (!in_range(q, q.default_value))
                bad.push_back("property " + key + " default " + fmt(q.default_value) + " is outside its range " +
                              range_text(q));
            break;
        case PLAB_KIND_BOOL:
            if (!in_range(q, q.default_value))
                bad.push_back("property " + key + " (bool) default " + fmt(q.default_value) + " is not 0 or 1");
            break;
        case PLAB_KIND_CHOICE:
            if (q.choice_count < 2 || !q.choices) {
                bad.push_back("property " + key + " (choice) needs two or more choices (choices, choice_count)");
                break;
            }
            for (uint32_t c = 0; c < q.choice_count; ++c) {
                if (!q.choices[c] || !*q.choices[c]) {
                    bad.push_back("property " + key + " has an empty choice name (#" + std::to_string(c) + ")");
                    continue;
                }
                for (uint32_t e = 0; e < c; ++e)
                    if (q.choices[e] && std::string(q.choices[e]) == q.choices[c])
                        bad.push_back("property " + key + " names the choice \"" + q.choices[c] + "\" twice");
            }
            if (!in_range(q, q.default_value))
                bad.push_back("property " + key + " (choice) default " + fmt(q.default_value) +
                              " is not an index into its " + std::to_string(q.choice_count) + " choices");
            break;
        case PLAB_KIND_GROUP:
            if (q.default_value != -1.0)
                bad.push_back("property " + key + " (group) default " + fmt(q.default_value) +
                              " is not -1 (a scene names its groups: there is no default group)");
            break;
        default:
            bad.push_back("property " + key + " has an unknown kind " + std::to_string(q.kind) + " (abi.h PLAB_KIND_*)");
        }
        for (uint32_t j = 0; j < i; ++j)
            if (p[j].key && q.key && std::string(p[j].key) == q.key)
                bad.push_back("property key " + key + " is declared twice");
    }
    return bad;
}

namespace {
// A tangential vector (PLAB_HISTORY_TANGENTIAL) is three slots, x, y, z:
// its first slot has two after it, neither the first of another.
std::vector<std::string> check_tangential_slots(const plab_contact_model_desc& d) {
    std::vector<std::string> bad;
    for (uint32_t i = 0; d.history && i < d.history_count; ++i) {
        const std::string slot = "history slot " + std::to_string(i);
        const uint32_t flags = d.history[i].flags;
        if (flags & ~uint32_t(PLAB_HISTORY_KNOWN_FLAGS))
            bad.push_back(slot + " has flags this host does not know (abi.h PLAB_HISTORY_*)");
        if (!(flags & PLAB_HISTORY_TANGENTIAL)) continue;
        if (i + 2 >= d.history_count)
            bad.push_back(slot + " is flagged tangential, the x of a vector, but fewer than two slots follow it");
        else if ((d.history[i + 1].flags | d.history[i + 2].flags) & PLAB_HISTORY_TANGENTIAL)
            bad.push_back(slot + " is flagged tangential, the x of a vector, and so is its y or z");
        else
            i += 2;
    }
    return bad;
}
} // namespace

std::vector<std::string> check_model_desc(const plab_contact_model_desc& d) {
    std::vector<std::string> bad = check_properties(d.properties, d.property_count);
    if (!d.name || !*d.name) bad.push_back("model has no name");
    if (!d.doc) bad.push_back("model has no doc text");
    if (!d.timestep_rule || !*d.timestep_rule)
        bad.push_back("model does not state its stable-timestep rule (timestep_rule); the host needs "
                      "set_stiffness() or set_dt_limit() from every active contact");
    if (!d.activity_range) bad.push_back("model has no activity_range function");
    if (!d.compute) bad.push_back("model has no compute function");
    if (d.range_kind != PLAB_RANGE_GAP && d.range_kind != PLAB_RANGE_DISTANCE)
        bad.push_back("range_kind must be PLAB_RANGE_GAP or PLAB_RANGE_DISTANCE");
    if (d.history_count > 0 && !d.history) bad.push_back("history_count > 0 but history is NULL");
    if (d.persist_slot < -1 || d.persist_slot >= int32_t(d.history_count))
        bad.push_back("persist_slot must be -1 or the index of a history slot");
    if (d.flags & ~uint32_t(PLAB_MODEL_KNOWN_FLAGS)) bad.push_back("flags has bits this host does not know (abi.h PLAB_MODEL_*)");
    if (d.io & ~uint32_t(PLAB_IO_KNOWN_BITS)) bad.push_back("io has bits this host does not know (abi.h PLAB_IO_*)");
    if (!(d.io & PLAB_IO_DECLARED))
        bad.push_back("does not declare its io (PLAB_IO_DECLARED not set): name the optional inputs it reads and "
                      "outputs it writes, PLAB_IO_DECLARED alone for none (abi.h PLAB_IO_*; in C++ "
                      "`static constexpr uint32_t io = ...;`)");
    for (uint32_t i = 0; d.history && i < d.history_count; ++i) {
        if (!d.history[i].name || !*d.history[i].name) bad.push_back("history slot " + std::to_string(i) + " has no name");
        if (d.history[i].swap_rule > PLAB_SWAP_NEGATE)
            bad.push_back("history slot " + std::to_string(i) + " has an unknown swap rule");
    }
    for (const std::string& b : check_tangential_slots(d)) bad.push_back(b);
    return bad;
}

const plab_property_desc* material_property(const plab_material_desc* m, const char* key) {
    if (!m || !key) return nullptr;
    for (uint32_t i = 0; i < m->property_count; ++i)
        if (m->properties[i].key && std::strcmp(m->properties[i].key, key) == 0) return &m->properties[i];
    return nullptr;
}

std::string declaration_difference(const plab_property_desc& a, const plab_property_desc& b) {
    const auto text = [](const char* s) { return std::string(s ? s : ""); };
    if (a.kind != b.kind) return std::string("kind ") + kind_name(a.kind) + " against " + kind_name(b.kind);
    if (text(a.unit) != text(b.unit)) return "unit " + text(a.unit) + " against " + text(b.unit);
    if (!(a.default_value == b.default_value))
        return "default " + fmt(a.default_value) + " against " + fmt(b.default_value);
    if (!(a.min_value == b.min_value) || !(a.max_value == b.max_value) || a.flags != b.flags)
        return "range " + range_text(a) + " against " + range_text(b) + (a.flags != b.flags ? " (flags)" : "");
    if (a.mixing != b.mixing) return std::string("mixing ") + mixing_name(a.mixing) + " against " + mixing_name(b.mixing);
    bool same_choices = a.choice_count == b.choice_count && (a.choices == nullptr) == (b.choices == nullptr);
    for (uint32_t c = 0; same_choices && a.choices && c < a.choice_count; ++c)
        same_choices = text(a.choices[c]) == text(b.choices[c]);
    if (!same_choices) return range_text(a) + " against " + range_text(b);
    return "";
}

// What the libraries registered: the host's copies of their descriptions
// (abi.h: each struct read by its own size), to which the maps by name
// point, and the library that registered each.
struct PluginHost::Registry {
    struct ModelCopy {
        plab_contact_model_desc desc;
        std::vector<plab_property_desc> properties;
        std::vector<plab_history_desc> history;
        std::vector<plab_field_desc> fields_read, fields_accumulated;
    };
    struct PassCopy {
        plab_pass_desc desc;
        std::vector<plab_property_desc> properties;
        std::vector<plab_field_desc> fields;
    };
    struct MaterialCopy {
        plab_material_desc desc;
        std::vector<plab_property_desc> properties;
    };
    std::list<ModelCopy> model_copies;
    std::list<PassCopy> pass_copies;
    std::list<plab_pass_state_hooks> hook_copies;
    std::list<MaterialCopy> material_copies;
    std::map<std::string, const plab_contact_model_desc*> models;
    std::map<std::string, const plab_pass_desc*> passes;
    std::map<std::string, std::string> model_lib, pass_lib;
    std::map<std::string, const plab_pass_state_hooks*> pass_state;
    std::map<std::string, const plab_material_desc*> materials;
    std::map<std::string, std::string> material_lib;
};

PluginHost::PluginHost() : registry_(std::make_unique<Registry>()) {
    if (const std::string builtin = builtin_plugin_dir(); !builtin.empty()) dirs_.push_back(builtin);
    if (const char* env = std::getenv("PLAB_PLUGIN_PATH")) {
        std::stringstream ss(env);
        std::string d;
        while (std::getline(ss, d, ':'))
            if (!d.empty()) dirs_.insert(dirs_.begin(), d);  // the user's folders win
    }
}

PluginHost::~PluginHost() = default;

const std::string& PluginHost::library_of_model(const std::string& name) const { return registry_->model_lib.at(name); }
const std::string& PluginHost::library_of_pass(const std::string& name) const { return registry_->pass_lib.at(name); }
const std::string& PluginHost::library_of_material(const std::string& name) const {
    return registry_->material_lib.at(name);
}

void PluginHost::add_search_dir(const std::string& dir, bool front) {
    if (front) dirs_.insert(dirs_.begin(), dir);
    else dirs_.push_back(dir);
}

namespace {
// A name no file can have (too long, say) is simply not there: no
// filesystem_error escapes the resolution of a scene's plug-in name.
bool file_exists(const fs::path& p) {
    std::error_code ec;
    return fs::exists(p, ec) && !ec;
}
} // namespace

std::string PluginHost::resolve(const std::string& ref, const std::string& relative_to) const {
    const bool is_path = ref.find('/') != std::string::npos || fs::path(ref).extension() == ".so";
    std::vector<std::string> tried;
    if (const std::string now = merged_into(ref); !is_path && !now.empty()) return resolve(now, relative_to);
    if (is_path) {
        fs::path p(ref);
        if (p.is_relative() && !relative_to.empty()) p = fs::path(relative_to) / p;
        if (file_exists(p)) return fs::canonical(p).string();
        throw PluginError("plug-in library '" + ref + "' not found (looked for " + p.string() + ")");
    }
    std::vector<std::string> dirs = dirs_;
    if (!relative_to.empty()) dirs.push_back(relative_to);
    for (const auto& d : dirs)
        for (const std::string& file : {"plab_" + ref + ".so", "lib" + ref + ".so", ref + ".so"}) {
            fs::path p = fs::path(d) / file;
            tried.push_back(p.string());
            if (file_exists(p)) return fs::canonical(p).string();
        }
    throw PluginError("plug-in '" + ref + "' not found in the search path (" + join(dirs) +
                      "); set PLAB_PLUGIN_PATH or give a path to the .so");
}

std::string PluginHost::merged_into(const std::string& name) {
    const auto it = merged_libraries().find(name);
    return it == merged_libraries().end() ? std::string() : it->second;
}

std::vector<std::string> PluginHost::discover() const {
    std::vector<std::string> out;
    for (const auto& d : dirs_) {
        std::error_code ec;
        if (!fs::is_directory(d, ec)) continue;
        std::vector<std::string> here;
        for (const auto& e : fs::directory_iterator(d, ec))
            if (e.path().extension() == ".so") here.push_back(fs::canonical(e.path()).string());
        std::sort(here.begin(), here.end());
        for (auto& h : here)
            if (std::find(out.begin(), out.end(), h) == out.end()) out.push_back(h);
    }
    return out;
}

const LoadedLibrary& PluginHost::load(const std::string& path_in) {
    const std::string path = fs::exists(path_in) ? fs::canonical(path_in).string() : path_in;
    for (const auto& l : libs_)
        if (l.path == path) return l;
    auto lib = std::make_unique<boost::dll::shared_library>();
    boost::dll::fs::error_code ec;
    lib->load(path, boost::dll::load_mode::rtld_local | boost::dll::load_mode::rtld_now, ec);
    if (ec) throw PluginError("plug-in library " + path + " cannot be loaded: " + ec.message());
    for (const char* sym : {"plab_plugin_abi_version", "plab_plugin_init"})
        if (!lib->has(sym))
            throw PluginError("plug-in library " + path + " has no entry point '" + sym +
                              "'; define it with PLAB_PLUGIN(...) from <plab/contact_model.hpp>");
    const uint32_t version = lib->get<uint32_t()>("plab_plugin_abi_version")();
    if (version >> 16 != PLAB_ABI_MAJOR || (version & 0xffffu) > PLAB_ABI_MINOR)
        throw PluginError(abi_mismatch(path, version));
    LoadedLibrary entry;
    entry.path = path;
    loading_ = path;
    problems_.clear();
    loading_materials_.clear();
    const auto before_models = registry_->models;
    const auto before_passes = registry_->passes;
    const auto before_materials = registry_->materials;
    plab_registrar reg{uint32_t(sizeof(plab_registrar)), this, &cb_register_model, &cb_register_pass, &cb_register_pass_state,
                       &cb_register_material};
    const int rc = lib->get<int(const plab_registrar*)>("plab_plugin_init")(&reg);
    loading_.clear();
    if (rc != 0 || !problems_.empty()) {
        // roll back whatever this library registered before failing
        for (auto it = registry_->models.begin(); it != registry_->models.end();)
            it = before_models.count(it->first) ? std::next(it) : (registry_->model_lib.erase(it->first), registry_->models.erase(it));
        for (auto it = registry_->passes.begin(); it != registry_->passes.end();)
            it = before_passes.count(it->first) ? std::next(it)
                                                : (registry_->pass_lib.erase(it->first), registry_->pass_state.erase(it->first), registry_->passes.erase(it));
        for (auto it = registry_->materials.begin(); it != registry_->materials.end();)
            it = before_materials.count(it->first) ? std::next(it) : (registry_->material_lib.erase(it->first), registry_->materials.erase(it));
        std::string why = problems_.empty() ? "plab_plugin_init returned " + std::to_string(rc) : join(problems_, "; ");
        throw PluginError("plug-in library " + path + " refused: " + why);
    }
    for (const auto& [name, lib_path] : registry_->model_lib)
        if (lib_path == path) entry.models.push_back(name);
    for (const auto& [name, lib_path] : registry_->pass_lib)
        if (lib_path == path) entry.passes.push_back(name);
    entry.materials = loading_materials_;  // (also those an earlier library registered alike)
    entry.lib = std::move(lib);
    libs_.push_back(std::move(entry));
    return libs_.back();
}

int PluginHost::register_model(const plab_contact_model_desc* d) {
    if (!d) { problems_.push_back("register_contact_model(NULL)"); return 1; }
    if (d->size < kMinModelDescSize) {
        problems_.push_back(too_small("a contact model description", "plab_contact_model_desc", d->size,
                                      kMinModelDescSize, 0));
        return 1;
    }
    Registry::ModelCopy c;
    std::memset(&c.desc, 0, sizeof(plab_contact_model_desc));  // (members of a later minor than the plug-in's)
    std::memcpy(&c.desc, d, std::min<std::size_t>(d->size, sizeof(plab_contact_model_desc)));
    c.desc.size = uint32_t(sizeof(plab_contact_model_desc));
    const std::string name = d->name ? d->name : "?";
    std::vector<std::string> bad;
    copy_array(d->properties, d->property_count, "property", "plab_property_desc", c.properties, bad);
    copy_array(d->history, d->history_count, "history slot", "plab_history_desc", c.history, bad, kMinHistoryDescSize, 0);
    copy_array(d->fields_read, d->fields_read_count, "field read", "plab_field_desc", c.fields_read, bad);
    copy_array(d->fields_accumulated, d->fields_accumulated_count, "field accumulated", "plab_field_desc",
               c.fields_accumulated, bad);
    if (!bad.empty()) { problems_.push_back("model '" + name + "': " + join(bad, "; ")); return 1; }
    Registry::ModelCopy& m = registry_->model_copies.emplace_back(std::move(c));
    m.desc.properties = data_or_null(m.properties);
    m.desc.history = data_or_null(m.history);
    m.desc.fields_read = data_or_null(m.fields_read);
    m.desc.fields_accumulated = data_or_null(m.fields_accumulated);
    d = &m.desc;
    bad = check_model_desc(*d);
    for (const std::string& b : check_material_use(d->material, d->properties, d->property_count)) bad.push_back(b);
    if (!bad.empty()) { problems_.push_back("model '" + name + "': " + join(bad, "; ")); return 1; }
    if (name_taken(name, "model")) return 1;
    registry_->models[name] = d;
    registry_->model_lib[name] = loading_;
    return 0;
}

bool PluginHost::name_taken(const std::string& name, const char* kind) {
    if (!registry_->models.count(name) && !registry_->passes.count(name)) return false;
    const std::string& other = registry_->models.count(name) ? registry_->model_lib[name] : registry_->pass_lib[name];
    problems_.push_back(std::string(kind) + " name '" + name + "' is already registered by " + other);
    return true;
}

int PluginHost::register_pass(const plab_pass_desc* d) {
    if (!d) { problems_.push_back("register_pass(NULL)"); return 1; }
    if (d->size < kMinPassDescSize) {
        problems_.push_back(too_small("a pass description", "plab_pass_desc", d->size, kMinPassDescSize, 0));
        return 1;
    }
    Registry::PassCopy c;
    std::memset(&c.desc, 0, sizeof(plab_pass_desc));  // (members of a later minor than the plug-in's)
    std::memcpy(&c.desc, d, std::min<std::size_t>(d->size, sizeof(plab_pass_desc)));
    c.desc.size = uint32_t(sizeof(plab_pass_desc));
    const std::string name = d->name && *d->name ? d->name : "?";
    std::vector<std::string> bad;
    copy_array(d->properties, d->property_count, "property", "plab_property_desc", c.properties, bad);
    copy_array(d->fields, d->field_count, "field", "plab_field_desc", c.fields, bad);
    if (!bad.empty()) { problems_.push_back("pass '" + name + "': " + join(bad, "; ")); return 1; }
    Registry::PassCopy& pc = registry_->pass_copies.emplace_back(std::move(c));
    pc.desc.properties = data_or_null(pc.properties);
    pc.desc.fields = data_or_null(pc.fields);
    d = &pc.desc;
    bad = check_properties(d->properties, d->property_count);
    if (name == "?") bad.push_back("pass has no name");
    if (!d->run) bad.push_back("pass has no run function");
    if (d->phase > PLAB_PHASE_PRE_DRIFT) bad.push_back("pass has an unknown phase");
    for (const std::string& b : check_material_use(d->material, d->properties, d->property_count)) bad.push_back(b);
    if (!bad.empty()) { problems_.push_back("pass '" + name + "': " + join(bad, "; ")); return 1; }
    if (name_taken(name, "pass")) return 1;
    registry_->passes[name] = d;
    registry_->pass_lib[name] = loading_;
    return 0;
}

int PluginHost::register_pass_state(const plab_pass_state_hooks* h) {
    if (h && h->size < sizeof(plab_pass_state_hooks)) {
        problems_.push_back(too_small("the pass state hooks", "plab_pass_state_hooks", h->size,
                                      sizeof(plab_pass_state_hooks)));
        return 1;
    }
    if (!h || !h->pass_name || !h->save || !h->load) {
        problems_.push_back("register_pass_state: hooks need a pass name, save and load");
        return 1;
    }
    const auto it = registry_->pass_lib.find(h->pass_name);
    if (it == registry_->pass_lib.end() || it->second != loading_) {
        problems_.push_back(std::string("register_pass_state: '") + h->pass_name + "' is not a pass of this library");
        return 1;
    }
    plab_pass_state_hooks& c = registry_->hook_copies.emplace_back();
    std::memcpy(&c, h, sizeof(plab_pass_state_hooks));
    c.size = uint32_t(sizeof(plab_pass_state_hooks));
    registry_->pass_state[h->pass_name] = &c;
    return 0;
}

int PluginHost::register_material(const plab_material_desc* d) {
    if (!d) { problems_.push_back("register_material(NULL)"); return 1; }
    if (d->size < sizeof(plab_material_desc)) {
        problems_.push_back(too_small("a material description", "plab_material_desc", d->size, sizeof(plab_material_desc)));
        return 1;
    }
    Registry::MaterialCopy c;
    std::memcpy(&c.desc, d, sizeof(plab_material_desc));
    c.desc.size = uint32_t(sizeof(plab_material_desc));
    const std::string name = d->name && *d->name ? d->name : "?";
    std::vector<std::string> bad;
    copy_array(d->properties, d->property_count, "property", "plab_property_desc", c.properties, bad);
    if (bad.empty()) {
        for (const std::string& b : check_properties(data_or_null(c.properties), uint32_t(c.properties.size()))) bad.push_back(b);
        if (name == "?") bad.push_back("material has no name");
        if (!d->doc) bad.push_back("material has no doc text");
        if (c.properties.empty()) bad.push_back("material declares no properties");
    }
    if (!bad.empty()) { problems_.push_back("material '" + name + "': " + join(bad, "; ")); return 1; }
    // a material several libraries (or models of one) register: the same
    // properties each time, declared alike, in the same order
    if (const auto it = registry_->materials.find(name); it != registry_->materials.end()) {
        const plab_material_desc& known = *it->second;
        std::string differs;
        if (known.property_count != c.properties.size())
            differs = std::to_string(c.properties.size()) + " properties against " + std::to_string(known.property_count);
        for (uint32_t i = 0; differs.empty() && i < known.property_count; ++i) {
            const plab_property_desc& a = c.properties[i];
            const plab_property_desc& b = known.properties[i];
            if (std::strcmp(a.key, b.key) != 0) differs = "property #" + std::to_string(i) + " " + a.key + " against " + b.key;
            else if (const std::string why = declaration_difference(a, b); !why.empty()) differs = std::string(a.key) + ": " + why;
        }
        if (differs.empty()) {  // registered before, alike
            if (std::find(loading_materials_.begin(), loading_materials_.end(), name) == loading_materials_.end())
                loading_materials_.push_back(name);
            return 0;
        }
        problems_.push_back("material '" + name + "' is already registered by " + registry_->material_lib[name] +
                            " with other properties (" + differs + "); one material, one description");
        return 1;
    }
    Registry::MaterialCopy& m = registry_->material_copies.emplace_back(std::move(c));
    m.desc.properties = data_or_null(m.properties);
    registry_->materials[name] = &m.desc;
    registry_->material_lib[name] = loading_;
    loading_materials_.push_back(name);
    return 0;
}

std::vector<std::string> PluginHost::check_material_use(const char* material, const plab_property_desc* p,
                                                        uint32_t n) const {
    if (!material) return {};
    if (!*material) return {"material is an empty name (NULL: no material)"};
    const auto it = registry_->materials.find(material);
    if (it == registry_->materials.end())
        return {std::string("takes its shared properties from the material '") + material +
                "', which is not registered; register the material before the models and passes that name it "
                "(plab::add_contact_model and plab::add_pass do), or load the library that declares it first"};
    std::vector<std::string> bad;
    uint32_t shared = 0;
    for (uint32_t i = 0; p && i < n; ++i) {
        const plab_property_desc* m = material_property(it->second, p[i].key);
        if (!m) continue;
        ++shared;
        if (const std::string why = declaration_difference(p[i], *m); !why.empty())
            bad.push_back(std::string("property ") + p[i].key + " is a property of its material '" + material +
                          "', declared differently (" + why + " in the material); take the material's description");
    }
    if (shared == 0) {
        std::vector<std::string> keys;
        for (uint32_t i = 0; i < it->second->property_count; ++i) keys.push_back(it->second->properties[i].key);
        bad.push_back(std::string("names the material '") + material + "' but declares none of its properties (" +
                      join(keys) + ")");
    }
    return bad;
}

const plab_material_desc* PluginHost::material(const std::string& name) const {
    auto it = registry_->materials.find(name);
    return it == registry_->materials.end() ? nullptr : it->second;
}

const plab_pass_state_hooks* PluginHost::pass_state(const std::string& name) const {
    auto it = registry_->pass_state.find(name);
    return it == registry_->pass_state.end() ? nullptr : it->second;
}

const plab_contact_model_desc* PluginHost::model(const std::string& name) const {
    auto it = registry_->models.find(name);
    return it == registry_->models.end() ? nullptr : it->second;
}

const plab_pass_desc* PluginHost::pass(const std::string& name) const {
    auto it = registry_->passes.find(name);
    return it == registry_->passes.end() ? nullptr : it->second;
}

std::vector<std::string> PluginHost::model_names() const {
    std::vector<std::string> v;
    for (const auto& [n, d] : registry_->models) v.push_back(n);
    return v;
}

std::vector<std::string> PluginHost::pass_names() const {
    std::vector<std::string> v;
    for (const auto& [n, d] : registry_->passes) v.push_back(n);
    return v;
}

} // namespace plab
