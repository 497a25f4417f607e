// The `plab` command line: run scenes, list plug-ins, run validation cases.
#include "new_model.hpp"
#include "plot_command.hpp"
#include "quantities.hpp"
#include "simulation.hpp"
#include "sweep.hpp"
#include "validation.hpp"

#include <plab_host/checkpoint.hpp>
#include <plab_host/plugins.hpp>

#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <thread>

#ifdef _OPENMP
#include <omp.h>
#endif
#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace fs = std::filesystem;
using namespace plab;

namespace {

const char* usage =
    "usage:\n"
    "  plab run SCENE.json [--set PATH=VALUE]... [--out DIR] [--quiet] [--checkpoint-every SECONDS]\n"
    "           [--png INTERVAL[:FIELD]] [--vtk INTERVAL] [--watch]\n"
    "  plab check SCENE.json [--set PATH=VALUE]...\n"
    "  plab restart CHECKPOINT.plab [--set PATH=VALUE]... [--out DIR] [--quiet] [--checkpoint-every SECONDS] [--watch]\n"
    "  plab sweep SCENE.json... [--vary PATH=v1,v2]... [--set PATH=VALUE]... [--jobs N] [--out DIR]\n"
    "             [--metric NAME] [--cost cpu_s|wall_s|steps|particle_steps|peak_rss_mb]\n"
    "  plab plugins [--describe MODEL]\n"
    "  plab validate CASE... | --list | --all [--quick] [--report DIR]\n"
    "  plab new-model NAME [DIR]   (an out-of-tree contact-model project)\n"
    "  plab plot HISTORY.csv... [--label A,B] [--x COL] [--y A,B] [--ref REF.csv --ref-y COL [--band F]]\n"
    "            [--title T] [--xlabel T] [--ylabel T] [--log x|y|xy] [--out FILE.png]\n"
    "  plab quantities\n";

// What the compiler was told: the vector extensions the kernel may use and
// whether OpenMP is on (speed tables name them, bench/peers/README.md).
std::string build_flags() {
    std::string f = "built with";
#if defined(__AVX512F__)
    f += " AVX-512";
#elif defined(__AVX2__)
    f += " AVX2";
#elif defined(__SSE4_2__)
    f += " SSE4.2";
#else
    f += " the baseline instruction set";
#endif
#ifdef _OPENMP
    f += ", OpenMP " + std::to_string(omp_get_max_threads()) + " threads";
#else
    f += ", no OpenMP";
#endif
    return f;
}

double checkpoint_interval(const std::string& text) {
    char* end = nullptr;
    const double t = std::strtod(text.c_str(), &end);
    if (text.empty() || *end || !(t > 0) || !std::isfinite(t))
        throw InputError("--checkpoint-every", "expected a positive simulated time in s, got '" + text + "'; valid range (0, inf)");
    return t;
}

// OpenMP's idle threads spin a while before they sleep. On a machine whose
// cores other work keeps busy, a spinning thread waits a whole time slice
// for its descheduled partner at every parallel region: a 2-thread run was
// 10-15x slower than 1 thread under load 5 on 2 cores. Say so, with the fix.
void warn_if_threads_will_spin() {
#ifdef _OPENMP
    const int threads = omp_get_max_threads();
    const unsigned cores = std::thread::hardware_concurrency();
    double load[1] = {0};
    if (threads < 2 || std::getenv("OMP_WAIT_POLICY") || getloadavg(load, 1) != 1 || cores == 0) return;
    if (load[0] + threads > cores + 0.5)
        spdlog::warn("the machine is busy (load {:.1f} on {} cores) and this run uses {} OpenMP threads, whose idle "
                     "threads spin: it may run many times slower than with one. Set OMP_WAIT_POLICY=PASSIVE or "
                     "OMP_NUM_THREADS=1 (results are the same bits with any thread count)",
                     load[0], cores, threads);
#endif
}

// Runs to the end, or until SIGINT/SIGTERM/SIGHUP: then the checkpoint is written
// and the exit code is 128 + the signal, as a shell reports a killed job.
int run_and_report(Simulation& sim, bool quiet, const std::string& out) {
    install_stop_handlers();
    if (!quiet) warn_if_threads_will_spin();
    try {
        sim.run();
    } catch (const RunError& e) {  // on stderr, as every error, where a script looks for it
        std::cerr << "error: run stopped: " << e.what() << "\n";
        return 3;
    }
    if (sim.interrupted()) {
        const World& w = sim.world();
        std::cerr << "plab: stopped by signal " << stop_signal() << " after step " << w.step_count << " (t = " << w.time
                  << " s); checkpoint and outputs written" << (out.empty() ? "" : " to " + out)
                  << ".\ncontinue with:\n  plab restart " << sim.checkpoint_path() << "\n";
        return 128 + stop_signal();
    }
    const json s = sim.summary();
    if (!quiet)
        spdlog::info("done: {} steps, {:.6g} s simulated, {:.3g} s wall, {:.3g} particle-steps/s, {} contacts{}",
                     s["steps"].get<std::uint64_t>(), s["simulated_time"].get<double>(), s["wall_seconds"].get<double>(),
                     s["particle_steps_per_second"].get<double>(), s["contacts"].get<std::size_t>(),
                     out.empty() ? "" : "; outputs in " + out);
    return 0;
}

// The options `plab run` and `plab restart` share; `what` names the one
// positional argument (a scene or a checkpoint).
struct RunOptions {
    std::string path, out;
    std::vector<std::string> sets;
    bool quiet = false, watch = false;
    double every = 0;
    std::string png, vtk;  // --png INTERVAL[:FIELD], --vtk INTERVAL (run only)
};

// --png and --vtk as the scene keys they stand for, after the user's --set.
void apply_output_flags(json& scene, const RunOptions& o) {
    const auto interval = [](const std::string& flag, const std::string& text) {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end || !(v > 0) || !std::isfinite(v))
            throw InputError(flag, "expected a positive simulated time in s, got '" + text + "'; valid range (0, inf)");
        return v;
    };
    if (o.vtk.empty() && o.png.empty()) return;
    json& out = scene["output"];
    if (!out.is_object()) out = json::object();
    if (!o.vtk.empty()) {
        const double v = interval("--vtk", o.vtk);
        if (out.contains("vtk") || !out.contains("vtk_interval")) out["vtk"]["interval"] = v;
        else out["vtk_interval"] = v;
    }
    if (!o.png.empty()) {
        const auto colon = o.png.find(':');
        out["png"]["interval"] = interval("--png", o.png.substr(0, colon));
        if (colon != std::string::npos) out["png"]["field"] = o.png.substr(colon + 1);
    }
}

