#!/usr/bin/env bash
# Builds build-fuzz/: the libFuzzer target of the scene parser and the
# in-tree plug-ins, with clang, ASan and UBSan (installs clang if missing:
# the fuzz build needs it, the default build does not). tests/fuzz/run.sh
# calls it; CTest runs it alone as fuzz_build, the fixture of fuzz_smoke.
# Line tables only (-gline-tables-only): a finding's stack still names files
# and lines, and the build does not emit the full debug information it never
# reads. -O1, not -O0: -O0 compiles 2.4 times faster, but its slower
# inputs run past libFuzzer's 10 s per input (a random fill of the corpus).
# The kernel and scene library as unity batches (PLAB_UNITY_BUILD): a
# quarter of the compile time, most of which went to parsing the same
# headers under the sanitizers once per source.
set -euo pipefail
cd "$(dirname "$0")/../.."
scripts/install-deps.sh
if ! command -v clang++ >/dev/null; then
  sudo_cmd=(); [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get install -y -qq clang >/dev/null
fi
flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
flags+=" -gline-tables-only -O1"
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug -DPLAB_FUZZ=ON -DPLAB_BUILD_TESTS=OFF \
  -DPLAB_OPENMP=OFF -DPLAB_UNITY_BUILD=ON -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" -DCMAKE_MODULE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build build-fuzz -j"$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)" --target plab_scene_fuzz
