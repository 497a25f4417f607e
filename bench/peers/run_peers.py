#!/usr/bin/env python3
"""plab against LAMMPS and LIGGGHTS on the issue-8 scenes, side by side.

Scenes: gran3d, gran2d (granular settling) and sph (the SPH double dam break,
sph_double_dam_break.json / liggghts_sph.in: LAMMPS has no SPH in Debian, so
it is run against LIGGGHTS only, 8000 steps unless --sph-steps says otherwise).
Runs every (scene, code, threads) combination `--reps` times, interleaved so
that a change in machine load hits every code alike, and prints the median
loop throughput (particle-steps per second), the ratio plab/peer, and a
physics check: pair contacts and kinetic energy at the end of each code (SPH:
the fluid's mean height instead of contacts, and both must agree within 3 %).
plab's throughput is from its run summary (the solve loop); the peers' from
their "Loop time" line. Threads: plab OpenMP threads, peers MPI ranks, started
as a user starts them: the inputs set the processors grid for the scene's
geometry (`processors * 1 1`: the default grid cuts a settling column along
its tall axis and one rank holds nearly all the balls) and mpirun binds each
rank to a core. Each run's peak resident memory (wait4 maxrss) and the load
average are printed; every table comes with the CPU model, its vector
extensions, the date and the load average (a table is only comparable with
one taken on the same CPU at a similar load).
Every code runs with its own defaults, as a user would run it: OpenMP's and
Open MPI's idle threads and ranks spin briefly before they sleep. On a
machine shared with other work, spinning steals the others' CPU (an earlier
run under load 11-15 made 2-thread plab 11x slower); --shared-machine then
makes idle threads and ranks yield instead (plab: OMP_WAIT_POLICY=PASSIVE;
Open MPI: mpi_yield_when_idle 1), and the table says so. On an idle
machine PASSIVE costs plab a futex wake per parallel region (gran3d at 2
threads: 12.7 s against 7.6 s wall, 2026-11-22); the peers' loop times do
not change.
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


SPH_SCENE = "sph_double_dam_break"
# the vector extensions that decide how fast the codes' loops can be (plab's kernels use AVX-512 when there)
VECTOR_FLAGS = ("sse4_2", "avx", "fma", "avx2", "avx512f", "avx512dq", "avx512bw", "avx512vl")


def machine():
    """One line for every table: CPU model and vector extensions (/proc/cpuinfo), date, load average."""
    model, flags = "unknown CPU", set()
    try:
        for line in open("/proc/cpuinfo"):
            key, _, val = line.partition(":")
            if key.strip() == "model name":
                model = val.strip()
            elif key.strip() == "flags":
                flags = set(val.split())
                break
    except OSError:
        pass
    vec = " ".join(f for f in VECTOR_FLAGS if f in flags) or "none listed"
    return (f"machine: {model}, {os.cpu_count()} CPUs, {vec}; {time.strftime('%Y-%m-%d %H:%M %Z')}; "
            f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


def grid(infile):
    """The input's processors line (what the table's peers ran with)."""
    return next((" ".join(l.split()[1:]) for l in open(os.path.join(HERE, infile)) if l.startswith("processors")),
                "LAMMPS default")


def run_measured(cmd, env, capture):
    """Runs cmd; returns (stdout text or None, peak resident memory in MB, CPU seconds user + system,
    its reaped children's included: both MPI ranks under mpirun)."""
    p = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE if capture else subprocess.DEVNULL,
                         stderr=subprocess.DEVNULL, text=True)
    text = p.stdout.read() if capture else None
    _, status, usage = os.wait4(p.pid, 0)
    code = os.waitstatus_to_exitcode(status)
    if code != 0:
        raise subprocess.CalledProcessError(code, cmd)
    return text, usage.ru_maxrss / 1024.0, usage.ru_utime + usage.ru_stime  # Linux: kB


