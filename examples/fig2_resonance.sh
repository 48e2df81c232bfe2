#!/usr/bin/env bash
# Regenerates Wagg & Bishop (2001) Fig. 2: resonance curves of the paper's
# system without its stop (max-min displacement of x1, x2 against Ω), from
# the closed form, and prints the peaks.
#
#   examples/fig2_resonance.sh [impactkit binary] [figure folder] [data folder]
#
# Defaults: ./build/apps/impactkit, ./out/figures, ./out/maps.
set -euo pipefail
impactkit=${1:-./build/apps/impactkit}
figures=${2:-./out/figures}
data=${3:-./out/maps}
mkdir -p "$figures" "$data"
"$impactkit" resonance --from 0.1 --to 2.5 --steps 2401 \
  --out "$data/fig2.csv" --plot "$figures/fig2_resonance.png"
