# Usage: check_figures.sh IMPACTKIT SOURCE_DIR
# Every figure of the paper rendered (docs/paper-reproduction.md, "The
# figures"): each examples/fig*.sh runs as scripts/run.sh calls it, and each
# PNG it promises exists, is at least 500 x 300 pixels and is not blank. Every
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
for script in $(printf '%s\n' examples/fig*.sh | sort -V); do
  PATH="$work/shim:$PATH" bash "$script" "$impactkit" "$work/figures" "$work/data" \
    >"$work/log" 2>&1 || fail "$script failed: $(tail -5 "$work/log")"
done

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
