#!/usr/bin/env bash
# The paper system's parameter planes and basins of attraction (docs/grids.md,
# section "The paper's system") with `impactkit map` and
# `impactkit basins`: the (Ω, r) map over Ω 0.1-2.5, r 0.3-0.95 and the
# (Ω, xs) map over xs 0-0.3, 500 discarded and 100 recorded periods a cell,
# each row from the previous value's final state; the basins at Ω = 1.7 over
# (x1, v1) and at Ω = 2.0 over (x2, v2). Prints each run's class counts and
# attractors.
# The maps draw over their cells the curves examples/parameter_planes.sh
# writes into the same data folder (`impactkit curve --json`: P(1,1)'s period
# doubling and grazing, P(1,2)'s fold and period doubling, where the
# non-impacting response touches the stop), when they are there; scripts/run.sh
# runs that script first.
#
#   examples/parameter_maps.sh [impactkit binary] [figure folder] [data folder]
#
# Defaults: ./build/apps/impactkit, ./out/figures, ./out/maps. Needs gnuplot.
# Under `mpirun`, see docs/grids.md ("Threads, processes, checkpoints").
set -euo pipefail
impactkit=${1:-./build/apps/impactkit}
figures=${2:-./out/figures}
data=${3:-./out/maps}
mkdir -p "$figures" "$data"

# curves SECOND: --curves and every curve file of the (omega, SECOND) plane present.
curves() {
  local files=() name
  for name in pd11 graze11 fold12 pd12 response; do
    [[ -f $data/$name-$1.json ]] && files+=("$data/$name-$1.json")
  done
  ((${#files[@]} == 0)) || echo --curves "${files[@]}"
}

# shellcheck disable=SC2046  # curves: no flag, or a flag and its file
"$impactkit" map --param omega --from 0.1 --to 2.5 --steps 241 --param2 r --from2 0.3 --to2 0.95 \
  --steps2 66 --out "$data/map-omega-r.csv" --json "$data/map-omega-r.json" \
  --plot "$figures/map_omega_r.png" $(curves r) | sed 's/^/    /'
# shellcheck disable=SC2046
"$impactkit" map --param omega --from 0.1 --to 2.5 --steps 241 --param2 xs --from2 0 --to2 0.3 \
  --steps2 61 --out "$data/map-omega-xs.csv" --json "$data/map-omega-xs.json" \
  --plot "$figures/map_omega_xs.png" $(curves xs) | sed 's/^/    /'
# Ω = 1.7: P(4,4) and P(12,8) over starts (x1, v1), x2 = v2 = 0.
"$impactkit" basins --omega 1.7 --coord x1 --from -2 --to 2 --steps 100 --coord2 v1 --from2 -2 \
  --to2 2 --steps2 100 --out "$data/basins-1.7.csv" --json "$data/basins-1.7.json" \
  --plot "$figures/basins_omega_1.7.png" | sed 's/^/    /'
# Ω = 2.0: P(1,2) and the non-impacting orbit over (x2, v2) around that
# orbit's state at t = 0 (from `impactkit simulate --set xs=100 --omega 2`).
"$impactkit" basins --omega 2.0 --x0 -0.26711792347284413,0.07971582009399215 \
  --v0 0.17509509957467634,-0.10460953233380528 --coord x2 --from 0.03 --to 0.1 --steps 100 \
  --coord2 v2 --from2 -0.2 --to2 0 --steps2 100 --out "$data/basins-2.0.csv" \
  --json "$data/basins-2.0.json" --plot "$figures/basins_omega_2.0.png" | sed 's/^/    /'