RunOptions parse_run_options(const std::vector<std::string>& args, const std::string& what) {
    RunOptions o;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--set" && i + 1 < args.size()) o.sets.push_back(args[++i]);
        else if (a == "--out" && i + 1 < args.size()) o.out = args[++i];
        else if (a == "--checkpoint-every" && i + 1 < args.size()) o.every = checkpoint_interval(args[++i]);
        else if (a == "--quiet") o.quiet = true;
        else if (a == "--watch") o.watch = true;
        else if (a == "--png" && what == "scene" && i + 1 < args.size()) o.png = args[++i];
        else if (a == "--vtk" && what == "scene" && i + 1 < args.size()) o.vtk = args[++i];
        else if (a == "--set" || a == "--out" || a == "--checkpoint-every" || a == "--png" || a == "--vtk")
            throw InputError("command line", a + " needs a value after it\n" + usage);
        else if (a.rfind("--", 0) == 0) throw InputError("command line", "unknown option " + a + "\n" + usage);
        else if (o.path.empty()) o.path = a;
        else throw InputError("command line", "more than one " + what + " given (" + o.path + ", " + a + ")");
    }
    if (o.path.empty()) throw InputError("command line", "no " + what + " given\n" + usage);
    return o;
}

// Loads the scene as `run` would and says what it will do, without a step.
int cmd_check(const std::vector<std::string>& args) {
    const RunOptions o = parse_run_options(args, "scene");
    json scene = read_scene_file(o.path);
    for (const auto& s : o.sets) apply_override(scene, s);
    Simulation sim(scene, fs::absolute(o.path).parent_path().string());
    if (!o.out.empty()) sim.set_output_dir(o.out);
    else if (!(scene.contains("output") && scene["output"].contains("dir")))
        sim.set_output_dir("plab_out/" + fs::path(o.path).stem().string());
    std::cout << "scene: " << o.path << " (loads: every value is in range)\n";
    sim.check_report(std::cout);
    return 0;
}

