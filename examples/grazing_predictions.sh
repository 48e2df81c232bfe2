#!/usr/bin/env bash
# What each grazing of the paper's connected diagram will do (docs/continuation.md,
# "What a grazing will do"): `impactkit diagram` over Ω 0.4-2.3 computes the
# discontinuity-map normal form at every grazing, predicts the motion past it,
# and with --grazings checks each prediction by two sweeps through the grazing
# (towards the side past it, started on the grazing orbit, and back). Prints one
# line per grazing and writes the checks' JSON; about a minute on 2 cores.
#
#   examples/grazing_predictions.sh [impactkit binary] [data folder]
#
# Defaults: ./build/apps/impactkit, ./out/grazings.
set -euo pipefail
impactkit=${1:-./build/apps/impactkit}
data=${2:-./out/grazings}
mkdir -p "$data"
"$impactkit" diagram --from 0.4 --to 2.3 --json "$data/diagram.json" \
  --grazings "$data/grazings.json" | sed -n '/^grazings checked/,$p'
