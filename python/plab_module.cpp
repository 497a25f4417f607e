// The Python module `plab._plab`: a scene loaded by the scene loader
// (scripting/, as `plab run` loads it), cycled from Python, its state shown
// as NumPy arrays over the kernel's own columns (no copies).
//
// Views and freed memory: an array over a column holds a Lease (its NumPy
// base), and the Session counts the live leases per column. A column's
// storage moves only when balls are added or removed (a scene's inlets and
// outlets: Bodies::add grows the columns, Bodies::remove compacts them) or
// trimmed (World::prepare, done once at load, when the columns are already
// trimmed afterwards). So before a call that runs the kernel on a scene with
// inlets or outlets, every column with a live lease is *pinned*: its buffer
// is moved to the Session and the kernel runs on a copy; after the call the
// copy's values go back into the pinned buffer and the kernel gets it back,
// unless the number of rows changed: then the pinned buffer is kept (a
// graveyard, emptied when the last lease dies) and the generation goes up.
// A lease never points to freed memory. The generation also goes up when
// any column's address or length changed for any other reason; plab.View
// (python/plab/__init__.py) checks it at every use and raises StaleViewError.
//
// Writes: velocities, spins and fixity are writable. While a lease of one
// of them lives, the Session keeps a copy of the column after each call and
// compares it before the next; a change marks the world dirty
// (World::mark_dirty), as the scene's `set` command does, so that the lists,
// the caches of fixed balls and the last good state follow it.
#include "python_law.hpp"
#include "simulation.hpp"

#include <plab_host/checkpoint.hpp>
#include <plab_host/errors.hpp>
#include <plab_host/world.hpp>

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <tuple>

namespace py = pybind11;
namespace fs = std::filesystem;
using namespace plab;

namespace {

// Plug-ins: the module's own install location first (P/lib/python3/dist-packages/plab
// -> P/lib/plab/plugins), then as the plab binary finds them (PLAB_PLUGIN_PATH wins).
std::string g_installed_plugins;

std::shared_ptr<PluginHost> make_host() {
    auto host = std::make_shared<PluginHost>();
    python::register_laws(*host);  // first: a library cannot take their names
    if (!g_installed_plugins.empty() && fs::is_directory(g_installed_plugins)) {
        host->add_search_dir(g_installed_plugins, true);
        if (const char* env = std::getenv("PLAB_PLUGIN_PATH")) {  // the user's folders stay first
            std::vector<std::string> dirs;
            std::stringstream ss(env);
            for (std::string d; std::getline(ss, d, ':');)
                if (!d.empty()) dirs.push_back(d);
            for (const auto& d : dirs) host->add_search_dir(d, true);
        }
    }
    return host;
}

// One column of the state a view can show: its place in the world and its shape.
enum class Col { position, velocity, spin, force, moment, radius, mass, group, fixity, id, field };

struct ColumnKey {
    Col col;
    int field = -1;
    bool operator<(const ColumnKey& o) const { return std::tie(col, field) < std::tie(o.col, o.field); }
};

bool writable(Col c) { return c == Col::velocity || c == Col::spin || c == Col::fixity; }

struct Session;

// A pinned buffer: the views' storage, moved out while the kernel runs on a copy.
struct Pin {
    std::shared_ptr<void> kept;          // the moved-out vector
    std::function<bool()> give_back;     // true: rows unchanged, the buffer is the kernel's again
};

struct Session {
    std::unique_ptr<Simulation> sim;
    std::uint64_t generation = 0;
    std::map<ColumnKey, int> leases;
    std::vector<std::shared_ptr<void>> graveyard;
    std::vector<std::pair<const void*, std::size_t>> layout;  // of every column, at the last check
    std::map<ColumnKey, std::vector<char>> seen;              // writable columns as the last call left them

    World& world() { return sim->world(); }
    bool has_flows() const { return sim->scene().contains("inlets") || sim->scene().contains("outlets"); }