const char* help =
    "plab: particle simulations (DEM, SPH and their coupling) from JSON scenes, physics from plug-ins.\n\n"
    "  run        run a scene to its end: outputs, history.csv, summary.json in plab_out/NAME (or --out)\n"
    "  check      load a scene and say what it would do (bodies, models, timestep, steps, outputs), without running\n"
    "  restart    continue a run from its checkpoint.plab (written on SIGINT/SIGTERM/SIGHUP or --checkpoint-every)\n"
    "  sweep      run a scene over a grid of values (--vary), a cost-error table and its Pareto front\n"
    "  plugins    list the plug-ins found, or describe one model's properties and units\n"
    "  validate   run the validation cases against their reference data (validation/)\n"
    "  new-model  make an out-of-tree project for a new contact model\n"
    "  plot       draw history columns of one or more runs, and reference data, as a PNG\n"
    "  quantities list the history quantities a scene can record, with their units\n"
    "  --version  the version and how this binary was built\n\n";

int cmd_restart(const std::vector<std::string>& args) {
    const RunOptions o = parse_run_options(args, "checkpoint");
    std::unique_ptr<Simulation> sim;
    try {
        sim = Simulation::restart(o.path, o.sets);
    } catch (const CheckpointError& e) {
        std::cerr << "error: cannot restart: " << e.what() << "\n";
        return 2;
    }
    sim->set_quiet(o.quiet);
    if (!o.out.empty()) sim->set_output_dir(o.out);
    if (o.every > 0) sim->set_checkpoint_every(o.every);
    if (o.watch) sim->set_watch();
    return run_and_report(*sim, o.quiet, sim->output_dir());
}

int cmd_run(const std::vector<std::string>& args) {
    const RunOptions o = parse_run_options(args, "scene");
    const std::string& scene_path = o.path;
    std::string out = o.out;
    json scene = read_scene_file(scene_path);
    for (const auto& s : o.sets) apply_override(scene, s);
    apply_output_flags(scene, o);
    const std::string scene_dir = fs::absolute(scene_path).parent_path().string();
    Simulation sim(scene, scene_dir);
    sim.set_quiet(o.quiet);
    // --out wins, then the scene's output.dir, then plab_out/<scene name>
    if (out.empty() && !(scene.contains("output") && scene["output"].contains("dir")))
        out = "plab_out/" + fs::path(scene_path).stem().string();
    if (!out.empty()) sim.set_output_dir(out);
    if (o.every > 0) sim.set_checkpoint_every(o.every);
    if (o.watch) sim.set_watch();
    return run_and_report(sim, o.quiet, sim.output_dir());
}

double default_range(const plab_contact_model_desc& d) {
    std::vector<double> props;
    for (uint32_t p = 0; p < d.property_count; ++p) props.push_back(d.properties[p].default_value);
    return d.activity_range(props.data());
}

// One property for --describe: key, name, kind (a choice's names, a
// group's "none"), unit, default, range, mixing rule, doc; "(material M)"
// for one that a scene material may give (its package material declares it).
void describe_property(const plab_property_desc& q, const plab_material_desc* material) {
    std::cout << "    " << q.key << "  " << q.name;
    if (material_property(material, q.key)) std::cout << " (material " << material->name << ")";
    switch (q.kind) {
    case PLAB_KIND_BOOL:
        std::cout << ", bool (true | false), default " << (q.default_value != 0 ? "true" : "false");
        break;
    case PLAB_KIND_CHOICE: {
        std::cout << ", choice: ";
        for (uint32_t c = 0; c < q.choice_count; ++c) std::cout << (c ? " | " : "") << q.choices[c];
        std::cout << ", default " << q.choices[std::size_t(q.default_value)];
        break;
    }
    case PLAB_KIND_GROUP:
        std::cout << ", group (a group name"
                  << (q.flags & PLAB_GROUP_NONE_ALLOWED ? ", or null for none), default none" : "), required");
        break;
    default:
        std::cout << " [" << q.unit << "], " << kind_name(q.kind) << ", default " << q.default_value << ", range "
                  << range_text(q);
    }
    // two materials' values mix only for numbers (abi.h PLAB_MIX_*)
    if (q.kind == PLAB_KIND_NUMBER || q.kind == PLAB_KIND_INTEGER) std::cout << ", mixing " << mixing_name(q.mixing);
    std::cout << "\n        " << q.doc << "\n";
}

