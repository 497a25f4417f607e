#!/usr/bin/env bash
# One command: install what is missing, build, and run every test (Catch2
# unit, contract, physics and the coarse validation cases) through CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
cd build
ctest --output-on-failure -j"$(nproc)" --timeout 900
