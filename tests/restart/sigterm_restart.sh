#!/usr/bin/env bash
# A run killed with SIGTERM mid-way stops after its current step, writes a
# checkpoint and its outputs, exits 143 and says how to continue; `plab
# restart` then finishes it with the same final state hash, history and VTK
# series as a run that was never killed (issue 9, acceptance 2). SIGHUP (a
# closed terminal) and SIGINT stop it the same way, with 128 + their number.
#   sigterm_restart.sh PLAB_EXE SCENE WORK_DIR [SIGNAL (TERM)]
set -euo pipefail
plab=$1 scene=$2 work=$3 signal=${4:-TERM}
expected=$((128 + $(kill -l "$signal")))
rm -rf "$work" && mkdir -p "$work"
hash_of() { sed -n 's/.*"state_hash": "\([0-9a-f]*\)".*/\1/p' "$1/summary.json"; }

"$plab" run "$scene" --out "$work/whole" --quiet --checkpoint-every 0.05
"$plab" run "$scene" --out "$work/cut" --quiet --checkpoint-every 0.05 2>"$work/cut.err" &
pid=$!
# kill it once it is under way: after its first periodic checkpoint
for _ in $(seq 1 3000); do
  [ -e "$work/cut/checkpoint.plab" ] && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.01
done
kill -"$signal" "$pid"
set +e; wait "$pid"; rc=$?; set -e
cat "$work/cut.err"
[ "$rc" -eq "$expected" ] || { echo "FAIL: the killed run exited $rc, expected $expected (128 + SIG$signal)"; exit 1; }
grep -q "plab restart $work/cut/checkpoint.plab" "$work/cut.err" || { echo "FAIL: no 'plab restart' hint"; exit 1; }
killed_at=$(sed -n 's/.*"steps": \([0-9]*\).*/\1/p' "$work/cut/summary.json")
total=$(sed -n 's/.*"steps": \([0-9]*\).*/\1/p' "$work/whole/summary.json")
echo "killed at step $killed_at of $total"
[ "$killed_at" -lt "$total" ] || { echo "FAIL: the run ended before the signal"; exit 1; }

"$plab" restart "$work/cut/checkpoint.plab" --quiet
whole=$(hash_of "$work/whole") restarted=$(hash_of "$work/cut")
echo "state hash: uninterrupted $whole, killed + restarted $restarted"
[ -n "$whole" ] && [ "$whole" = "$restarted" ] || { echo "FAIL: state hashes differ"; exit 1; }
cmp "$work/whole/history.csv" "$work/cut/history.csv" || { echo "FAIL: histories differ"; exit 1; }
cmp "$work/whole/series.pvd" "$work/cut/series.pvd" || { echo "FAIL: VTK series differ"; exit 1; }
echo "PASS"