    template <class F> void with_column(const ColumnKey& k, F&& f) {
        Bodies& b = world().bodies;
        switch (k.col) {
        case Col::position: return f(b.position);
        case Col::velocity: return f(b.velocity);
        case Col::spin: return f(b.angular_velocity);
        case Col::force: return f(b.force);
        case Col::moment: return f(b.moment);
        case Col::radius: return f(b.radius);
        case Col::mass: return f(b.mass);
        case Col::group: return f(b.group);
        case Col::fixity: return f(b.fixity);
        case Col::id: return f(b.id);
        case Col::field: return f(world().fields.column(k.field));
        }
    }
    std::vector<ColumnKey> all_columns() {
        std::vector<ColumnKey> keys;
        for (Col c : {Col::position, Col::velocity, Col::spin, Col::force, Col::moment, Col::radius, Col::mass,
                      Col::group, Col::fixity, Col::id})
            keys.push_back({c});
        for (std::size_t f = 0; f < world().fields.size(); ++f) keys.push_back({Col::field, int(f)});
        return keys;
    }
    std::vector<std::pair<const void*, std::size_t>> current_layout() {
        std::vector<std::pair<const void*, std::size_t>> l;
        for (const ColumnKey& k : all_columns())
            with_column(k, [&](auto& v) { l.emplace_back(static_cast<const void*>(v.data()), v.size()); });
        return l;
    }
    template <class T> static std::vector<char> bytes_of(const std::vector<T>& v) {
        std::vector<char> out(v.size() * sizeof(T));
        if (!out.empty()) std::memcpy(out.data(), v.data(), out.size());
        return out;
    }

    // Before a call into the kernel: writes through views re-establish the
    // kernel's invariants; on a scene whose rows can change, leased columns are pinned.
    std::vector<Pin> before_call() {
        bool changed = false;
        for (auto& [k, bytes] : seen)
            with_column(k, [&](auto& v) { changed |= bytes != bytes_of(v); });
        if (changed) world().mark_dirty();
        std::vector<Pin> pins;
        if (!has_flows()) return pins;
        for (const auto& [k, n] : leases) {
            if (n == 0) continue;
            with_column(k, [&](auto& v) {
                using V = std::decay_t<decltype(v)>;
                auto kept = std::make_shared<V>(std::move(v));
                v = *kept;  // the kernel runs on a copy
                V* col = &v;
                pins.push_back({kept, [col, kept] {
                                    if (col->size() != kept->size()) return false;
                                    std::copy(col->begin(), col->end(), kept->begin());
                                    col->swap(*kept);
                                    return true;
                                }});
            });
        }
        return pins;
    }

    void after_call(std::vector<Pin>& pins) {
        bool moved = false;
        for (Pin& p : pins)
            if (!p.give_back()) {
                graveyard.push_back(p.kept);
                moved = true;
            }
        const auto now = current_layout();
        if (moved || now != layout) ++generation;
        layout = now;
        seen.clear();
        for (const auto& [k, n] : leases)
            if (n > 0 && writable(k.col)) with_column(k, [&](auto& v) { seen[k] = bytes_of(v); });
    }

    // Runs `f` on the kernel with the guarantees above, the GIL released.
    template <class F> void call(F&& f) {
        std::vector<Pin> pins = before_call();
        struct After {
            Session& s;
            std::vector<Pin>& p;
            ~After() { s.after_call(p); }
        } after{*this, pins};
        py::gil_scoped_release release;
        f();
    }
};

// The NumPy base of an array over a column: keeps the session alive and counts.
struct Lease {
    std::shared_ptr<Session> session;
    ColumnKey key;
    Lease(std::shared_ptr<Session> s, ColumnKey k) : session(std::move(s)), key(k) { ++session->leases[key]; }
    ~Lease() {
        if (--session->leases[key] > 0) return;
        for (const auto& [k, n] : session->leases)
            if (n > 0) return;
        session->graveyard.clear();  // no view left that could point into them
    }
    Lease(const Lease&) = delete;
    Lease& operator=(const Lease&) = delete;
};

// The class Python sees: a session with its operations.
class PySim {
public:
    // `fresh`: a scene just loaded, not a restarted run (whose world is
    // ready as the checkpoint left it, columns read at their length).
    PySim(std::unique_ptr<Simulation> sim, bool fresh) : s_(std::make_shared<Session>()) {
        s_->sim = std::move(sim);
        s_->sim->set_quiet(true);
        // forces at the loaded state and the columns trimmed to their rows,
        // as the first step would (and `plab run` does before it): from here
        // on their storage moves only with inlets and outlets
        if (fresh) {
            py::gil_scoped_release release;  // (a Python law takes the GIL from the kernel's threads)
            s_->world().prepare();
        }
        s_->layout = s_->current_layout();
    }

