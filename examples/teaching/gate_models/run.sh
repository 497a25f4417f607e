#!/bin/sh
# The elastic gate twice, the structure model swapped (linear_pbond, then sph_solid by sph_solid.sets),
# and both tip histories with Antoci's experiment on one plot.
# usage: examples/teaching/gate_models/run.sh [PLAB (build/plab)] [END_TIME s (0.25)] [OUT (runs/gate_models)]
set -e
plab=${1:-build/plab}
end=${2:-0.25}
out=${3:-runs/gate_models}
here=$(dirname "$0")
mkdir -p "$out"
"$plab" run "$here/gate.json" --quiet --out "$out/linear_pbond" --set variables.end_time="$end"
# the swap: every non-comment line of sph_solid.sets is one --set
set --
while IFS= read -r line; do
  case "$line" in ''|'#'*) continue ;; esac
  set -- "$@" --set "$line"
done < "$here/sph_solid.sets"
"$plab" run "$here/gate.json" --quiet --out "$out/sph_solid" --set variables.end_time="$end" "$@"
# the experiment's horizontal points (fsi_etvf digitisation) as a two-column table for plab plot
awk -F, 'BEGIN { print "t,antoci_2007_x" } $1 == "fsi_etvf" && $2 == "x" { print $3 "," $4 }' \
  "$here/../../../validation/reference/antoci_2007_gate_tip.csv" > "$out/antoci_2007_x.csv"
"$plab" plot "$out/linear_pbond/history.csv" "$out/sph_solid/history.csv" --label linear_pbond,sph_solid \
  --y tip_dx --ref "$out/antoci_2007_x.csv" --ref-x t --ref-y antoci_2007_x \
  --title "elastic gate: free end, horizontal" --xlabel "t (s)" --ylabel "x displacement (m)" --out "$out/tip_dx.png"
echo "wrote $out/tip_dx.png"
