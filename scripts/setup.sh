#!/usr/bin/env bash
# One command from a fresh Debian machine: install what is missing, build,
# and run the default scene (the dry granular column collapse, thesis §6.1).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
build/plab run examples/dry_column_collapse.json --out plab_out/dry_column_collapse
