// Contact laws in Python (python_law.hpp). The C ABI's activity_range and
// create take no context, so each law gets one of kSlots slots, whose
// functions (templates on the slot) find it; compute() gets the law as its
// instance. A batch reaches Python as a dict of NumPy arrays that are
// copies (a student's function may keep them: they must not point into the
// host's buffers after the call); the outputs are copied back.
#include "python_law.hpp"

#include <plab_host/errors.hpp>

#include <pybind11/numpy.h>

#include <array>
#include <cstring>
#include <deque>
#include <iostream>
#include <memory>
#include <utility>

namespace py = pybind11;

namespace plab::python {

namespace {

struct PythonLaw {
    std::deque<std::string> text;  // the descriptions' strings, at fixed addresses
    std::vector<plab_property_desc> properties;
    std::vector<plab_history_desc> history;
    int range_property = -1;  // the property that is the activity range (a gap), or -1: 0
    plab_contact_model_desc desc{};
    py::object law;
    const char* keep(const std::string& s) { return text.emplace_back(s).c_str(); }
};

constexpr std::size_t kSlots = 16;
// Never freed: the hosts' copies of the descriptions point to their strings.
std::array<PythonLaw*, kSlots> g_laws{};
std::size_t g_count = 0;

template <std::size_t I> double range_of(const double* props) {
    const PythonLaw& law = *g_laws[I];
    return law.range_property >= 0 ? props[law.range_property] : 0.0;
}
template <std::size_t I> void* create_of(const double*) { return g_laws[I]; }
template <std::size_t... I> constexpr auto range_table(std::index_sequence<I...>) {
    return std::array<double (*)(const double*), kSlots>{&range_of<I>...};
}
template <std::size_t... I> constexpr auto create_table(std::index_sequence<I...>) {
    return std::array<void* (*)(const double*), kSlots>{&create_of<I>...};
}

py::array_t<double> copy_of(const double* p, std::size_t rows, std::size_t cols) {
    py::array_t<double> a = cols == 1 ? py::array_t<double>(rows) : py::array_t<double>({rows, cols});
    if (p && rows * cols) std::memcpy(a.mutable_data(), p, rows * cols * sizeof(double));
    else std::fill(a.mutable_data(), a.mutable_data() + rows * cols, 0.0);
    return a;
}
void copy_back(const py::dict& d, const char* key, double* out, std::size_t n) {
    if (!out || n == 0) return;
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(d[key]);
    if (!a || std::size_t(a.size()) != n)
        throw std::runtime_error(std::string("batch[\"") + key + "\"] must keep its shape");
    std::memcpy(out, a.data(), n * sizeof(double));
}

// One batch through the Python function; 0 on success, as abi.h asks.
int compute(void* instance, const double* props, const plab_contact_batch* b) {
    const PythonLaw& law = *static_cast<const PythonLaw*>(instance);
    py::gil_scoped_acquire gil;
    try {
        const std::size_t n = b->count, hs = b->history_stride;
        py::dict d, p;
        for (std::size_t i = 0; i < law.properties.size(); ++i) p[law.properties[i].key] = props[i];
        d["props"] = p;
        d["dt"] = b->dt;
        d["dim"] = b->dim;
        d["with_wall"] = bool(b->end2_is_wall);
        py::array_t<bool> active(n);
        for (std::size_t k = 0; k < n; ++k) active.mutable_data()[k] = b->active[k] != 0;
        d["active"] = active;
        d["gap"] = copy_of(b->gap, n, 1);
        d["normal"] = copy_of(b->normal, n, 3);
        d["rel_velocity"] = copy_of(b->rel_velocity, n, 3);
        d["eff_mass"] = copy_of(b->eff_mass, n, 1);
        d["history"] = copy_of(b->history, n, hs);
        for (const char* out : {"force"}) d[out] = copy_of(nullptr, n, 3);
        for (const char* out : {"stiffness", "strain_energy", "slip_energy", "dashpot_energy"}) d[out] = copy_of(nullptr, n, 1);
        law.law(d);
        copy_back(d, "history", b->history, n * hs);
        copy_back(d, "force", b->force, 3 * n);
        copy_back(d, "stiffness", b->stiffness_translational, n);
        copy_back(d, "strain_energy", b->strain_energy, n);
        copy_back(d, "slip_energy", b->slip_energy, n);
        copy_back(d, "dashpot_energy", b->dashpot_energy, n);
        return 0;
    } catch (const std::exception& e) {  // the host stops the run naming the model and the step
        std::cerr << "contact law " << law.desc.name << " (Python): " << e.what() << "\n";
        return 1;
    }
}

} // namespace

void register_law(const std::string& name, const std::string& doc, const std::string& timestep_rule, py::object fn,
                  const std::vector<PropertySpec>& properties, const std::vector<HistorySpec>& history,
                  const std::string& range_key) {
    if (g_count == kSlots) throw InputError("register_model", "at most " + std::to_string(kSlots) + " Python laws");
    for (std::size_t i = 0; i < g_count; ++i)
        if (name == g_laws[i]->desc.name) throw InputError("register_model", "a law named '" + name + "' is registered already");
    auto law = std::make_unique<PythonLaw>();
    for (const auto& [key, pname, unit, def, lo, hi, pdoc] : properties) {
        plab_property_desc q{};
        q.size = sizeof q;
        q.kind = PLAB_KIND_NUMBER;
        q.key = law->keep(key);
        q.name = law->keep(pname);
        q.unit = law->keep(unit);
        q.default_value = def;
        q.min_value = lo;
        q.max_value = hi;
        q.mixing = PLAB_MIX_NONE;
        q.doc = law->keep(pdoc);
        if (key == range_key) law->range_property = int(law->properties.size());
        law->properties.push_back(q);
    }
    if (!range_key.empty() && law->range_property < 0)
        throw InputError("register_model", "range: no property named '" + range_key + "'");
    for (const auto& [hname, hdoc, def, negate, tangential] : history)
        law->history.push_back({sizeof(plab_history_desc), law->keep(hname), def,
                                negate ? PLAB_SWAP_NEGATE : PLAB_SWAP_KEEP, law->keep(hdoc),
                                tangential ? PLAB_HISTORY_TANGENTIAL : 0u});
    plab_contact_model_desc& d = law->desc;
    d.size = sizeof d;
    d.name = law->keep(name);
    d.doc = law->keep(doc);
    d.property_count = uint32_t(law->properties.size());
    d.properties = law->properties.empty() ? nullptr : law->properties.data();
    d.history_count = uint32_t(law->history.size());
    d.history = law->history.empty() ? nullptr : law->history.data();
    d.range_kind = PLAB_RANGE_GAP;
    d.timestep_rule = law->keep(timestep_rule);
    static constexpr auto ranges = range_table(std::make_index_sequence<kSlots>{});
    static constexpr auto creates = create_table(std::make_index_sequence<kSlots>{});
    d.activity_range = ranges[g_count];
    d.create = creates[g_count];
    d.compute = &compute;
    d.persist_slot = -1;
    d.io = PLAB_IO_DECLARED | PLAB_IO_EFF_MASS;
    std::string problems;
    for (const std::string& p : check_model_desc(d)) problems += (problems.empty() ? "" : "; ") + p;
    if (!problems.empty()) throw InputError("register_model", "model '" + name + "': " + problems);
    law->law = std::move(fn);
    g_laws[g_count++] = law.release();
}

void register_laws(PluginHost& host) {
    for (std::size_t i = 0; i < g_count; ++i)
        if (host.register_model(&g_laws[i]->desc) != 0)
            throw InputError("register_model", std::string("the host refused the Python law '") + g_laws[i]->desc.name +
                                                   "' (a model of that name is registered already?)");
}

std::vector<std::string> law_names() {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < g_count; ++i) names.push_back(g_laws[i]->desc.name);
    return names;
}

} // namespace plab::python
