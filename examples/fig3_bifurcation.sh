#!/usr/bin/env bash
# Regenerates Wagg & Bishop (2001) Fig. 3 with `impactkit sweep`: Ω from 0.1
# to 2.5 in 2401 values (ΔΩ = 0.001), 500 discarded and 100 recorded forcing
# periods at each, each value from the previous one's final state; (a) the
# max - min of x2 in every recorded period, (b) every recorded impact speed.
# Prints how many values of each kind the classification found. The data
# kept is the summary, one row per value (fig3-summary.csv); add
# `--out FILE.csv` to the sweep for every recorded impact, a table of
# tens of megabytes.
#
#   examples/fig3_bifurcation.sh [impactkit binary] [figure folder] [data folder]
#
# Defaults: ./build/apps/impactkit, ./out/figures, ./out/sweep. Needs gnuplot.
set -euo pipefail
impactkit=${1:-./build/apps/impactkit}
figures=${2:-./out/figures}
data=${3:-./out/sweep}
mkdir -p "$figures" "$data"

"$impactkit" sweep --param omega --from 0.1 --to 2.5 --steps 2401 --transient 500 --record 100 \
  --summary "$data/fig3-summary.csv" \
  --plot "$figures/fig3_sweep.png" | sed 's/^/    /'
echo "kinds (values):"
grep -v '^#' "$data/fig3-summary.csv" | tail -n +2 | cut -d, -f2 | sort | uniq -c | sed 's/^/    /'
