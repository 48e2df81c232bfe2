#!/usr/bin/env bash
# Regenerates Wagg & Bishop (2001) Fig. 10: return maps v(j) -> v(j+1) of
# low-velocity impacts, (a) v < 0.3 at Ω = 1.72, with the least-squares fit
# of the square-root map (Eq. 18) drawn over it and reported; (b) v < 0.22
# at Ω = 1.75. From rest, 500 periods discarded, 20000 recorded.
#
#   examples/fig10_return_maps.sh [impactkit binary] [figure folder] [data folder]
#
# Defaults: ./build/apps/impactkit, ./out/figures, ./out/maps.
set -euo pipefail
impactkit=${1:-./build/apps/impactkit}
figures=${2:-./out/figures}
data=${3:-./out/maps}
mkdir -p "$figures" "$data"
echo "Fig. 10(a), and the Eq. 18 fit over all its points:"
"$impactkit" returnmap --omega 1.72 --bound 0.3 --periods 20000 --fit \
  --out "$data/fig10a.csv" --json "$data/fig10a_fit.json" --plot "$figures/fig10a_return_map.png"
echo "The fit over the one-dimensional part only, v(j) < 0.2:"
"$impactkit" returnmap --omega 1.72 --bound 0.3 --periods 20000 --fit --fit-to 0.2 \
  --json "$data/fig10a_fit_below_0.2.json" | grep -A1 '^fit'
echo "Fig. 10(b):"
"$impactkit" returnmap --omega 1.75 --bound 0.22 --periods 20000 \
  --out "$data/fig10b.csv" --plot "$figures/fig10b_return_map.png"
