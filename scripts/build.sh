#!/usr/bin/env bash
# Configures and builds ParticleLab in ./build (Release). PLAB_FUZZ_SMOKE=1
# also registers the CTest fuzz_build and fuzz_smoke (tests/fuzz/).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPLAB_FUZZ_SMOKE="${PLAB_FUZZ_SMOKE:-OFF}" >/dev/null
cmake --build build -j"$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)"