    void cycle(long n) { s_->call([&] { s_->sim->cycle(n); }); }
    // Up to n cycles, stopping after the first in which a bond breaks (an
    // event a callback waits for): the cycles run. One cycle at a time, so
    // each writes its contact forces (a few % of a step's cost).
    long cycle_to_bond_break(long n) {
        long done = 0;
        s_->call([&] {
            const std::size_t before = s_->world().bond_breaks.size();
            while (done < n && s_->world().bond_breaks.size() == before) {
                s_->sim->cycle(1);
                ++done;
            }
        });
        return done;
    }
    // The bonds broken so far, from the k-th on: (step, time, id1, id2, point, mode, model).
    py::list bond_breaks(std::size_t from) const {
        py::list out;
        const auto& breaks = s_->world().bond_breaks;
        for (std::size_t k = from; k < breaks.size(); ++k) {
            const BondBreak& b = breaks[k];
            py::dict d;
            d["step"] = b.step;
            d["time"] = b.time;
            d["ids"] = py::make_tuple(b.id1, b.id2);
            d["point"] = py::make_tuple(b.point.x(), b.point.y(), b.point.z());
            d["mode"] = b.mode == PLAB_BREAK_SHEAR ? "shear" : "tension";
            d["model"] = b.model;
            out.append(d);
        }
        return out;
    }
    std::size_t bond_break_count() const { return s_->world().bond_breaks.size(); }
    void run() { s_->call([&] { s_->sim->run(); }); }
    // Cycles until `end` (absolute simulated time), as the scene's solve time does.
    void solve_until(double end, long max_cycles) {
        s_->call([&] {
            World& w = s_->world();
            long k = 0;
            while (w.time < end - 1e-12 * std::fabs(end)) {
                if (k++ >= max_cycles)
                    throw RunError("solve: reached t = " + short_number(w.time) + " s of " + short_number(end) +
                                   " s after max_cycles = " + std::to_string(max_cycles) +
                                   " cycles; raise max_cycles or check the timestep");
                s_->sim->cycle(1);
            }
        });
    }
    std::string summary() const { return s_->sim->summary().dump(); }
    std::string scene() const { return s_->sim->scene().dump(); }
    void checkpoint(const std::string& path) { s_->sim->save_checkpoint(path); }
    void set_output_dir(const std::string& dir) { s_->sim->set_output_dir(dir); }
    std::uint64_t state_hash() const { return plab::state_hash(s_->world()); }
    std::uint64_t generation() const { return s_->generation; }
    int dim() const { return s_->world().dim; }
    std::size_t size() const { return s_->world().bodies.size(); }
    double time() const { return s_->world().time; }
    std::uint64_t step_count() const { return s_->world().step_count; }
    double last_dt() const { return s_->world().last_dt; }
    std::vector<std::string> field_names() const { return s_->world().fields.names(); }
    std::vector<std::string> group_names() const { return s_->world().group_names(); }

    std::vector<std::string> history_columns() const {
        std::vector<std::string> names;
        for (const auto& c : s_->sim->history_columns()) names.push_back(c.name);
        return names;
    }
    // rows × columns, a copy (the rows are a vector of vectors)
    py::array_t<double> history_rows() const {
        const auto& rows = s_->sim->history_rows();
        const std::size_t nc = s_->sim->history_columns().size();
        py::array_t<double> a({rows.size(), nc});
        auto m = a.mutable_unchecked<2>();
        for (std::size_t r = 0; r < rows.size(); ++r)
            for (std::size_t c = 0; c < nc; ++c) m(r, c) = rows[r][c];
        return a;
    }

    // A zero-copy array over a column; `name` as in the views' names.
    py::array column(const std::string& name) {
        const ColumnKey key = key_of(name);
        const int dim = s_->world().dim;
        py::array a;
        s_->with_column(key, [&](auto& v) {
            using T = typename std::decay_t<decltype(v)>::value_type;
            const auto base = py::cast(new Lease(s_, key), py::return_value_policy::take_ownership);
            const auto n = py::ssize_t(v.size());
            if constexpr (std::is_same_v<T, Vec>) {
                double* p = v.empty() ? nullptr : v[0].data();
                const py::ssize_t row = sizeof(Vec);
                if (key.col == Col::spin || key.col == Col::moment) {
                    if (dim == 2) a = py::array(py::dtype::of<double>(), {n}, {row}, p ? p + 2 : p, base);  // about z
                    else a = py::array(py::dtype::of<double>(), {n, py::ssize_t(3)}, {row, py::ssize_t(8)}, p, base);
                } else {
                    a = py::array(py::dtype::of<double>(), {n, py::ssize_t(dim)}, {row, py::ssize_t(8)}, p, base);
                }
            } else {
                a = py::array(py::dtype::of<T>(), {n}, {py::ssize_t(sizeof(T))}, v.data(), base);
            }
        });
        if (!writable(key.col)) a.attr("flags").attr("writeable") = false;
        else s_->with_column(key, [&](auto& v) { s_->seen.emplace(key, Session::bytes_of(v)); });
        return a;
    }

