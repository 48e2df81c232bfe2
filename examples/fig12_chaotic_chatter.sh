#!/usr/bin/env bash
# Wagg & Bishop (2001) Fig. 12 shows "chaotic chatter" between the chaotic
# attractor at Ω = 1.72 and the P(4,4) at Ω = 1.725. This draws the time
# series at Ω = 1.7225 (mid-range) and counts, over 1.7205..1.7245, the
# chatter sequences the simulator ends (see docs/maps.md for what we find).
#
#   examples/fig12_chaotic_chatter.sh [impactkit binary] [figure folder] [data folder]
#
# Defaults: ./build/apps/impactkit, ./out/figures, ./out/maps.
set -euo pipefail
impactkit=${1:-./build/apps/impactkit}
figures=${2:-./out/figures}
data=${3:-./out/maps}
mkdir -p "$figures" "$data"
for w in 1.7205 1.721 1.7215 1.722 1.7225 1.723 1.7235 1.724 1.7245; do
  echo "Ω = $w: $("$impactkit" impactmap --omega "$w" --periods 2000 | sed -n 's/^run: *.*recorded: //p')"
done
"$impactkit" simulate --omega 1.7225 --transient 1000 --periods 20 \
  --series "$data/fig12.csv" --plot "$figures/fig12_chaotic_chatter.png" | sed 's/^/    /'
