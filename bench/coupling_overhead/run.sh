#!/bin/sh
# Issue 5: a DEM-only scene must not pay for the coupling plug-ins. Runs the
# granular scene with and without the coupling plug-ins loaded (they are in
# the plug-in folder in both cases), alternating, N times each, one thread,
# and prints the CPU seconds of each run (summary.json) and their means.
#   bench/coupling_overhead/run.sh [BUILD_DIR] [N]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../../build}
n=${2:-5}
export OMP_NUM_THREADS=1
out=$(mktemp -d)
for i in $(seq 1 "$n"); do
  for scene in granular granular_with_coupling; do
    "$build/plab" run "$here/$scene.json" --quiet --out "$out/run" >/dev/null
    cpu=$(sed -n 's/.*"cpu_seconds": *\([0-9.e+-]*\).*/\1/p' "$out/run/summary.json")
    echo "$scene $cpu" >> "$out/times"
  done
done
cat "$out/times"
awk '{s[$1]+=$2; q[$1]+=$2*$2; c[$1]++}
     END {for (k in s) {m=s[k]/c[k]; sd=sqrt((q[k]/c[k]-m*m)>0?(q[k]/c[k]-m*m):0); printf "%-24s mean %.3f s  sd %.3f s  (n=%d)\n", k, m, sd, c[k]}}' "$out/times"
rm -rf "$out"