// The package material a model or pass takes from, for --describe.
const plab_material_desc* describe_material(const PluginHost& host, const char* name, bool pass) {
    const plab_material_desc* m = name ? host.material(name) : nullptr;
    if (!m) {
        std::cout << "  material: none (a scene's materials give it no values)\n";
        return nullptr;
    }
    std::cout << "  material: " << m->name << ", " << m->doc << "\n    "
              << (pass ? "the scene material the pass names (\"material\": NAME)" : "a scene material of the rule's groups")
              << " gives the properties marked (material " << m->name << ")\n";
    return m;
}

void describe(const PluginHost& host, const std::string& name) {
    if (const plab_contact_model_desc* d = host.model(name)) {
        std::cout << "contact model " << d->name << "  (" << host.library_of_model(name) << ")\n  " << d->doc << "\n"
                  << "  activity range: active while the " << (d->range_kind == PLAB_RANGE_GAP ? "surface gap" : "centre distance")
                  << " <= a value set by the properties (" << default_range(*d) << " m with the defaults)\n"
                  << "  stable timestep: " << d->timestep_rule << "\n";
        const plab_material_desc* material = describe_material(host, d->material, false);
        std::cout << "  properties:\n";
        for (uint32_t p = 0; p < d->property_count; ++p) describe_property(d->properties[p], material);
        std::cout << "  history slots:\n";
        for (uint32_t h = 0; h < d->history_count; ++h)
            std::cout << "    " << d->history[h].name << " (default " << d->history[h].default_value << ", "
                      << (d->history[h].swap_rule == PLAB_SWAP_NEGATE ? "negated" : "kept") << " when ends swap"
                      << (d->history[h].flags & PLAB_HISTORY_TANGENTIAL
                              ? "; with the next two, a vector in the contact plane, turned with it by the host"
                              : "")
                      << ")\n";
        for (uint32_t f = 0; f < d->fields_read_count; ++f) std::cout << "  reads body field " << d->fields_read[f].name << "\n";
        return;
    }
    if (const plab_pass_desc* p = host.pass(name)) {
        static const char* phases[] = {"pre-force", "post-force", "integrate", "rates-done", "pre-drift"};
        std::cout << "pass " << p->name << " (" << phases[p->phase] << ", stage " << p->stage << ")  ("
                  << host.library_of_pass(name) << ")\n  " << p->doc << "\n";
        const plab_material_desc* material = describe_material(host, p->material, true);
        if (p->property_count > 0) std::cout << "  properties:\n";
        for (uint32_t q = 0; q < p->property_count; ++q) describe_property(p->properties[q], material);
        for (uint32_t f = 0; f < p->field_count; ++f)
            std::cout << "  field " << p->fields[f].name << " [" << p->fields[f].unit << "]\n";
        return;
    }
    throw InputError("--describe", "no model or pass named '" + name + "' among the plug-ins found");
}

int cmd_plugins(const std::vector<std::string>& args) {
    PluginHost host;
    if (args.size() == 2 && args[0] == "--describe") {  // the one asked for, not the list
        for (const auto& path : host.discover()) {
            try {
                host.load(path);
            } catch (const PluginError&) {
            }
        }
        describe(host, args[1]);
        return 0;
    }
    std::cout << "plug-in search path:\n";
    for (const auto& d : host.search_dirs()) std::cout << "  " << d << "\n";
    for (const auto& path : host.discover()) {
        try {
            const LoadedLibrary& lib = host.load(path);
            std::cout << path << "\n";
            for (const auto& m : lib.models) std::cout << "  model " << m << "\n";
            for (const auto& p : lib.passes) std::cout << "  pass  " << p << "\n";
            for (const auto& m : lib.materials) std::cout << "  material " << m << "\n";
        } catch (const PluginError& e) {
            std::cout << path << "\n  REFUSED: " << e.what() << "\n";
        }
    }
    if (!args.empty()) throw InputError("command line", std::string("plab plugins takes [--describe MODEL]\n") + usage);
    return 0;
}

// The history quantities with their units; a scene's plug-ins add fields
// for probe.<field> (plab plugins --describe PASS lists them).
int cmd_quantities(const std::vector<std::string>& args) {
    if (!args.empty()) throw InputError("command line", std::string("plab quantities takes no arguments\n") + usage);
    std::cout << "history quantities (histories.record[k].quantity), unit, what:\n";
    for (const QuantityInfo& q : history_quantities())
        std::cout << "  " << q.name << "  [" << q.unit << "]\n      " << q.doc << "\n";
    std::cout << "  or {\"name\": N, \"expression\": \"...\"} of earlier columns and the scene's variables\n";
    return 0;
}

