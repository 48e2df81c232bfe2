#!/usr/bin/env bash
# Regenerates Wagg & Bishop (2001) Fig. 9: close-ups of impact maps, the
# paper's (a) "medium" velocity set at Ω = 1.701, (b) the high-velocity
# region at Ω = 1.715, (c) the "high" velocity set at Ω = 1.72. Velocity
# bands: medium 0.28 < v < 0.65, high v > 0.28 (read off our Fig. 8); long
# runs (20000 periods) from rest after 500 discarded.
#
#   examples/fig9_impact_map_details.sh [impactkit binary] [figure folder] [data folder]
#
# FIG9_PERIODS (default 20000) shortens the recorded runs for a quick look.
#
# Defaults: ./build/apps/impactkit, ./out/figures, ./out/maps. Needs gnuplot.
set -euo pipefail
here=$(dirname "$0")
impactkit=${1:-./build/apps/impactkit}
figures=${2:-./out/figures}
data=${3:-./out/maps}
mkdir -p "$figures" "$data"

# panel  Ω      v band
panels="a 1.701 0.28 0.65
b 1.715 0.28 10
c 1.72 0.28 10"
{
  echo 'set terminal pngcairo size 1500,500 font "Sans,10"'
  echo "set output '$figures/fig9_impact_map_details.png'"
  echo 'set datafile separator ","'
  echo 'set multiplot layout 1,3'
  echo 'unset key'
  while read -r panel w lo hi; do
    "$impactkit" impactmap --omega "$w" --transient 500 --periods ${FIG9_PERIODS:-20000} \
      --out "$data/fig9$panel.csv" >/dev/null
    band="((\$3 > $lo && \$3 < $hi) ? \$3 : 1/0)"
    echo "set title '($panel) Ω = $w, $lo < v2 < $hi'; set xlabel 'phase'; set ylabel 'v2'"
    echo "call '$here/gnuplot/single_value_axis.gp' 'x' '$data/fig9$panel.csv' '((\$3 > $lo && \$3 < $hi) ? \$2 : 1/0)'"
    echo "call '$here/gnuplot/single_value_axis.gp' 'y' '$data/fig9$panel.csv' '$band'"
    echo "plot '$data/fig9$panel.csv' every ::1 using 2:$band with points pointtype 7 pointsize 0.1 linecolor rgb '#1f4e9a'"
  done <<<"$panels"
  echo 'unset multiplot'
} | gnuplot
echo "wrote $figures/fig9_impact_map_details.png"