    // The active contacts of every model instance, copied into columns (the
    // tables give rows through accessors, not as contiguous columns).
    py::dict contacts() const {
        const World& w = s_->world();
        std::vector<std::int64_t> model, end1, end2, id1, id2;
        std::vector<std::uint8_t> wall, bonded;
        std::vector<double> normal, force, overlap;
        for (std::size_t m = 0; m < w.model_count(); ++m) {
            const ModelView mv = w.model(m);
            for (const ContactTable& t : {mv.balls(), mv.walls()})
                for (std::size_t k = 0; k < t.size(); ++k) {
                    if (!t.active(k)) continue;
                    model.push_back(std::int64_t(m));
                    end1.push_back(std::int64_t(t.end1(k)));
                    end2.push_back(std::int64_t(t.end2(k)));
                    const ContactKey key = t.key(k);
                    id1.push_back(std::int64_t(key.first));
                    id2.push_back(std::int64_t(key.second));
                    wall.push_back(t.with_wall());
                    bonded.push_back(t.bonded(k));
                    const Vec nrm = t.normal(k), f = t.force(k);
                    normal.insert(normal.end(), nrm.data(), nrm.data() + 3);
                    force.insert(force.end(), f.data(), f.data() + 3);
                    overlap.push_back(-t.gap(k));
                }
        }
        const auto vec3 = [](const std::vector<double>& v) {
            py::array_t<double> a({v.size() / 3, std::size_t(3)});
            if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(double));
            return a;
        };
        py::dict d;
        d["model"] = py::array_t<std::int64_t>(model.size(), model.data());
        d["end1"] = py::array_t<std::int64_t>(end1.size(), end1.data());
        d["end2"] = py::array_t<std::int64_t>(end2.size(), end2.data());
        d["id1"] = py::array_t<std::int64_t>(id1.size(), id1.data());
        d["id2"] = py::array_t<std::int64_t>(id2.size(), id2.data());
        d["with_wall"] = py::array_t<std::uint8_t>(wall.size(), wall.data()).attr("astype")("bool");
        d["bonded"] = py::array_t<std::uint8_t>(bonded.size(), bonded.data()).attr("astype")("bool");
        d["normal"] = vec3(normal);
        d["force"] = vec3(force);
        d["overlap"] = py::array_t<double>(overlap.size(), overlap.data());
        return d;
    }
    std::vector<std::string> model_names() const {
        std::vector<std::string> names;
        for (std::size_t m = 0; m < s_->world().model_count(); ++m) names.push_back(s_->world().model(m).model());
        return names;
    }
    // Live leases per column name: what the pins cover (tests, docs).
    std::size_t live_views() const {
        std::size_t n = 0;
        for (const auto& [k, c] : s_->leases) n += std::size_t(c);
        return n;
    }

private:
    std::shared_ptr<Session> s_;

    ColumnKey key_of(const std::string& name) const {
        static const std::map<std::string, Col> cols = {
            {"positions", Col::position}, {"velocities", Col::velocity}, {"spins", Col::spin},
            {"forces", Col::force},       {"moments", Col::moment},      {"radii", Col::radius},
            {"masses", Col::mass},        {"groups", Col::group},        {"fixity", Col::fixity},
            {"ids", Col::id}};
        if (auto it = cols.find(name); it != cols.end()) return {it->second};
        const int f = s_->world().fields.index(name);
        if (f >= 0) return {Col::field, f};
        std::string known;
        for (const auto& [k, c] : cols) known += (known.empty() ? "" : ", ") + k;
        for (const auto& fname : s_->world().fields.names()) known += ", " + fname;
        throw py::key_error("no body column named '" + name + "'; columns: " + known);
    }
};

std::unique_ptr<PySim> load_scene(json scene, const std::vector<std::string>& sets, const std::string& scene_dir,
                                  const std::string& out_dir) {
    for (const auto& s : sets) apply_override(scene, s);
    auto host = make_host();
    std::unique_ptr<Simulation> sim;
    {
        py::gil_scoped_release release;
        sim = std::make_unique<Simulation>(scene, scene_dir, host);
    }
    if (!out_dir.empty()) sim->set_output_dir(out_dir);
    return std::make_unique<PySim>(std::move(sim), true);
}

} // namespace

