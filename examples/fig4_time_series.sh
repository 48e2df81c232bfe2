#!/usr/bin/env bash
# Regenerates Wagg & Bishop (2001) Fig. 4(a)-(h): time series of the paper's
# system from rest, over the paper's time windows, as PNGs (and CSVs).
#
#   examples/fig4_time_series.sh [impactkit binary] [figure folder] [data folder]
#
# Defaults: ./build/apps/impactkit, ./out/figures, ./out/fig4.
set -euo pipefail
impactkit=${1:-./build/apps/impactkit}
figures=${2:-./out/figures}
data=${3:-./out/fig4}
mkdir -p "$figures" "$data"

# panel  Ω     window start and end as drawn in the paper
panels="a 0.1 680 800
b 0.2 740 800
c 0.4 715 750
d 0.6 450 495
e 0.9 740 760
f 1.4 740 760
g 1.7 760 800
h 2.0 780 800"

while read -r panel omega start end; do
  # Whole forcing periods: discard those before the window, record enough to cover it.
  read -r transient periods < <(awk -v w="$omega" -v a="$start" -v b="$end" 'BEGIN {
    T = 2 * 3.141592653589793 / w; n = int(a / T); m = int((b - n * T) / T) + 1;
    print n, m }')
  echo "Fig. 4($panel): Ω = $omega, periods $transient..$((transient + periods))"
  "$impactkit" simulate --omega "$omega" --transient "$transient" --periods "$periods" \
    --series "$data/fig4$panel.csv" --impacts "$data/fig4$panel-impacts.csv" \
    --plot "$figures/fig4$panel.png" | sed 's/^/    /'
done <<< "$panels"
echo "Figures written to $figures/fig4[a-h].png"
