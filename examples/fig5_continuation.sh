#!/usr/bin/env bash
# The paper's path following (Wagg & Bishop 2001, §3 and Fig. 5(a)), made
# automatic: the P(1,1), P(2,1), P(2,2) and P(1,2) branches continued in Ω
# with their folds, period doublings and grazings, each branch's PNG, and a
# Fig. 5(a)-style overlay of the continued branches (lines: stable solid,
# unstable dashed) on a brute-force sweep (dots); and the connected diagram of
# every branch over Ω 0.1-2.5 seeded by a sweep alone (`impactkit diagram`),
# as a user without the paper's orbits gets it. The study's diagram is
# `impactkit paper`'s diagram.png, seeded by the paper's three orbits as well:
# it holds more branches; each figure's title says how many, from how many
# seeds, and whether a bound cut the network short.
#
#   examples/fig5_continuation.sh [impactkit binary] [figure folder] [data folder]
#
# Defaults: ./build/apps/impactkit, ./out/figures, ./out/continuation. The
# figures are continuation-*.png; the branch CSV/JSON, sweeps and the diagram's
# JSON are data.
# Needs gnuplot.
set -euo pipefail
impactkit=${1:-./build/apps/impactkit}
figures=${2:-./out/figures}
data=${3:-./out/continuation}
mkdir -p "$figures" "$data"

echo "P(1,1) from Ω = 1 both ways, with the P(2,2) branch at its period doubling and"
echo "the P(2,1) branch at its grazing:"
"$impactkit" continue --from 0.5 --to 2.0 --start 1.0 --switch-pd --follow-grazing \
  --out "$data/p11.csv" --json "$data/p11.json" --plot "$figures/continuation-p11.png"
echo
echo "P(2,1) from Ω = 0.6 upwards:"
"$impactkit" continue --from 0.6 --to 1.0 \
  --out "$data/p21.csv" --json "$data/p21.json" --plot "$figures/continuation-p21.png"
echo
echo "P(1,2) from Ω = 2.0 both ways, with the P(2,4) branch at its period doubling:"
"$impactkit" continue --from 1.0 --to 3.0 --start 2.0 --switch-pd \
  --out "$data/p12.csv" --json "$data/p12.json" --plot "$figures/continuation-p12.png"
echo
echo "Brute-force sweeps for the overlay:"
"$impactkit" sweep --from 0.80 --to 0.90 --steps 201 --transient 300 --record 30 \
  --out "$data/sweep-080-090.csv"
"$impactkit" sweep --from 1.55 --to 1.75 --steps 201 --transient 300 --record 30 \
  --out "$data/sweep-155-175.csv"

# Columns of the branch CSVs: omega, arclength, impact_phase1..p, impact_velocity1..p, ..., stable.
plot_branch() {  # file p color -> gnuplot plot clauses (solid stable, dashed unstable)
  local file=$1 p=$2 color=$3 clauses="" i
  local stable=$((2 + 2 * p + 1 + 2 * 2 + 1))  # omega, arclength, phases, vs, range, 4 moduli
  for ((i = 1; i <= p; i++)); do
    local v=$((2 + p + i))
    clauses+="'$file' using 1:(\$$stable == 1 ? \$$v : 1/0) with lines lw 2 lc rgb '$color' notitle, "
    clauses+="'$file' using 1:(\$$stable == 0 ? \$$v : 1/0) with lines lw 2 dt 2 lc rgb '$color' notitle, "
  done
  echo "$clauses"
}

overlay() {  # sweep file, x range, png
  gnuplot <<GNUPLOT
set terminal pngcairo size 1000,600 noenhanced
set output '$3'
set datafile separator ','
set xrange [$2]
set xlabel 'Ω'
set ylabel 'impact velocity v2'
set title 'Continued branches (lines: stable solid, unstable dashed) over brute-force impacts (dots)'
plot '$1' using 1:4 with points pt 7 ps 0.25 lc rgb '#777777' title 'sweep', \
  $(plot_branch "$data/p11.csv" 1 '#1f77b4') \
  $(plot_branch "$data/p11.graze1.csv" 2 '#2ca02c') \
  $(plot_branch "$data/p11.pd2.csv" 2 '#9467bd') \
  1/0 notitle
GNUPLOT
}
overlay "$data/sweep-080-090.csv" "0.80:0.90" "$figures/continuation-overlay-080-090.png"
overlay "$data/sweep-155-175.csv" "1.55:1.75" "$figures/continuation-overlay-155-175.png"
echo "wrote: $figures/continuation-overlay-080-090.png $figures/continuation-overlay-155-175.png"
echo
echo "The connected diagram, Ω 0.1 to 2.5, seeded by a sweep alone (the study's, seeded by"
echo "the paper's orbits as well, is \`impactkit paper\`'s diagram.png):"
"$impactkit" diagram --from 0.1 --to 2.5 --json "$data/diagram.json" \
  --plot "$figures/continuation-diagram.png"