def run_plab(plab, scene, threads, steps, work, shared):
    out = os.path.join(work, "plab_out")
    sph = scene == "sph"
    sc = json.load(open(os.path.join(HERE, (SPH_SCENE if sph else scene) + ".json")))
    sc["commands"] = [{"cycle": steps}]
    if sph:  # one history row at the end: the fluid's mean height
        sc["histories"] = {"every": steps, "record": [
            {"name": "ymean", "quantity": "group.mean.position.y", "group": "fluid"}]}
    path = os.path.join(work, scene + "_run.json")
    json.dump(sc, open(path, "w"))
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    if shared:
        env.setdefault("OMP_WAIT_POLICY", "PASSIVE")
    _, rss, cpu = run_measured([plab, "run", path, "--out", out], env, False)
    s = json.load(open(os.path.join(out, "summary.json")))
    if sph:
        rows = open(os.path.join(out, "history.csv")).read().split()
        return (s["particle_steps_per_second"], float(rows[-1].split(",")[-1]), s["energies"]["kinetic"],
                s["state_hash"], rss, cpu)
    pairs = sum(m["active_contacts"] for m in s["models"][:1])  # first rule: grains-grains
    return s["particle_steps_per_second"], pairs, s["energies"]["kinetic"], s["state_hash"], rss, cpu


