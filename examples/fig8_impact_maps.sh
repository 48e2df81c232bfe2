#!/usr/bin/env bash
# Regenerates Wagg & Bishop (2001) Fig. 8: impact maps (phase at impact
# against impact speed) of the paper's system over its chaotic range, at the
# twelve Ω of the paper's text, each from rest after 500 discarded periods,
# 5000 periods recorded; prints each Ω's largest Lyapunov exponent beside it.
#
#   examples/fig8_impact_maps.sh [impactkit binary] [figure folder] [data folder]
#
# Defaults: ./build/apps/impactkit, ./out/figures, ./out/maps. Needs gnuplot.
set -euo pipefail
impactkit=${1:-./build/apps/impactkit}
figures=${2:-./out/figures}
data=${3:-./out/maps}
mkdir -p "$figures" "$data"
omegas="1.70 1.701 1.71 1.715 1.72 1.725 1.74 1.75 1.77 1.79 1.81 1.82"

for w in $omegas; do
  "$impactkit" impactmap --omega "$w" --transient 500 --periods 5000 --out "$data/fig8_$w.csv" \
    >/dev/null
  largest=$("$impactkit" lyapunov --omega "$w" --impacts 4000 | sed -n 's/^largest: *\([^ ]*\).*/\1/p')
  echo "Ω = $w: $(($(grep -vc '^#' "$data/fig8_$w.csv") - 1)) impacts, largest Lyapunov exponent $largest"
done

# One panel per Ω, 4 rows of 3, as the paper lays them out.
{
  echo 'set terminal pngcairo size 1500,1600 font "Sans,10"'
  echo "set output '$figures/fig8_impact_maps.png'"
  echo 'set datafile separator ","'
  echo 'set multiplot layout 4,3 title "Impact maps: phase at impact (t mod T) vs impact velocity v2"'
  echo 'unset key'
  for w in $omegas; do
    echo "set title 'Ω = $w'; set xlabel 'phase'; set ylabel 'v2'"
    echo "plot '$data/fig8_$w.csv' every ::1 using 2:3 with points pointtype 7 pointsize 0.15 linecolor rgb '#1f4e9a'"
  done
  echo 'unset multiplot'
} | gnuplot
echo "wrote $figures/fig8_impact_maps.png"
