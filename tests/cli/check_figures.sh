# Usage: check_figures.sh IMPACTKIT SOURCE_DIR
# Every figure of the paper rendered (docs/paper-reproduction.md, "The
# figures"): each examples/fig*.sh runs as scripts/run.sh calls it, writes
# the data it promises (each table's rows, the kinds, branches and lines its
# figure is drawn from, checked), and each PNG it promises exists, is at least
# 500 x 300 pixels and is not blank. Every
# gnuplot run (the scripts' own and impactkit's --plot) goes through a shim
# that reports the x and y ranges of its last plot, and no range may be
# degenerate: narrower than 1e-9 of its magnitude (an axis autoscaled into
# rounding noise, every tick label the same digits), or not finite.
# Exit 77 (skipped) without gnuplot.
source "$(dirname "$0")/testlib.sh"
impactkit=$(realpath "$1")
source_dir=$(realpath "$2")
real_gnuplot=$(command -v gnuplot) || exit 77

# The shim: the same script (from its arguments or stdin), then the ranges.
mkdir "$work/shim"
cat >"$work/shim/gnuplot" <<SHIM
#!/usr/bin/env bash
script=\$(mktemp)
if ((\$#)); then cat "\$@" >"\$script"; else cat >"\$script"; fi
cat >>"\$script" <<'GP'

if (exists("GPVAL_X_MIN") && exists("GPVAL_Y_MIN")) {
  set print "$work/ranges" append
  print sprintf("%s %.17g %.17g %.17g %.17g", GPVAL_OUTPUT, GPVAL_X_MIN, GPVAL_X_MAX, GPVAL_Y_MIN, GPVAL_Y_MAX)
  unset print
}
GP
"$real_gnuplot" "\$script"
status=\$?
rm -f "\$script"
exit \$status
SHIM
chmod +x "$work/shim/gnuplot"

cd "$source_dir"
mkdir "$work/logs"
for script in $(printf '%s\n' examples/fig*.sh | sort -V); do
  log=$work/logs/$(basename "$script" .sh).log
  PATH="$work/shim:$PATH" bash "$script" "$impactkit" "$work/figures" "$work/data" \
    >"$log" 2>&1 || fail "$script failed: $(tail -5 "$log")"
done

# Each script's data, not only its figures: the rows it promises and what
# they must hold.
rows() { grep -v '^#' "$work/data/$1" | tail -n +2 | grep -c . || true; }
expect_rows() {  # FILE MIN: at least MIN data rows under the header
  [[ -f $work/data/$1 ]] || fail "no data file $1"
  (($(rows "$1") >= $2)) || fail "$1 has $(rows "$1") data rows, expected at least $2"
}
log_has() {  # SCRIPT PATTERN: the script's printed output matches PATTERN
  grep -qE "$2" "$work/logs/$1.log" || fail "$1 printed no line matching '$2'"
}
expect_rows fig2.csv 2401
(($(grep -cE '^ +x[12] +[0-9.]+ +[0-9.]+$|^peaks: +mass' "$work/logs/fig2_resonance.log") >= 5)) ||
  fail "fig2_resonance.sh printed fewer than the four resonance peaks"
expect_rows fig3-summary.csv 2401
for kind in periodic sticking chaotic non_impacting; do
  log_has fig3_bifurcation "^ +[0-9]+ $kind\$"
done
for panel in a b c d e f g h; do
  expect_rows "fig4$panel.csv" 100
  expect_rows "fig4$panel-impacts.csv" 1
done
for table in p11.csv p11.pd2.csv p11.graze1.csv p21.csv p12.csv sweep-080-090.csv sweep-155-175.csv; do
  expect_rows "$table" 20
done
python3 -c 'import json, sys; sys.exit(len(json.load(open(sys.argv[1]))["branches"]) < 10)' \
  "$work/data/diagram.json" || fail "fig5's connected diagram has fewer than 10 branches"
for panel in a b c; do expect_rows "fig6$panel.csv" 1000; done
expect_rows fig7-summary.csv 501
expect_rows fig7-sticking-branch.csv 20
for n in 2 3 4 5 6 7 8; do log_has fig7_sticking "^ +[0-9.]+ - [0-9.]+: periodic P\\($n,1\\)\$"; done
(($(grep -cE '^ +branch main: +P\([0-9]+,1\) from the start' "$work/logs/fig7_sticking.log") >= 8)) ||
  fail "fig7_sticking.sh followed fewer than 8 P(n,1) branches"
! grep -q 'P(,)' "$work/logs/fig7_sticking.log" || fail "fig7_sticking.sh printed a period without p and q"
for csv in "$work"/data/fig8_*.csv; do expect_rows "$(basename "$csv")" 1000; done
(($(ls "$work"/data/fig8_*.csv | wc -l) == 12)) || fail "fig8 wrote $(ls "$work"/data/fig8_*.csv | wc -l) impact maps, expected 12"
for panel in a b c; do expect_rows "fig9$panel.csv" 1000; done
expect_rows fig10a.csv 100
expect_rows fig10b.csv 100
grep -q '"termination": "converged"' "$work/data/fig10a_fit.json" || fail "fig10(a)'s fit did not converge"
expect_rows fig12.csv 100

# The figures docs/paper-reproduction.md shows, one or more per paper figure.
for name in fig2_resonance fig3_sweep fig4a fig4b fig4c fig4d fig4e fig4f fig4g fig4h \
            continuation-overlay-080-090 continuation-diagram fig6a fig6b fig6c \
            fig7_sticking fig7_branches fig8_impact_maps fig9_impact_map_details \
            fig10a_return_map fig10b_return_map fig11_sqrt_map fig12_chaotic_chatter; do
  png="$work/figures/$name.png"
  [[ -f $png ]] || fail "no $name.png"
  read -r -a bytes <<<"$(od -An -tu1 -N24 "$png" | tr -s ' \n' ' ')"
  [[ "${bytes[*]:0:8}" == "137 80 78 71 13 10 26 10" ]] || fail "$name.png is not a PNG"
  width=$(((bytes[16] << 24) | (bytes[17] << 16) | (bytes[18] << 8) | bytes[19]))
  height=$(((bytes[20] << 24) | (bytes[21] << 16) | (bytes[22] << 8) | bytes[23]))
  ((width >= 500 && height >= 300)) || fail "$name.png is ${width}x${height}"
  (($(stat -c %s "$png") > 8000)) || fail "$name.png is $(stat -c %s "$png") bytes: blank?"
done

[[ -s $work/ranges ]] || fail "the gnuplot shim saw no plot"
awk '
  function degenerate(lo, hi) {
    size = (lo < 0 ? -lo : lo) > (hi < 0 ? -hi : hi) ? (lo < 0 ? -lo : lo) : (hi < 0 ? -hi : hi)
    return !(hi - lo > 1e-9 * size) || lo != lo || hi != hi
  }
  degenerate($2, $3) { print "x range " $2 " to " $3 " of " $1; bad = 1 }
  degenerate($4, $5) { print "y range " $4 " to " $5 " of " $1; bad = 1 }
  END { exit bad }
' "$work/ranges" || fail "degenerate axes"
echo "ok: $(wc -l <"$work/ranges") plots, every figure of the paper"
