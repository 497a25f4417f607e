#!/usr/bin/env bash
# Side-by-side throughput of plab, LAMMPS and LIGGGHTS on the issue-8 scenes.
# Installs the peers from Debian when missing (root), builds plab, then runs
# bench/peers/run_peers.py (arguments are passed on, e.g. --reps 5).
set -euo pipefail
cd "$(dirname "$0")/../.."
missing=()
command -v lmp >/dev/null || missing+=(lammps)
command -v liggghts >/dev/null || missing+=(liggghts)
command -v mpirun >/dev/null || missing+=(openmpi-bin)
if ((${#missing[@]})); then
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}"
fi
scripts/install-deps.sh
scripts/build.sh
exec python3 bench/peers/run_peers.py "$@"
