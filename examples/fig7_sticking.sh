#!/usr/bin/env bash
# Regenerates Wagg & Bishop (2001) Fig. 7, the chatter and sticking region:
# the impact speeds of `impactkit sweep` over the paper's axis, Ω from 0.1 to
# 0.6 in 501 values (ΔΩ = 0.001), 500 discarded and 100 recorded forcing
# periods at each, each value from the previous one's final state. Panel (b)
# of the PNG is Fig. 7; panel (a) gives the max - min of x2 beside it.
# Prints the ranges of Ω over which each P(p,q) is found.
#
#   examples/fig7_sticking.sh [impactkit binary] [figure folder] [data folder]
#
# Defaults: ./build/apps/impactkit, ./out/figures, ./out/sweep. Needs gnuplot.
set -euo pipefail
impactkit=${1:-./build/apps/impactkit}
figures=${2:-./out/figures}
data=${3:-./out/sweep}
mkdir -p "$figures" "$data"

"$impactkit" sweep --param omega --from 0.1 --to 0.6 --steps 501 --transient 500 --record 100 \
  --out "$data/fig7-impacts.csv" --summary "$data/fig7-summary.csv" \
  --plot "$figures/fig7_sticking.png" | sed 's/^/    /'
# Runs of equal motion: first and last Ω of each.
echo "motions (first Ω - last Ω: kind P(p,q)):"
awk -F, 'NR > 2 {
  label = $2 ($3 == "nan" ? "" : " P(" $3 "," $4 ")")
  if (label != last) { if (NR > 3) printf "    %s - %s: %s\n", first, prev, last; first = $1; last = label }
  prev = $1 }
  END { printf "    %s - %s: %s\n", first, prev, last }' "$data/fig7-summary.csv"
