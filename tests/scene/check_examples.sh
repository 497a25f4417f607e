#!/usr/bin/env bash
# `plab check` on every example and validation scene: each loads and is
# described without a step (exit 0, the timestep and the commands named).
set -euo pipefail
plab=$1
root=$2
failed=0
count=0
while IFS= read -r scene; do
  count=$((count + 1))
  if ! out=$("$plab" check "$scene" --out /tmp/plab_check_unused 2>&1) || ! grep -q "^timestep: " <<<"$out" || ! grep -q "^commands:" <<<"$out"; then
    echo "FAIL $scene"; echo "$out" | tail -3; failed=$((failed + 1))
  fi
done < <(find "$root/examples" "$root/validation" -name '*.json' ! -name case.json | sort)
echo "$count scenes checked, $failed failed"
[ "$count" -gt 20 ] && [ "$failed" -eq 0 ]
