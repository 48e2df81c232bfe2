#!/usr/bin/env bash
# Builds impactkit, then runs the main job on the paper's system, everything
# into ./out/paper/: `impactkit paper` (modal data, resonance peaks, orbits,
# the Fig. 3 regimes, the connected diagram of every branch with its special points) and
# every examples/fig*.sh, each called alike — binary, figure folder, data
# folder — so that the paper's Figs. 2-12 land in out/paper/figures/ and
# their CSV/JSON in out/paper/data/; then examples/parameter_maps.sh, the
# (Ω, r) and (Ω, xs) maps and two basin pictures (docs/grids.md), a few
# minutes more.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh
impactkit=./build/apps/impactkit
out=out/paper
start=$SECONDS
mkdir -p "$out"
echo
"$impactkit" paper --out "$out"
# In figure order (fig2 ... fig12), not the glob's (fig10 before fig2).
for script in $(printf '%s\n' examples/fig*.sh | sort -V); do
  echo
  echo "== $script"
  bash "$script" "$impactkit" "$out/figures" "$out/data"
done
# The same Fig. 3 and P(1,1) branch from Python (docs/python.md), when the
# module was built (it needs pybind11, which setup.sh installs).
if compgen -G "build/python/impactkit/_impactkit*.so" > /dev/null; then
  for script in examples/python/*.py; do
    name=$(basename "$script" .py)
    echo
    echo "== $script"
    PYTHONPATH=build/python /usr/bin/python3 "$script" "$out/figures/${name}_python.png" |
      sed 's/^/    /'
  done
fi
echo
echo "== examples/parameter_planes.sh"
bash examples/parameter_planes.sh "$impactkit" "$out/figures" "$out/data"
echo "== examples/parameter_maps.sh"
bash examples/parameter_maps.sh "$impactkit" "$out/figures" "$out/data"
echo
echo "Results in $(pwd)/$out/ ($((SECONDS - start)) s after the build):"
echo "  summary.json      the summary above: modes, peaks, orbits, branches, regimes"
echo "  branch-*.csv      the paper's three branches, one row per point (every branch's"
echo "                    with \`impactkit paper --all-branches\`; diagram.json holds them all)"
echo "  fig3-sweep.csv    the Fig. 3 sweep, one row per value"
echo "  *.png             Figs. 2 and 3 and the connected diagram (diagram.png, the result:"
echo "                    seeded by the paper's orbits and the sweep; figures/continuation-"
echo "                    diagram.png is examples/fig5_continuation.sh's, seeded by a sweep alone)"
echo "  figures/          the paper's Figs. 2-12 from examples/fig*.sh, the parameter"
echo "                    planes plane-*.png and the cusp cusp-p74-r.png from"
echo "                    examples/parameter_planes.sh, the maps"
echo "                    from examples/parameter_maps.sh and *_python.png from examples/python/"
echo "  data/             their CSV and JSON"