int cmd_validate(const std::vector<std::string>& args) {
    bool quick = false, all = false;
    std::string report;
    std::vector<std::string> names;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--quick") quick = true;
        else if (a == "--report" && i + 1 < args.size()) report = args[++i];
        else if (a == "--report") throw InputError("command line", "--report needs a folder, e.g. --report validation_report");
        else if (a == "--all") all = true;
        else if (a == "--list") {
            for (const auto& c : validation_cases()) std::cout << c.name << "  " << c.description << "\n";
            return 0;
        } else names.push_back(a);
    }
    if (!all && names.empty()) throw InputError("command line", std::string("name a case, or --all / --list\n") + usage);
    std::vector<const ValidationCase*> chosen;
    for (const auto& c : validation_cases())
        if (all || std::find(names.begin(), names.end(), c.name) != names.end()) chosen.push_back(&c);
    for (const auto& n : names)
        if (std::none_of(chosen.begin(), chosen.end(), [&](auto* c) { return c->name == n; })) {
            std::string known;
            for (const auto& c : validation_cases()) known += " " + c.name;
            throw InputError("command line", "unknown validation case '" + n + "'; cases:" + known);
        }
    int failed = 0;
    std::vector<CaseRun> runs;
    for (const ValidationCase* c : chosen) {
        const std::clock_t t0 = std::clock();
        CaseResult r;
        std::string crash;
        try {
            r = c->run(quick);
        } catch (const std::exception& e) {
            crash = e.what();
            r.error = kInf;
            r.failed_checks = 1;  // a case that could not be judged has failed
        }
        const double cpu = double(std::clock() - t0) / CLOCKS_PER_SEC;
        std::printf("%-22s %-4s error %.4g (tolerance %.4g, %s)  cpu %.2f s\n", c->name.c_str(),
                    r.passed() ? "PASS" : "FAIL", r.error, r.tolerance, r.metric.c_str(), cpu);
        if (!r.details.empty()) std::printf("%s", r.details.c_str());
        if (!crash.empty()) std::printf("    stopped: %s\n", crash.c_str());
        failed += !r.passed();
        runs.push_back({c->name, c->description, r, cpu, crash});
        std::fflush(stdout);
    }
    std::printf("%zu passed, %d failed\n", chosen.size() - failed, failed);
    if (!report.empty()) std::printf("report: %s\n", write_validation_report(report, runs, quick).c_str());
    return failed ? 1 : 0;
}

} // namespace

int main(int argc, char** argv) {
#ifdef __GLIBC__
    // Blocks of 1 MiB and more straight from the system and back to it when
    // freed. glibc would otherwise raise this threshold to the largest block
    // freed and serve big ones from its heap, whose free pages stay
    // resident: a big world's lean rebuilds (World::lean_rebuild_rows) free
    // and make its lists anew, and its peak memory grew by the holes (109
    // against 94 MiB on memory.py's settled pile of 1e5 balls). Small worlds
    // keep their buffers across rebuilds, so this costs them nothing.
    mallopt(M_MMAP_THRESHOLD, 1 << 20);
#endif
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
        std::cout << help << usage;
        return args.empty() ? 2 : 0;
    }
    if (args[0] == "--version" || args[0] == "version") {
        std::cout << "plab " << PLAB_VERSION << " (plug-in ABI " << PLAB_ABI_MAJOR << "." << PLAB_ABI_MINOR << ", " << build_flags() << ")\n";
        return 0;
    }
    const std::string cmd = args[0];
    args.erase(args.begin());
    try {
        if (cmd == "run") return cmd_run(args);
        if (cmd == "restart") return cmd_restart(args);
        if (cmd == "check") return cmd_check(args);
        if (cmd == "plugins") return cmd_plugins(args);
        if (cmd == "sweep") return cmd_sweep(args, fs::read_symlink("/proc/self/exe").string());
        if (cmd == "validate") return cmd_validate(args);
        if (cmd == "new-model") return cmd_new_model(args);
        if (cmd == "plot") return cmd_plot(args);
        if (cmd == "quantities") return cmd_quantities(args);
        std::cerr << "unknown command '" << cmd << "'\n" << usage;
        return 2;
    } catch (const InputError& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    } catch (const PluginError& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 1;
    }
}
