// plab_bench_plugin_overhead: what the plug-in boundary costs (issue 8,
// target <= 3 %). The `linear` law runs on the same contact batches twice:
//   plugin  — the library the host loads (plab_linear.so), called through
//             the C ABI (one indirect call per batch of kContactBatch rows);
//   inline  — the same source (physics/dem/linear/linear.cpp) compiled
//             into this binary and called directly, so the compiler may
//             inline the batch loop into the benchmark.
// The batches look like a settling pile's: about 45 % of the candidate rows
// in contact (overlaps up to 1e-5 m, the rest at small positive gaps), unit
// normals, relative velocities up to 0.1 m/s, a stored shear force on most
// contacts, half of them at the Coulomb limit. Both paths start from the same
// history for every repetition and must give bit-identical outputs (else the
// comparison is void and the exit status is 1). Repetitions alternate the two
// paths; the minimum time of each is compared (a loaded machine only adds).
#include <plab_host/plugins.hpp>
#include <plab_host/world.hpp>

// The law compiled into this binary: the plug-in's own source. Its two
// exported entry points are renamed so they cannot clash with the library's.
#define plab_plugin_abi_version inline_linear_abi_version
#define plab_plugin_init inline_linear_init
#include "../physics/dem/linear/linear.cpp"
#undef plab_plugin_abi_version
#undef plab_plugin_init

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace {

// Host-owned columns of `rows` contacts, as the kernel's call_model lays them out.
struct Columns {
    std::size_t rows = 0;
    std::vector<std::int32_t> end1, end2;
    std::vector<std::uint8_t> active;
    std::vector<double> normal, gap, distance, rel_velocity, rel_angular_velocity, radius1, radius2, mass1, mass2,
        eff_mass, eff_radius, history, force, moment1, moment2, strain, slip, dashpot, k_t, k_r, dt_limit, broken;

    explicit Columns(std::size_t n) : rows(n) {
        std::mt19937_64 rng(8);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        end1.resize(n); end2.resize(n); active.resize(n);
        for (auto* v : {&normal, &rel_velocity, &rel_angular_velocity, &force, &moment1, &moment2, &history})
            v->assign(3 * n, 0.0);
        for (auto* v : {&gap, &distance, &radius1, &radius2, &mass1, &mass2, &eff_mass, &eff_radius, &strain, &slip,
                        &dashpot, &k_t, &k_r, &dt_limit, &broken})
            v->assign(n, 0.0);
        const double r = 0.005, m = 2500 * 4.0 / 3.0 * M_PI * r * r * r;
        for (std::size_t k = 0; k < n; ++k) {
            end1[k] = std::int32_t(k % 10000);
            end2[k] = std::int32_t((k * 7 + 1) % 10000);
            active[k] = u(rng) < -0.1;  // ~45 %
            double nx = u(rng), ny = u(rng), nz = u(rng);
            const double len = std::sqrt(nx * nx + ny * ny + nz * nz) + 1e-12;
            nx /= len; ny /= len; nz /= len;
            normal[3 * k] = nx; normal[3 * k + 1] = ny; normal[3 * k + 2] = nz;
            gap[k] = active[k] ? -1e-5 * (0.5 + 0.5 * u(rng)) : 1e-3 * (0.5 + 0.5 * u(rng));
            distance[k] = 2 * r + gap[k];
            for (int c = 0; c < 3; ++c) {
                rel_velocity[3 * k + c] = 0.05 * u(rng);
                rel_angular_velocity[3 * k + c] = u(rng);
            }
            radius1[k] = radius2[k] = r;
            mass1[k] = mass2[k] = m;
            eff_mass[k] = m / 2;
            eff_radius[k] = r / 2;
            // a shear force in the contact plane, of the order of mu kn overlap
            const double t[3] = {u(rng), u(rng), u(rng)};
            const double tn = t[0] * nx + t[1] * ny + t[2] * nz;
            const double scale = 0.5 * (1 + u(rng)) * 0.5 * 1e5 * 1e-5;
            history[3 * k] = scale * (t[0] - tn * nx);
            history[3 * k + 1] = scale * (t[1] - tn * ny);
            history[3 * k + 2] = scale * (t[2] - tn * nz);
        }
    }

    plab_contact_batch batch(std::size_t o, std::size_t m) {
        plab_contact_batch b{sizeof(plab_contact_batch)};
        b.dim = 3;
        b.count = std::uint32_t(m);
        b.history_stride = 3;
        b.dt = 1e-5;
        b.end1 = end1.data() + o; b.end2 = end2.data() + o; b.active = active.data() + o;
        b.normal = normal.data() + 3 * o; b.gap = gap.data() + o; b.distance = distance.data() + o;
        b.rel_velocity = rel_velocity.data() + 3 * o; b.rel_angular_velocity = rel_angular_velocity.data() + 3 * o;
        b.radius1 = radius1.data() + o; b.radius2 = radius2.data() + o; b.mass1 = mass1.data() + o;
        b.mass2 = mass2.data() + o; b.eff_mass = eff_mass.data() + o; b.eff_radius = eff_radius.data() + o;
        b.history = history.data() + 3 * o;
        b.force = force.data() + 3 * o; b.moment1 = moment1.data() + 3 * o; b.moment2 = moment2.data() + 3 * o;
        b.strain_energy = strain.data() + o; b.slip_energy = slip.data() + o; b.dashpot_energy = dashpot.data() + o;
        b.stiffness_translational = k_t.data() + o; b.stiffness_rotational = k_r.data() + o;
        b.dt_limit = dt_limit.data() + o; b.break_energy = broken.data() + o;
        return b;
    }
};

// One sweep over all rows in batches, as the host's force pass does: zero
// the outputs the law adds to, then one call per batch.
template <class Call> double sweep(Columns& c, const std::vector<double>& history0, Call call) {
    c.history = history0;
    std::fill(c.slip.begin(), c.slip.end(), 0.0);
    std::fill(c.dashpot.begin(), c.dashpot.end(), 0.0);
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t o = 0; o < c.rows; o += plab::kContactBatch) {
        const plab_contact_batch b = c.batch(o, std::min(plab::kContactBatch, c.rows - o));
        if (call(b) != 0) {
            std::fprintf(stderr, "plab_bench_plugin_overhead: compute() failed\n");
            std::exit(2);
        }
    }
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<double> outputs(const Columns& c) {
    std::vector<double> out = c.force;
    out.insert(out.end(), c.history.begin(), c.history.end());
    out.insert(out.end(), c.strain.begin(), c.strain.end());
    out.insert(out.end(), c.slip.begin(), c.slip.end());
    out.insert(out.end(), c.dashpot.begin(), c.dashpot.end());
    return out;
}

} // namespace