PYBIND11_MODULE(_plab, m) {
    m.doc() = "ParticleLab's kernel and scene loader (use the package `plab`)";
    static py::exception<std::runtime_error> error(m, "Error", PyExc_RuntimeError);
    static py::exception<InputError> input_error(m, "InputError", error.ptr());
    static py::exception<PluginError> plugin_error(m, "PluginError", input_error.ptr());
    static py::exception<RunError> run_error(m, "RunError", error.ptr());
    static py::exception<CheckpointError> checkpoint_error(m, "CheckpointError", error.ptr());
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const InputError& e) {
            py::object exc = py::reinterpret_borrow<py::object>(input_error.ptr())(e.what());
            exc.attr("path") = e.path();
            PyErr_SetObject(input_error.ptr(), exc.ptr());
        } catch (const PluginError& e) {
            plugin_error(e.what());
        } catch (const RunError& e) {
            py::object exc = py::reinterpret_borrow<py::object>(run_error.ptr())(e.what());
            exc.attr("quantity") = e.quantity();
            PyErr_SetObject(run_error.ptr(), exc.ptr());
        } catch (const CheckpointError& e) {
            checkpoint_error(e.what());
        }
    });

    py::class_<Lease>(m, "_Lease");
    py::class_<PySim>(m, "Sim")
        .def("cycle", &PySim::cycle, py::arg("n"))
        .def("cycle_to_bond_break", &PySim::cycle_to_bond_break, py::arg("n"))
        .def("bond_breaks", &PySim::bond_breaks, py::arg("from") = 0)
        .def_property_readonly("bond_break_count", &PySim::bond_break_count)
        .def("run", &PySim::run)
        .def("solve_until", &PySim::solve_until, py::arg("end"), py::arg("max_cycles"))
        .def("summary_json", &PySim::summary)
        .def("scene_json", &PySim::scene)
        .def("checkpoint", &PySim::checkpoint, py::arg("path"))
        .def("set_output_dir", &PySim::set_output_dir)
        .def("state_hash", &PySim::state_hash)
        .def_property_readonly("generation", &PySim::generation)
        .def_property_readonly("dim", &PySim::dim)
        .def_property_readonly("size", &PySim::size)
        .def_property_readonly("time", &PySim::time)
        .def_property_readonly("step_count", &PySim::step_count)
        .def_property_readonly("last_dt", &PySim::last_dt)
        .def("field_names", &PySim::field_names)
        .def("group_names", &PySim::group_names)
        .def("model_names", &PySim::model_names)
        .def("history_columns", &PySim::history_columns)
        .def("history_rows", &PySim::history_rows)
        .def("column", &PySim::column, py::arg("name"))
        .def("contacts", &PySim::contacts)
        .def("live_views", &PySim::live_views);

    m.def("register_law", &python::register_law, py::arg("name"), py::arg("doc"), py::arg("timestep_rule"),
          py::arg("law"), py::arg("properties"), py::arg("history"), py::arg("range_key"));
    m.def("law_names", &python::law_names);
    m.def("set_installed_plugin_dir", [](const std::string& dir) { g_installed_plugins = dir; });
    m.def(
        "load_file",
        [](const std::string& path, const std::vector<std::string>& sets, const std::string& out_dir) {
            json scene = read_scene_file(path);
            return load_scene(std::move(scene), sets, fs::absolute(path).parent_path().string(), out_dir);
        },
        py::arg("path"), py::arg("sets"), py::arg("out_dir"));
    m.def(
        "load_text",
        [](const std::string& text, const std::vector<std::string>& sets, const std::string& scene_dir,
           const std::string& out_dir) {
            return load_scene(parse_scene_text(text, "scene"), sets, scene_dir, out_dir);
        },
        py::arg("text"), py::arg("sets"), py::arg("scene_dir"), py::arg("out_dir"));
    m.def(
        "restart",
        [](const std::string& path, const std::vector<std::string>& sets) {
            auto host = make_host();
            std::unique_ptr<Simulation> sim;
            {
                py::gil_scoped_release release;
                sim = Simulation::restart(path, sets, host);
            }
            return std::make_unique<PySim>(std::move(sim), false);
        },
        py::arg("path"), py::arg("sets"));
}
