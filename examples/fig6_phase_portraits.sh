#!/usr/bin/env bash
# Regenerates Wagg & Bishop (2001) Fig. 6: phase portraits (x, v) of the
# large-amplitude motions at Ω = 0.82 (P(2,1)), 1.17 (P(1,1)) and 1.69
# (P(4,4)); solid x2, dashed x1, the stop at xs marked.
#
#   examples/fig6_phase_portraits.sh [impactkit binary] [figure folder] [data folder]
#
# Defaults: ./build/apps/impactkit, ./out/figures, ./out/fig6. Needs gnuplot.
set -euo pipefail
impactkit=${1:-./build/apps/impactkit}
figures=${2:-./out/figures}
data=${3:-./out/fig6}
mkdir -p "$figures" "$data"

for panel in "a 0.82" "b 1.17" "c 1.69"; do
  read -r name omega <<<"$panel"
  # 500 periods of transient, 9 recorded: enough to confirm P(4,4) (2q + 1 periods).
  "$impactkit" simulate --omega "$omega" --transient 500 --periods 9 --samples-per-period 400 \
    --series "$data/fig6$name.csv" | sed -n 's/^motion: */    Fig. 6('"$name"'), Ω = '"$omega"': /p'
  gnuplot <<GNUPLOT
set terminal pngcairo size 700,600 noenhanced
set output '$figures/fig6$name.png'
set datafile separator ','
set title 'Fig. 6($name): phase portrait, Ω = $omega'
set xlabel 'displacement'
set ylabel 'velocity'
set arrow from 0.1, graph 0 to 0.1, graph 1 nohead dt 3 lc rgb '#888888'
plot '$data/fig6$name.csv' using 3:5 with lines lw 2 lc rgb '#1f77b4' title 'x2', \
     '' using 2:4 with lines lw 1 lc rgb '#d62728' title 'x1'
GNUPLOT
done
echo "wrote: $figures/fig6a.png $figures/fig6b.png $figures/fig6c.png"
