#!/usr/bin/env bash
# Builds ParticleLab with AddressSanitizer and UndefinedBehaviorSanitizer in
# build-asan/ (the kernel, the CLI, every plug-in and the tests: the plug-ins
# are loaded by the sanitized host, so they run under ASan too) and runs the
# unit tests. Any report fails the run.
#   scripts/sanitize.sh [ctest -R regex]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g -O2"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_C_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_MODULE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build build-asan -j"$(nproc)"
cd build-asan
# halt on the first report; plug-ins stay loaded until exit, so leak reports
# name real leaks
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:halt_on_error=1:strict_string_checks=1"
# fontconfig's process-wide caches are not ours (scripts/lsan.supp)
export LSAN_OPTIONS="suppressions=$PWD/../scripts/lsan.supp"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export OMP_NUM_THREADS=1
export OMP_WAIT_POLICY=PASSIVE  # the tests that set 2 threads sleep, not spin, beside the others
# the unit tests; the coarse validation cases (validate_*_quick) and the
# static cantilever solves (hundreds of thousands of steps on the same bond
# code the quick bonded tests run) are physics runs that take an hour under
# ASan and add run time, not coverage
ctest --output-on-failure -j"$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)" --timeout 1800 -E '^validate_.*_quick$|cantilever' ${1:+-R "$1"}
