# Usage: check_figure_key.sh IMPACTKIT
# The continuation figure's key (docs/cli.md, "Figures"), read from the
# gnuplot source that IMPACTKIT_PLOT_SOURCE keeps: "stable" and "unstable"
# once each; one entry per branch, each its own colour; one entry per type
# of special point present, each its own marker; every line drawn without a
# title of its own. The kept source renders the same figure again.
# Exit 77 (skipped) without gnuplot.
source "$(dirname "$0")/testlib.sh"
impactkit=$1
command -v gnuplot >/dev/null || exit 77

IMPACTKIT_PLOT_SOURCE="$work/source" \
  "$impactkit" continue --from 0.5 --to 2.0 --start 1.0 --switch-pd --follow-grazing --plot "$work/b.png" >/dev/null
script="$work/source/1/chart.gp"
[[ -f $script ]] || fail "no kept source at $script"

titles() { grep -v "^set title" "$script" | grep -o 'title "[^"]*"' | sed 's/title "\(.*\)"/\1/' | sort; }
for entry in stable unstable "P(1,1) main" "P(2,1) graze1" "P(2,2) pd2" fold "period doubling" grazing; do
  count=$(titles | grep -cxF "$entry" || true)
  [[ $count == 1 ]] || fail "key entry '$entry' appears $count times (want once)"
done
# Nothing else has a title: every data line is notitle.
[[ $(titles | wc -l) == 8 ]] || fail "unexpected key entries: $(titles | tr '\n' '|')"

# Branch entries (key-only NaN lines other than the grey stability ones) in distinct colours.
colors=$(grep -o 'NaN with lines dashtype 1 [^,]*linecolor rgb "#[0-9a-f]*" title "P(' "$script" |
  grep -o '#[0-9a-f]*' | sort)
[[ $(echo "$colors" | wc -l) == 3 && $(echo "$colors" | uniq | wc -l) == 3 ]] ||
  fail "branch colours not distinct: $colors"

# Special-point types in distinct marker shapes.
shapes=$(grep -o 'with points pointtype [0-9]* pointsize [0-9.]* linecolor rgb "#000000" title' "$script" |
  awk '{print $4}' | sort)
[[ $(echo "$shapes" | wc -l) == 3 && $(echo "$shapes" | uniq | wc -l) == 3 ]] ||
  fail "special-point markers not distinct: $shapes"

# The kept source is self-contained.
(cd "$work/source/1" && gnuplot chart.gp) || fail "the kept source does not render"
[[ -s $work/source/1/chart.png ]] || fail "the kept source made no PNG"
echo "ok: figure key"