def run_peer(exe, infile, dim, data, threads, steps, shared):
    cmd = [exe, "-in", os.path.join(HERE, infile), "-var", "steps", str(steps), "-log", "none"]
    if data:
        cmd += ["-var", "dim", str(dim), "-var", "data", data]
    if threads > 1:
        # one rank per core, bound, as a user runs them (no --oversubscribe: more ranks than cores is an error,
        # not a measurement); the inputs set the processors grid
        yield_idle = ["--mca", "mpi_yield_when_idle", "1"] if shared else []
        cmd = ["mpirun", "--allow-run-as-root", "--bind-to", "core"] + yield_idle + ["-np", str(threads)] + cmd
    env = dict(os.environ, OMP_NUM_THREADS="1")
    text, rss, cpu = run_measured(cmd, env, True)
    loop = float(re.search(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps with (\d+) atoms", text).group(1))
    m = re.search(r"PEER_RESULT contacts ([0-9.eE+-]+) kinetic ([0-9.eE+-]+)", text)
    atoms = int(re.search(r"for \d+ steps with (\d+) atoms", text).group(1))
    return atoms * steps / loop, float(m.group(1)), float(m.group(2)), None, rss, cpu


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--plab", default=os.path.join(ROOT, "build", "plab"))
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--steps", type=int, default=20000)
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--scenes", default="gran3d,gran2d,sph")
    ap.add_argument("--sph-steps", type=int, default=8000)
    ap.add_argument("--codes", default="plab,lammps,liggghts")
    ap.add_argument("--shared-machine", action="store_true",
                    help="idle threads and ranks yield (OMP_WAIT_POLICY=PASSIVE, mpi_yield_when_idle 1)")
    a = ap.parse_args()
    work = tempfile.mkdtemp(prefix="plab_peers_")
    subprocess.run([sys.executable, os.path.join(HERE, "make_peer_data.py"), work], check=True)
    threads = [int(t) for t in a.threads.split(",")]
    codes = a.codes.split(",")
    results = {}
    print(machine())
    print("idle threads/ranks: " + ("yield (--shared-machine)" if a.shared_machine else "each code's default (spin, then sleep)"))
    print("peers: MPI ranks bound to cores (mpirun --bind-to core); processors grid: " +
          ", ".join(f"{f} {grid(f)}" for f in ("lammps_gran.in", "liggghts_gran.in", "liggghts_sph.in")))
    print(f"load average at start: {' '.join(f'{x:.2f}' for x in os.getloadavg())}", flush=True)
    for rep in range(a.reps):
        for scene in a.scenes.split(","):
            dim = 3 if scene.endswith("3d") else 2
            steps = a.sph_steps if scene == "sph" else a.steps
            for t in threads:
                for code in codes:
                    if scene == "sph" and code == "lammps":
                        continue  # no SPH package in Debian's LAMMPS
                    if code == "plab":
                        r = run_plab(a.plab, scene, t, steps, work, a.shared_machine)
                    elif scene == "sph":
                        r = run_peer("liggghts", "liggghts_sph.in", dim, None, t, steps, a.shared_machine)
                    elif code == "lammps":
                        r = run_peer("lmp", "lammps_gran.in", dim, os.path.join(work, scene + ".data"), t, steps, a.shared_machine)
                    else:
                        data = os.path.join(work, scene + ("_liggghts" if dim == 2 else "") + ".data")
                        r = run_peer("liggghts", "liggghts_gran.in", dim, data, t, steps, a.shared_machine)
                    results.setdefault((scene, t, code), []).append(r)
                    second = f"fluid mean height {r[1]:.5g} m" if scene == "sph" else f"{r[1]:.0f} pair contacts"
                    print(f"  rep {rep + 1} {scene} {code} x{t}: {r[0] / 1e6:.2f} M particle-steps/s, "
                          f"{second}, kinetic {r[2]:.4g} J, peak {r[4]:.0f} MB, CPU {r[5]:.1f} s" + (f", hash {r[3]}" if r[3] else "")
                          + f", load {os.getloadavg()[0]:.2f}", flush=True)
    print(f"load average at end: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    print("\n" + machine())
    print(f"median of {a.reps} interleaved runs, {a.steps} steps (sph: {a.sph_steps}), "
          "loop throughput in M particle-steps/s")
    print("| scene | threads | " + " | ".join(codes) + " | " +
          " | ".join(f"plab/{c}" for c in codes if c != "plab") +
          " | pair contacts (sph: fluid mean height, m) | kinetic energy, J | peak memory, MB |")
    print("|---" * (3 + 2 * len(codes) - 1 + 2) + "|")
    for scene in a.scenes.split(","):
        for t in threads:
            have = [c for c in codes if (scene, t, c) in results]
            med = {c: statistics.median(x[0] for x in results[(scene, t, c)]) for c in have}
            last = {c: results[(scene, t, c)][-1] for c in have}
            ratios = [f"{med['plab'] / med[c]:.2f}" if c in med and "plab" in med else "-"
                      for c in codes if c != "plab"]
            fmt = "{:.4g}" if scene == "sph" else "{:.0f}"
            print(f"| {scene} | {t} | " + " | ".join(f"{med[c] / 1e6:.2f}" if c in med else "-" for c in codes) +
                  " | " + " | ".join(ratios) + " | " + " / ".join(fmt.format(last[c][1]) for c in have) + " | " +
                  " / ".join(f"{last[c][2]:.4g}" for c in have) + " | " +
                  " / ".join(f"{max(x[4] for x in results[(scene, t, c)]):.0f}" for c in have) + " |")
            if scene == "sph" and "plab" in last and "liggghts" in last:
                dh = last["plab"][1] / last["liggghts"][1] - 1
                dk = last["plab"][2] / last["liggghts"][2] - 1
                ok = abs(dh) <= 0.03 and abs(dk) <= 0.03
                print(f"sph x{t}: plab vs LIGGGHTS: fluid mean height {100 * dh:+.2f} %, kinetic energy "
                      f"{100 * dk:+.2f} % -> {'physics agrees (3 %)' if ok else 'PHYSICS DIFFERS'}")
    # On a shared machine wall-clock loop times measure the load as much as the
    # codes; CPU time (whole process, set-up included) is the steadier figure.
    print("\n" + machine())
    print("median CPU seconds of the whole run (user + system, all threads/ranks), and peer/plab")
    for scene in a.scenes.split(","):
        for t in threads:
            have = [c for c in codes if (scene, t, c) in results]
            cpu = {c: statistics.median(x[5] for x in results[(scene, t, c)]) for c in have}
            ratios = [f"{c} {cpu[c]:.1f} s ({cpu[c] / cpu['plab']:.2f}x)" for c in have if c != "plab" and "plab" in cpu]
            print(f"{scene} x{t}: " + (f"plab {cpu['plab']:.1f} s; " if "plab" in cpu else "") + "; ".join(ratios))
    if "plab" in codes and len(threads) > 1:
        for scene in a.scenes.split(","):
            hashes = {t: results[(scene, t, "plab")][-1][3] for t in threads}
            print(f"plab {scene}: state hash by thread count {hashes} -> "
                  f"{'bit-identical' if len(set(hashes.values())) == 1 else 'DIFFERENT'}")


if __name__ == "__main__":
    main()
