#!/usr/bin/env bash
# Configures and builds ParticleLab in ./build (Release). PLAB_FUZZ_SMOKE=1
# also registers the CTest fuzz_build and fuzz_smoke (tests/fuzz/).
# The kernel and scene library build as unity batches (PLAB_UNITY_BUILD):
# a fresh build parses their shared headers once per batch of 8 sources,
# not once per source, and gives the same bits (bench/redesign/same_bits.py).
# A developer's own cmake build leaves it off: one edited source then
# recompiles alone.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPLAB_FUZZ_SMOKE="${PLAB_FUZZ_SMOKE:-OFF}" -DPLAB_UNITY_BUILD=ON >/dev/null
cmake --build build -j"$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)"
