#!/usr/bin/env bash
# The fuzzer in a CI-sized dose (ctest fuzz_smoke, with -DPLAB_FUZZ_SMOKE=ON):
# tests/fuzz/run.sh for SECONDS (default 60), failing if it stops with an
# error or leaves a finding (crash-*, timeout-*, oom-*, leak-*) in
# build-fuzz/findings/ during this run (CTest's fuzz_build makes
# build-fuzz/ first).
#   tests/fuzz/smoke.sh [SECONDS]
set -euo pipefail
seconds=${1:-60}
root=$(cd "$(dirname "$0")/../.." && pwd)
stamp=$(mktemp)
trap 'rm -f "$stamp"' EXIT
set +e
"$root/tests/fuzz/run.sh" "$seconds"
rc=$?
set -e
found=$(find "$root/build-fuzz/findings" -type f -newer "$stamp" 2>/dev/null || true)
[ -z "$found" ] || { echo "FAIL: the fuzzer found:"; echo "$found"; exit 1; }
[ "$rc" -eq 0 ] || { echo "FAIL: tests/fuzz/run.sh exited $rc"; exit 1; }
echo "PASS: no finding in $seconds s"
