#!/usr/bin/env bash
# Systems with several stops (docs/several-stops.md):
#  - the paper's system with mass 2 in a clearance of 0.2 around its
#    equilibrium (examples/systems/paper-two-stops.toml): the Fig. 3 style
#    sweep in Ω, and the time series of its P(6,1) at Ω = 0.8;
#  - one mass between two stops at ±0.5 (examples/systems/clearance-1dof.toml):
#    the connected diagram over Ω 0.8-1.8 — the symmetric P(2,1), its two
#    symmetry-breaking pitchforks and the asymmetric P(2,1) between them,
#    grazing both stops, and what branches off.
#
#   examples/several_stops.sh [impactkit binary] [figure folder] [data folder]
#
# Defaults: ./build/apps/impactkit, ./out/figures, ./out/stops. Needs
# gnuplot.
set -euo pipefail
impactkit=${1:-./build/apps/impactkit}
figures=${2:-./out/figures}
data=${3:-./out/stops}
mkdir -p "$figures" "$data"
two_stops=examples/systems/paper-two-stops.toml
clearance=examples/systems/clearance-1dof.toml

echo "== the paper's system in a clearance: sweep in omega"
"$impactkit" sweep --system "$two_stops" --from 0.3 --to 2.5 --steps 441 \
  --out "$data/two-stops-sweep.csv" --plot "$figures/two-stops-sweep.png"
echo "== its P(6,1) at omega = 0.8"
"$impactkit" simulate --system "$two_stops" --omega 0.8 --periods 3 \
  --impacts "$data/two-stops-impacts.csv" --plot "$figures/two-stops-series.png"
"$impactkit" orbit --system "$two_stops" --omega 0.8 --json "$data/two-stops-orbit.json"
echo "== one mass between two stops: the connected diagram"
"$impactkit" diagram --system "$clearance" --from 0.8 --to 1.8 \
  --json "$data/clearance-diagram.json" --plot "$figures/clearance-diagram.png"
