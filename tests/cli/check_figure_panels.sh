# Usage: check_figure_panels.sh IMPACTKIT
# Figures fit for the panels of a paper (issue 37), read from the gnuplot
# source that IMPACTKIT_PLOT_SOURCE keeps:
# - two maps that share classes, (Ω, r) and (Ω, xs): every class they share
#   has the same colour in both, and no two classes of one map share one;
# - each map's axes end at its cells (half a grid step beyond the first and
#   last value), also under a curve that runs beyond them, keyed by the
#   overlay's one name "impact of P(1,q) vanishes";
# - the connected diagram of several branch families draws them in more
#   than one colour, a key entry per family, each family's colour the colour
#   of its class in the maps;
# - a basin picture's title names Ω and the coordinates every start shares;
# - the sweep's panels are lettered (a) and (b), with no tool name; axes say Ω.
# Exit 77 (skipped) without gnuplot.
source "$(dirname "$0")/testlib.sh"
impactkit=$1
command -v gnuplot >/dev/null || exit 77

# A curve of `impactkit curve --json` running beyond both maps' Ω range.
cat >"$work/curve.json" <<'JSON'
{"curves": [{"type": "grazing", "p": 0, "q": 1, "params": ["omega", "r"],
  "points": [{"omega": 0.1, "r": 0.55}, {"omega": 3.0, "r": 0.85}]}]}
JSON
export IMPACTKIT_PLOT_SOURCE=$work/source
common=(--param omega --from 0.7 --to 2.1 --steps 15 --transient 200 --record 40 --threads 2)
"$impactkit" map "${common[@]}" --param2 r --from2 0.5 --to2 0.9 --steps2 5 \
  --curves "$work/curve.json" --plot "$work/r.png" >/dev/null || fail "map (omega, r) failed"
"$impactkit" map "${common[@]}" --param2 xs --from2 0.05 --to2 0.15 --steps2 5 \
  --plot "$work/xs.png" >/dev/null || fail "map (omega, xs) failed"

# "name colour" per legend entry of a map's script.
classes() {
  grep -o 'NaN with boxes fillstyle solid 1.0 lc rgb "#[0-9a-f]*" title "[^"]*"' "$1" |
    sed -E 's/.*rgb "(#[0-9a-f]+)" title "(.*)"/\2 \1/' | sort
}
classes "$work/source/1/map.gp" >"$work/r.classes"
classes "$work/source/2/map.gp" >"$work/xs.classes"
shared=$(join "$work/r.classes" "$work/xs.classes")
(($(wc -l <<<"$shared") >= 3)) || fail "the maps share too few classes: $shared"
while read -r name r_color xs_color; do
  [[ $r_color == "$xs_color" ]] || fail "$name is $r_color in one map and $xs_color in the other"
done <<<"$shared"
for map in r xs; do
  [[ $(cut -d' ' -f2 "$work/$map.classes" | sort | uniq -d) == "" ]] ||
    fail "two classes share a colour in the ($map) map: $(cat "$work/$map.classes")"
done

# Axes at the cells: [first - step/2, last + step/2] on both axes.
for n in 1 2; do
  script=$work/source/$n/map.gp
  for axis in x y; do
    column=$([[ $axis == x ]] && echo 1 || echo 2)
    expected=$(awk -v c="$column" '{print $c}' "$work/source/$n/cells.dat" | sort -gu |
      awk 'NR == 1 {first = $1} NR == 2 {step = $1 - first} {last = $1}
           END {printf "%.9g %.9g", first - step / 2, last + step / 2}')
    actual=$(sed -nE "s/^set ${axis}range \[([^:]*):([^]]*)\]/\1 \2/p" "$script" |
      awk '{printf "%.9g %.9g", $1, $2}')
    [[ $actual == "$expected" ]] || fail "map $n: ${axis} range '$actual', the cells span '$expected'"
  done
done
grep -q 'title "impact of P(1,q) vanishes"' "$work/source/1/map.gp" ||
  fail "the overlaid grazing curve is not keyed 'impact of P(1,q) vanishes'"

# The diagram over 0.8-0.9: P(2,1), P(3,2), P(4,2), P(1,1) (check_diagram.sh).
"$impactkit" diagram --from 0.8 --to 0.9 --sweep-values 41 --sweep-transient 300 \
  --sweep-record 20 --plot "$work/d.png" >/dev/null || fail "diagram failed"
script=$work/source/3/chart.gp
families=$(grep -o 'NaN with lines dashtype 1 linewidth 2 linecolor rgb "#[0-9a-f]*" title "P([0-9]*,[0-9]*)"' "$script" |
  sed -E 's/.*rgb "(#[0-9a-f]+)" title "(.*)"/\2 \1/' | sort)
(($(wc -l <<<"$families") >= 3)) || fail "the diagram keys too few families: $families"
line_colors=$(grep -o '"chart1-curve[0-9]*.dat" using 1:2 with lines [^,]*rgb "#[0-9a-f]*"' "$script" |
  grep -o '#[0-9a-f]*' | sort -u)
(($(wc -l <<<"$line_colors") > 1)) || fail "the diagram's branches are in one colour: $line_colors"
while read -r name color; do
  grep -qF "\"$color\"" <<<"$(grep -o 'with lines [^,]*rgb "#[0-9a-f]*"' "$script")" ||
    fail "no line in the colour of $name's key entry"
  map_color=$(awk -v n="$name" '$1 == n {print $2}' "$work/r.classes" "$work/xs.classes" | head -1)
  [[ -z $map_color || $map_color == "$color" ]] ||
    fail "$name is $color in the diagram and $map_color in the maps"
done <<<"$families"

# A basin picture's title: Ω and the coordinates every start shares.
"$impactkit" basins --omega 2.0 --coord x1 --from -1 --to 1 --steps 4 --coord2 v1 --from2 -1 \
  --to2 1 --steps2 4 --transient 200 --record 40 --plot "$work/b.png" >/dev/null ||
  fail "basins failed"
grep -qF 'set title "Basins of attraction at Ω = 2 over (x1, v1); x2 = 0, v2 = 0"' \
  "$work/source/4/map.gp" || fail "basins title: $(grep '^set title' "$work/source/4/map.gp")"

# The sweep's two panels, lettered, no tool name, Ω on the axis.
"$impactkit" sweep --from 0.8 --to 1.0 --steps 5 --transient 100 --record 20 \
  --plot "$work/s.png" >/dev/null || fail "sweep failed"
titles=$(grep '^set title' "$work/source/5/chart.gp")
grep -q '^set title "(a) ' <<<"$titles" && grep -q '^set title "(b) ' <<<"$titles" ||
  fail "sweep panels not lettered: $titles"
! grep -qi 'impactkit' <<<"$titles" || fail "a title names the tool: $titles"
grep -q '^set xlabel "Ω"' "$work/source/5/chart.gp" || fail "the sweep's x axis is not Ω"
echo "ok: figure panels"