int main(int argc, char** argv) {
    const std::size_t rows = argc > 1 ? std::size_t(std::atof(argv[1])) : 40000;
    const int reps = argc > 2 ? std::atoi(argv[2]) : 200;
    if (rows < 1 || reps < 1) {
        std::fprintf(stderr, "usage: plab_bench_plugin_overhead [ROWS (40000)] [REPETITIONS (200)]\n");
        return 2;
    }
    // properties of the issue-8 scene (gran3d.json, ball-ball rule)
    const double props[] = {1e5, 28571.4, 0.5, 0.215452, 0.201537, 0.0, 0.0};

    plab::PluginHost host;
    host.load(host.resolve("linear"));
    const plab_contact_model_desc* lib = host.model("linear");
    void* lib_state = lib->create(props);
    const plab_contact_model_desc* here = plab::contact_model_desc<Linear>();
    void* here_state = here->create(props);

    Columns c(rows);
    const std::vector<double> history0 = c.history;
    auto via_abi = [&](const plab_contact_batch& b) { return lib->compute(lib_state, props, &b); };
    auto direct = [&](const plab_contact_batch& b) { return plab::detail::compute<Linear>(here_state, props, &b); };

    sweep(c, history0, via_abi);
    const std::vector<double> ref = outputs(c);
    sweep(c, history0, direct);
    const bool same = outputs(c) == ref;

    double t_abi = 1e300, t_direct = 1e300, sum_abi = 0, sum_direct = 0;
    for (int r = 0; r < reps; ++r) {
        const double a = sweep(c, history0, via_abi), d = sweep(c, history0, direct);
        t_abi = std::min(t_abi, a);
        t_direct = std::min(t_direct, d);
        sum_abi += a;
        sum_direct += d;
    }
    const std::size_t active = std::size_t(std::count(c.active.begin(), c.active.end(), 1));
    std::printf("plab_bench_plugin_overhead: linear law, %zu candidate rows (%zu in contact), batches of %zu, %d "
                "alternating repetitions\n",
                rows, active, plab::kContactBatch, reps);
    std::printf("%-34s %12s %12s %14s\n", "path", "min ms", "mean ms", "ns/contact");
    std::printf("%-34s %12.3f %12.3f %14.2f\n", "plug-in library through the C ABI", 1e3 * t_abi, 1e3 * sum_abi / reps,
                1e9 * t_abi / double(active));
    std::printf("%-34s %12.3f %12.3f %14.2f\n", "same law compiled in, direct call", 1e3 * t_direct,
                1e3 * sum_direct / reps, 1e9 * t_direct / double(active));
    const double overhead = 100.0 * (t_abi - t_direct) / t_direct;
    std::printf("overhead of the plug-in boundary (min times): %+.2f %% (target <= 3 %%: %s); outputs %s\n", overhead,
                overhead <= 3.0 ? "PASS" : "FAIL", same ? "bit-identical" : "DIFFER");
    lib->destroy(lib_state);
    here->destroy(here_state);
    return same ? 0 : 1;
}
