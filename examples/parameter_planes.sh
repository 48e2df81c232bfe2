#!/usr/bin/env bash
# The paper system's parameter planes (Ω, r) and (Ω, xs), as vibro-impact
# papers draw them: P(1,1)'s period-doubling curve and lower grazing curve
# (a new contact), P(1,2)'s fold and period-doubling curves, each followed
# by `impactkit curve` from the point that continuation in Ω finds at the
# paper's r = 0.7, xs = 0.1; the region where P(1,1) exists and is stable
# (between its grazing and its period doubling) shaded; where P(1,q)'s
# impact vanishes (the non-impacting response touches the stop); the
# codimension-two points found marked. Then a cusp: P(7,4)'s fold curve in
# (Ω, r), which turns back where two folds of the branch in Ω meet.
# docs/continuation.md describes them.
#
#   examples/parameter_planes.sh [impactkit binary] [figure folder] [data folder]
#
# Defaults: ./build/apps/impactkit, ./out/figures, ./out/curves. The
# figures are plane-r.png, plane-xs.png and cusp-p74-r.png; each curve's
# CSV and JSON (docs/curves-json.md) are data. Needs gnuplot.
set -euo pipefail
impactkit=${1:-./build/apps/impactkit}
figures=${2:-./out/figures}
data=${3:-./out/curves}
mkdir -p "$figures" "$data"

# plane SECOND FROM2 TO2: the four curves in (omega, SECOND).
plane() {
  local second=$1 from2=$2 to2=$3
  local common=(--param omega --param2 "$second" --from 0.5 --to 3 --from2 "$from2" --to2 "$to2")
  "$impactkit" curve --type period_doubling --p 1 --q 1 --omega 1.6 "${common[@]}" \
    --out "$data/pd11-$second.csv" --json "$data/pd11-$second.json"
  "$impactkit" curve --type grazing --p 1 --q 1 --omega 1.0 "${common[@]}" \
    --out "$data/graze11-$second.csv" --json "$data/graze11-$second.json"
  "$impactkit" curve --type fold --p 1 --q 2 --omega 2.0 "${common[@]}" \
    --out "$data/fold12-$second.csv" --json "$data/fold12-$second.json"
  "$impactkit" curve --type period_doubling --p 1 --q 2 --omega 2.0 "${common[@]}" \
    --out "$data/pd12-$second.csv" --json "$data/pd12-$second.json"
  # Where P(1,1)'s (and P(1,2)'s) impact vanishes: the non-impacting
  # response touches the stop (the upper end of P(1,1)'s branch).
  "$impactkit" curve --type grazing --p 1 --q 2 --omega 2.0 "${common[@]}" \
    --out "$data/response-$second.csv" --json "$data/response-$second.json"
  # P(1,1) stable: between its grazing and its period doubling, both
  # curves running from FROM2 to TO2 (the polygon closes along the bounds).
  {
    grep -v '^#' "$data/graze11-$second.csv" | tail -n +2 | cut -d, -f1,2
    grep -v '^#' "$data/pd11-$second.csv" | tail -n +2 | cut -d, -f1,2 | tac
  } >"$data/stable11-$second.csv"
  # The codimension-two points: rows whose last column names one (labels
  # alternate sides: neighbours can be close).
  local codim2=""
  cat "$data"/*11-"$second".csv "$data"/*12-"$second".csv | grep -v '^#' |
    awk -F, '$NF ~ /[a-z]/ && $1 != "omega"' >"$data/codim2-$second.csv"
  if [[ -s $data/codim2-$second.csv ]]; then
    codim2="'$data/codim2-$second.csv' using 1:2 with points pt 7 ps 1.5 lc rgb '#2ca02c' title 'codimension two', \
      '$data/codim2-$second.csv' every 2 using 1:2:(stringcolumn(9)) with labels offset -1,1 right notitle, \
      '$data/codim2-$second.csv' every 2::1 using 1:2:(stringcolumn(9)) with labels offset 1,-1 left notitle"
  fi
  gnuplot <<GNUPLOT
set terminal pngcairo size 1000,700 noenhanced
set output '$figures/plane-$second.png'
set datafile separator ','
set xlabel 'Ω'
set ylabel '$second'
set key outside bottom center horizontal
set title 'Paper system: P(1,1) and P(1,2) bifurcation curves in (Ω, $second)'
plot '$data/stable11-$second.csv' using 1:2 with filledcurves closed fc rgb '#cce5ff' title 'P(1,1) stable', \
  '$data/graze11-$second.csv' using 1:2 with lines lw 2 dt 2 lc rgb '#000000' title 'P(1,1) grazing', \
  '$data/pd11-$second.csv' using 1:2 with lines lw 2 lc rgb '#d62728' title 'P(1,1) period doubling', \
  '$data/fold12-$second.csv' using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'P(1,2) fold', \
  '$data/pd12-$second.csv' using 1:2 with lines lw 2 lc rgb '#ff7f0e' title 'P(1,2) period doubling', \
  '$data/response-$second.csv' using 1:2 with lines lw 2 dt 3 lc rgb '#7f7f7f' title 'impact of P(1,q) vanishes'${codim2:+, $codim2}
GNUPLOT
  echo "wrote: $figures/plane-$second.png"
}

plane r 0.3 0.95
plane xs 0 0.3

# The cusp: P(7,4)'s fold near Ω = 1.6917 at r = 0.7, followed in r. The
# motion from rest at this Ω is not P(7,4), so the orbit is seeded by a
# guess (a P(7,4) orbit of `impactkit diagram`); the fold is located from
# the orbit it converges to.
"$impactkit" curve --type fold --p 7 --q 4 --omega 1.6915 --guess=0.4277,2.1354,-1.2808,0.1051 \
  --param omega --param2 r --from 1.68 --to 1.71 --from2 0.6 --to2 0.95 \
  --out "$data/fold74-r.csv" --json "$data/fold74-r.json" --plot "$figures/cusp-p74-r.png"
