#!/usr/bin/env bash
# A run killed with SIGKILL (no chance to write anything) keeps its history
# up to its last output interval, and the summary of its last checkpoint;
# its restart removes the temporary file a kill during a write leaves and
# ends with the history and state of a run that was never killed (issue 38,
# item 7).
#   sigkill_history.sh PLAB_EXE SCENE WORK_DIR
set -euo pipefail
plab=$1 scene=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
# a fixed step: history rows every 200 steps are 0.02 s apart; VTK frames
# every 0.05 s; a checkpoint every 0.1 s; ~50 000 steps in all
args=(--set 'timestep={"fixed":1e-4}' --set commands.2.cycle=40000 --quiet --checkpoint-every 0.1)
row_gap=0.02
hash_of() { sed -n 's/.*"state_hash": "\([0-9a-f]*\)".*/\1/p' "$1/summary.json"; }
frames() { grep -c '<DataSet' "$1/series.pvd" 2>/dev/null || true; }

"$plab" run "$scene" "${args[@]}" --out "$work/cut" &
pid=$!
# kill it once it has written ten VTK frames (three files each) and a checkpoint
for _ in $(seq 1 3000); do
  [ -e "$work/cut/checkpoint.plab" ] && [ "$(frames "$work/cut")" -ge 30 ] && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.01
done
kill -KILL "$pid"
set +e; wait "$pid"; rc=$?; set -e
[ "$rc" -eq 137 ] || fail "the run exited $rc before it was killed"
cut=$work/cut
last_frame=$(sed -n 's/.*timestep="\([^"]*\)".*/\1/p' "$cut/series.pvd" | tail -1)
echo "killed after the VTK frame at t = $last_frame s"

[ -s "$cut/history.csv" ] || fail "the killed run left no history.csv"
head -1 "$cut/history.csv" | grep -qx 'time,ke' || fail "history.csv has no header"
last_row=$(tail -1 "$cut/history.csv" | cut -d, -f1)
rows=$(($(wc -l < "$cut/history.csv") - 1))
echo "history.csv: $rows rows, the last at t = $last_row s"
awk -F, -v f="$last_frame" -v g="$row_gap" 'NR > 1 { if (seen && $1 <= prev) bad = 1; prev = $1; seen = 1 }
  END { exit (bad || prev + g < f + 1e-9) }' "$cut/history.csv" ||
  fail "history.csv ends at t = $last_row s, before the last row due by the frame at $last_frame s (or rows repeat)"

[ -s "$cut/summary.json" ] || fail "a checkpoint was written but no summary.json"
grep -q '"finished": false' "$cut/summary.json" || fail "the summary of a killed run says it finished"
echo "summary.json at step $(sed -n 's/.*"steps": \([0-9]*\).*/\1/p' "$cut/summary.json")"

# a kill while the checkpoint was being written would have left this
echo "half a checkpoint" > "$cut/checkpoint.plab.tmp"
"$plab" restart "$cut/checkpoint.plab" --checkpoint-every 0.1 > "$work/restart.log" 2>&1
grep -qF "removed $cut/checkpoint.plab.tmp" "$work/restart.log" || fail "the restart did not say it removed the stale .tmp"
[ ! -e "$cut/checkpoint.plab.tmp" ] || fail "the stale checkpoint.plab.tmp is still there"
[ -z "$(find "$cut" -name '*.tmp')" ] || fail "temporary files left: $(find "$cut" -name '*.tmp')"

"$plab" run "$scene" "${args[@]}" --out "$work/whole"
cmp "$work/whole/history.csv" "$cut/history.csv" || fail "the restarted history differs from the uninterrupted one"
[ "$(hash_of "$work/whole")" = "$(hash_of "$cut")" ] || fail "state hashes differ"
grep -q '"finished": true' "$cut/summary.json" || fail "the restarted run's summary does not say it finished"
echo "PASS"
