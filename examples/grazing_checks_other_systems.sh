#!/usr/bin/env bash
# Every grazing's prediction checked against brute-force sweeps on systems
# besides the paper's (docs/continuation.md, "What a grazing will do", the
# tables after the paper's): `impactkit diagram --grazings` on the 3-mass chain
# examples/systems/three-mass.toml over Ω 0.3-0.7 (81 grazings), on one mass
# in the symmetric clearance examples/systems/clearance-1dof.toml (two stops)
# over Ω 0.6-2.2 (23 grazings), and on the sticking chain of
# examples/systems/paper-mass1-stop.toml over Ω 0.14-0.2 (11 grazings of
# sticking families). Prints one check line per grazing and writes each
# diagram's JSON and its checks' JSON; about 3 minutes on 2 cores, most of
# it the 3-mass chain's (the clearance's takes about 13 s, the sticking
# chain's 30-70 s).
#
#   examples/grazing_checks_other_systems.sh [impactkit binary] [data folder]
#
# Defaults: ./build/apps/impactkit, ./out/grazing-checks.
set -euo pipefail
impactkit=${1:-./build/apps/impactkit}
data=${2:-./out/grazing-checks}
systems=$(cd "$(dirname "$0")/systems" && pwd)
mkdir -p "$data"

echo "three-mass.toml, omega 0.3-0.7:"
"$impactkit" diagram --system "$systems/three-mass.toml" --from 0.3 --to 0.7 \
  --json "$data/three-mass-diagram.json" --grazings "$data/three-mass-grazings.json" |
  sed -n '/^grazings checked/,$p'

echo "clearance-1dof.toml, omega 0.6-2.2:"
"$impactkit" diagram --system "$systems/clearance-1dof.toml" --from 0.6 --to 2.2 \
  --json "$data/clearance-diagram.json" --grazings "$data/clearance-grazings.json" |
  sed -n '/^grazings checked/,$p'

echo "paper-mass1-stop.toml, omega 0.14-0.2:"
"$impactkit" diagram --system "$systems/paper-mass1-stop.toml" --from 0.14 --to 0.2 \
  --json "$data/sticking-diagram.json" --grazings "$data/sticking-grazings.json" |
  sed -n '/^grazings checked/,$p'
