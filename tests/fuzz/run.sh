#!/usr/bin/env bash
# Fuzzes the scene parser and validator with libFuzzer for a fixed budget.
#   tests/fuzz/run.sh [SECONDS]   (default 600)
# Builds build-fuzz/ (tests/fuzz/build.sh: clang, ASan, UBSan), seeds a
# corpus with every scene in examples/, and runs plab_scene_fuzz under
# ASan/UBSan. Findings (crash-*,
# timeout-*, oom-*) land in build-fuzz/findings/; the corpus it grows stays
# in build-fuzz/corpus/ for the next run.
set -euo pipefail
seconds=${1:-600}
cd "$(dirname "$0")/../.."
root=$PWD
tests/fuzz/build.sh
mkdir -p build-fuzz/corpus build-fuzz/findings
find examples tests/restart -name '*.json' -exec cp {} build-fuzz/corpus/ \;
# a dictionary of every key and string value of the example scenes
python3 - "$root" > build-fuzz/scene.dict <<'PY'
import json, pathlib, sys
words = set()
def walk(v):
    if isinstance(v, dict):
        for k, x in v.items(): words.add(k); walk(x)
    elif isinstance(v, list):
        for x in v: walk(x)
    elif isinstance(v, str) and len(v) < 40: words.add(v)
for p in pathlib.Path(sys.argv[1]).glob("examples/**/*.json"):
    walk(json.loads(p.read_text()))
for w in sorted(words): print(json.dumps(json.dumps(w)))
PY
cd build-fuzz
# 2 GB and 10 s per input: a scene that asks for more must be refused by the
# validator, not attempted
./tests/fuzz/plab_scene_fuzz corpus -dict=scene.dict -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
  -max_len=8192 -artifact_prefix=findings/ -print_final_stats=1
