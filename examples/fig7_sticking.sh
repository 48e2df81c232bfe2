#!/usr/bin/env bash
# Regenerates Wagg & Bishop (2001) Fig. 7, the chatter and sticking region:
# the impact speeds of `impactkit sweep` over the paper's axis, Ω from 0.1 to
# 0.6 in 501 values (ΔΩ = 0.001), 500 discarded and 100 recorded forcing
# periods at each, each value from the previous one's final state. Panel (b)
# of the PNG is Fig. 7; panel (a) gives the max - min of x2 beside it.
# Prints the ranges of Ω over which each P(p,q) is found. Then the same
# range by branches, drawn over the sweep: fig7_branches.png.
#
#   examples/fig7_sticking.sh [impactkit binary] [figure folder] [data folder]
#
# Defaults: ./build/apps/impactkit, ./out/figures, ./out/sweep. Needs gnuplot.
set -euo pipefail
impactkit=${1:-./build/apps/impactkit}
figures=${2:-./out/figures}
data=${3:-./out/sweep}
mkdir -p "$figures" "$data"

"$impactkit" sweep --param omega --from 0.1 --to 0.6 --steps 501 --transient 500 --record 100 \
  --out "$data/fig7-impacts.csv" --summary "$data/fig7-summary.csv" \
  --plot "$figures/fig7_sticking.png" | sed 's/^/    /'
# Runs of equal motion: first and last Ω of each.
echo "motions (first Ω - last Ω: kind P(p,q)):"
# (Line 1 is the header, then the provenance comments, then the rows.)
awk -F, '!/^#/ && ++row > 1 {
  label = $2 ($3 == "" ? "" : " P(" $3 "," $4 ")")
  if (label != last) { if (row > 2) printf "    %s - %s: %s\n", first, prev, last; first = $1; last = label }
  prev = $1 }
  END { printf "    %s - %s: %s\n", first, prev, last }' "$data/fig7-summary.csv"

# The same range covered by branches (docs/continuation.md, "Sticking
# branches"): the sticking family P(inf,1) from Ω = 0.1 to where its chatter
# stops ending in sticking (its first, fastest impact), and above it the
# chatter orbits P(n,1), each continued from the steady motion at a few Ω
# values with --follow-grazing (one impact more or fewer at each grazing),
# drawn over the brute-force impact speeds: fig7_branches.png.
"$impactkit" continue --from 0.1 --to 0.6 --out "$data/fig7-sticking-branch.csv" |
  grep -E '^(branch|  )' | sed 's/^/    /'
branches=()
for start in 0.307 0.308 0.309 0.31 0.316 0.32 0.33 0.35 0.4 0.45 0.5 0.55; do
  if "$impactkit" continue --from "$start" --to 0.6 --follow-grazing \
    --out "$data/fig7-branch-$start.csv" >"$data/fig7-branch-$start.txt"; then
    grep -E '^branch' "$data/fig7-branch-$start.txt" | sed 's/^/    /'
    branches+=("$data"/fig7-branch-"$start"*.csv)
  else
    echo "    no branch from Ω = $start"
  fi
done
# One gnuplot term per impact-speed column v1, v2, ... of each branch file.
terms="'$data/fig7-impacts.csv' using 1:4 with points pt 7 ps 0.25 lc rgb '#555555' title 'simulation (sweep)'"
# Its columns impact_velocity1 (the first impact after the release) and stable, by name.
sticking_columns=$(grep -m1 -v '^#' "$data/fig7-sticking-branch.csv" | tr ',' '\n' | grep -n '')
v1=$(grep ':impact_velocity1$' <<<"$sticking_columns" | cut -d: -f1)
stable=$(grep ':stable$' <<<"$sticking_columns" | cut -d: -f1)
terms+=", '$data/fig7-sticking-branch.csv' using 1:(\$$stable > 0 ? \$$v1 : 1/0) with lines lw 2"
terms+=" lc rgb '#d62728' title 'sticking P(inf,1): first impact'"
first=1
for file in "${branches[@]}"; do
  header=$(head -1 "$file" | tr ',' '\n')
  while read -r column name; do
    [[ $name =~ ^v[0-9]+$ ]] || continue
    title=$([[ $first == 1 ]] && echo "P(n,1) branches (impact map)" || echo "")
    terms+=", '$file' using 1:$column with lines lw 1.5 lc rgb '#1f77b4' title '$title'"
    first=0
  done < <(nl -w1 -s' ' <<<"$header")
done
gnuplot <<GNUPLOT
set terminal pngcairo size 1100,700
set output '$figures/fig7_branches.png'
set datafile separator ','
set key top right
set xlabel 'Ω'
set ylabel 'impact velocity v2'
set xrange [0.1:0.6]
set yrange [0:*]
plot $terms
GNUPLOT
echo "    wrote $figures/fig7_branches.png"
