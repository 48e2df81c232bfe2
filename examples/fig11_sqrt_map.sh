#!/usr/bin/env bash
# Draws Wagg & Bishop (2001) Fig. 11: the one-dimensional square-root map of
# Eq. 18 for s = d = 1, λ = 0.2, in the form map_fit.hpp fits:
#   X' = s sqrt(d - X) + λ X  (X <= d),   X' = λ X  (X > d),
# with the diagonal X' = X. A formula, so gnuplot draws it directly.
#
#   examples/fig11_sqrt_map.sh [impactkit binary] [figure folder] [data folder]
#
# Defaults: ./out/figures; the binary and the data folder are unused (a
# formula needs neither), taken so that every figure script is called alike.
# Needs gnuplot.
set -euo pipefail
figures=${2:-./out/figures}
mkdir -p "$figures"
gnuplot <<GP
set terminal pngcairo size 700,600 font "Sans,11"
set output '$figures/fig11_sqrt_map.png'
s = 1; d = 1; lambda = 0.2
f(x) = x <= d ? s * sqrt(d - x) + lambda * x : lambda * x
set samples 2001
set xrange [0:2]; set yrange [0:1.2]
set xlabel 'X_n'; set ylabel 'X_{n+1}'
set title 'Eq. 18, s = d = 1, lambda = 0.2'
set key top right
plot f(x) title 'X_{n+1}' linewidth 2 linecolor rgb '#1f4e9a', x title 'X_{n+1} = X_n' dashtype 2 linecolor rgb '#888888'
GP
echo "wrote $figures/fig11_sqrt_map.png"
