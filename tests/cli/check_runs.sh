#!/usr/bin/env bash
# Good runs of `impactkit simulate`, checked through what a user gets: the
# summary on stdout and the files, whose contents must hold together.
#
#     check_runs.sh outputs    IMPACTKIT IMPACT_SPEEDS   CSV columns and contents
#     check_runs.sh sticking   IMPACTKIT                 a chatter-and-sticking run
#     check_runs.sh plot       IMPACTKIT                 the PNG (skipped, 77, without gnuplot)
#     check_runs.sh vector-plot IMPACTKIT                .pdf and .svg give PDF and SVG figures
#     check_runs.sh examples   IMPACTKIT DIR             every system file in DIR runs
#     check_runs.sh unwritable IMPACTKIT                 an output that cannot be written
#     check_runs.sh failed-plot IMPACTKIT                gnuplot fails: no file of the set is written
#     check_runs.sh help       IMPACTKIT                 every --help explains every option
source "$(dirname "$0")/testlib.sh"
check=$1
impactkit=$2

# The paper's system, as the runs below use it.
readonly dof=2 xs=0.1

# Columns: `first`, x1..xN, v1..vN, then `last` (either may be empty).
state_header() {
  local first=$1 last=$2
  echo "${first}$(seq -s, -f 'x%g' 1 "$dof"),$(seq -s, -f 'v%g' 1 "$dof")${last}"
}

check_provenance_and_header() {
  local file=$1 header=$2
  [[ $(run_line_of "$file") == "simulate "* ]] || fail "$file: no '# run: simulate' line"
  [[ $(columns_of "$file") == "$header" ]] ||
    fail "$file: header '$(columns_of "$file")', expected '$header'"
}

# Grid rows at strictly increasing t, event rows (docs/cli.md, simulate) in
# time order between them; the contact mass x_N never beyond the stop (and at
# it whenever stuck and at each impact); each impact twice, v_N before it > 0
# and after it -r times that (r = 0.7); stuck 0 or 1; every row complete.
check_series() {
  local file=$1
  check_provenance_and_header "$file" "$(state_header t, ,stuck,event)"
  awk -F, -v n="$dof" -v xs="$xs" '
    /^#/ || ++row == 1 { next }
    NF != 2 * n + 3 { print "row " NR ": " NF " fields"; bad = 1; exit }
    { event = $NF; stuck = $(NF - 1); x = $(1 + n); v = $(1 + 2 * n) }
    event !~ /^(|impact_before|impact_after|stick|release)$/ { print "row " NR ": event " event; bad = 1; exit }
    row > 2 && ($1 < t || ($1 == t && event == "")) { print "row " NR ": t = " $1 " after " t; bad = 1; exit }
    x > xs + 1e-12 { print "row " NR ": x" n " = " x " > xs"; bad = 1; exit }
    stuck != 0 && stuck != 1 { print "row " NR ": stuck = " stuck; bad = 1; exit }
    stuck == 1 && x != xs { print "row " NR ": stuck with x" n " = " x; bad = 1; exit }
    event == "impact_before" && (x != xs || v <= 0) { print "row " NR ": before impact " x ", " v; bad = 1; exit }
    event == "impact_after" && (previous != "impact_before" || $1 != t ||
      (v + 0.7 * before)^2 > (1e-12 * before)^2) { print "row " NR ": after impact " v " (" before ")"; bad = 1; exit }
    event == "impact_before" { before = v; impacts++ }
    { t = $1; previous = event; rows++ }
    END { if (!bad && rows == 0) { print "no rows"; bad = 1 }; exit bad }
  ' "$file" || fail "$file: bad series"
}

run_outputs() {
  local oracle=$1
  "$impactkit" simulate --omega 1.4 --transient 200 --periods 20 --samples-per-period 200 \
    --series "$work/series.csv" --impacts "$work/impacts.csv" --json "$work/summary.json" \
    >"$work/stdout"
  grep -q '^motion: *P(1,1) ' "$work/stdout" || fail "summary: $(cat "$work/stdout")"
  grep -q '"label": "P(1,1)"' "$work/summary.json" || fail "summary.json has no P(1,1)"

  check_series "$work/series.csv"
  local rows impact_rows
  rows=$(grep -v '^#' "$work/series.csv" | grep -c ',$' || true)
  ((rows >= 20 * 200)) || fail "series: $rows grid rows, expected at least 4000"
  # P(1,1) over 20 periods: 20 impacts, each before and after.
  impact_rows=$(grep -c ',impact_' "$work/series.csv" || true)
  ((impact_rows == 40)) || fail "series: $impact_rows impact rows, expected 40"

  check_provenance_and_header "$work/impacts.csv" "$(state_header t,phase,velocity, ,stop)"
  awk -F, -v n="$dof" -v xs="$xs" '!/^#/ && ++row > 1 && $(3 + n) != xs { print "row " NR ": x" n " = " $(3 + n); bad = 1 }
    END { exit bad }' "$work/impacts.csv" || fail "impacts: contact mass not at the stop"
  # The speeds must be the library's, bit for bit (both shortest round-trip).
  "$oracle" 1.4 200 20 >"$work/expected-speeds"
  awk -F, '!/^#/ && ++row > 1 { print $3 }' "$work/impacts.csv" >"$work/speeds"
  [[ -s $work/expected-speeds ]] || fail "the reference run has no impacts"
  diff "$work/expected-speeds" "$work/speeds" || fail "impact speeds differ from the library's"
}

run_sticking() {
  # Ω = 0.2: chatter, then sticking once per forcing period (the paper's Fig. 4b).
  "$impactkit" simulate --omega 0.2 --transient 100 --periods 3 --series "$work/series.csv" \
    >"$work/stdout"
  grep -q '^motion: *P(inf,1) sticking' "$work/stdout" || fail "summary: $(cat "$work/stdout")"
  check_series "$work/series.csv"
  grep -q ',1,[a-z_]*$' "$work/series.csv" || fail "no stuck sample in a sticking motion"
  grep -q ',1,stick$' "$work/series.csv" || fail "no stick row in a sticking motion"
  grep -q ',0,release$' "$work/series.csv" || fail "no release row in a sticking motion"
  # Its chatter accumulates: no cut is reported. Elastic chatter (r = 1: a
  # damped mass pressed into the stop, bouncing without accumulating) is
  # cut at a short bounce, and the summary and the JSON say how often.
  ! grep -q ' cut at a short bounce' "$work/stdout" || fail "a cut reported: $(cat "$work/stdout")"
  printf '%s\n' '{"mass":[[1]],"stiffness":[[1]],"damping":[[2]],"forcing":[1],"omega":0.05,' \
    '"xs":0.2,"r":1}' >"$work/elastic.json"
  "$impactkit" simulate --system "$work/elastic.json" --transient 2 --periods 2 \
    --json "$work/elastic-summary.json" >"$work/stdout"
  grep -q '^sticking: .* cut at a short bounce without accumulating' "$work/stdout" ||
    fail "elastic chatter: no cut reported: $(cat "$work/stdout")"
  python3 -c 'import json, sys; sys.exit(json.load(open(sys.argv[1]))["chatter_cuts"] < 2)' \
    "$work/elastic-summary.json" || fail "elastic chatter: chatter_cuts not in the JSON"
}

run_plot() {
  command -v gnuplot >/dev/null || { echo "gnuplot not installed: skipped"; exit 77; }
  "$impactkit" simulate --omega 1.4 --periods 5 --plot "$work/plot.png" >/dev/null
  # PNG signature, then the IHDR chunk: width and height, 4 bytes each, big-endian.
  local header
  header=$(od -An -tu1 -N24 "$work/plot.png" | tr -s ' \n' ' ')
  [[ $header == " 137 80 78 71 13 10 26 10 "* ]] || fail "not a PNG: $header"
  read -r -a bytes <<<"$header"
  local width=$(((bytes[16] << 24) | (bytes[17] << 16) | (bytes[18] << 8) | bytes[19]))
  local height=$(((bytes[20] << 24) | (bytes[21] << 16) | (bytes[22] << 8) | bytes[23]))
  [[ $width -eq 1000 && $height -eq 600 ]] || fail "PNG is ${width}x${height}, expected 1000x600"
}

# --plot by extension: a PDF (its page as many points as the PNG has
# pixels) or an SVG (well-formed, of the PNG's size, its <desc> the
# command), for a chart, a stacked chart (sweep) and a class map (map).
run_vector_plot() {
  command -v gnuplot >/dev/null || fail "gnuplot is not installed"
  cd "$work"
  "$impactkit" simulate --omega 1.4 --periods 5 --plot sim.pdf >/dev/null || fail "simulate failed"
  "$impactkit" simulate --omega 1.4 --periods 5 --plot sim.svg >/dev/null || fail "simulate failed"
  "$impactkit" sweep --from 0.6 --to 0.7 --steps 3 --transient 10 --record 5 --plot sweep.SVG \
    >/dev/null || fail "sweep failed"
  "$impactkit" map --from 0.6 --to 0.7 --steps 2 --param2 r --from2 0.6 --to2 0.7 --steps2 2 \
    --transient 10 --record 5 --threads 1 --plot map.pdf >/dev/null || fail "map failed"
  python3 - <<'PY' || fail "not the figures asked for"
import re
import xml.etree.ElementTree as ElementTree

for name, size in (("sim.pdf", (1000, 600)), ("map.pdf", (1200, 800))):
    data = open(name, "rb").read()
    assert data.startswith(b"%PDF-"), f"{name} is not a PDF: {data[:8]!r}"
    box = re.search(rb"/MediaBox \[ *0 0 ([0-9.]+) ([0-9.]+) *\]", data)
    assert box and (round(float(box[1])), round(float(box[2]))) == size, f"{name}: {box}"
for name, size, command in (("sim.svg", (1000, 600), "simulate --omega 1.4 --periods 5 --plot sim.svg"),
                            ("sweep.SVG", (1000, 900), None)):
    root = ElementTree.parse(name).getroot()
    assert root.tag == "{http://www.w3.org/2000/svg}svg", f"{name}: root {root.tag}"
    assert (int(root.get("width")), int(root.get("height"))) == size, f"{name}: {root.attrib}"
    desc = root.find("{http://www.w3.org/2000/svg}desc").text
    assert desc.startswith("impactkit "), f"{name}: <desc> {desc!r}"
    assert command is None or desc.endswith("command: impactkit " + command), desc
PY
}

run_examples() {
  local dir=$1 file
  for file in "$dir"/*.json "$dir"/*.toml; do
    "$impactkit" simulate --system "$file" --transient 20 --periods 4 >"$work/stdout" ||
      fail "$file did not run"
    grep -q '^motion:' "$work/stdout" || fail "$file: no motion line"
  done
}

run_unwritable() {
  local status=0
  "$impactkit" simulate --series "$work/no-such-directory/series.csv" \
    >"$work/stdout" 2>"$work/stderr" || status=$?
  [[ $status -eq 1 ]] || fail "exit status $status, expected 1"
  [[ $(wc -l <"$work/stderr") -eq 1 ]] || fail "stderr: $(cat "$work/stderr")"
  grep -q '^impactkit: error: cannot create .*series.csv' "$work/stderr" ||
    fail "stderr: $(cat "$work/stderr")"
}

run_failed_plot() {
  mkdir "$work/bin" "$work/out"
  printf '#!/bin/sh\necho "line 1: simulated failure" >&2\nexit 1\n' >"$work/bin/gnuplot"
  chmod +x "$work/bin/gnuplot"
  local status=0
  PATH="$work/bin:$PATH" "$impactkit" simulate --periods 2 --series "$work/out/series.csv" \
    --plot "$work/out/plot.png" --json "$work/out/summary.json" \
    >"$work/stdout" 2>"$work/stderr" || status=$?
  [[ $status -eq 1 ]] || fail "exit status $status, expected 1"
  grep -q '^impactkit: error: gnuplot failed: line 1: simulated failure$' "$work/stderr" ||
    fail "stderr: $(cat "$work/stderr")"
  [[ -z $(ls -A "$work/out") ]] || fail "files left behind: $(ls -A "$work/out")"
}

# `impactkit COMMAND --help` exits 0, every option line in it has an
# explanation (on its line, or on the next when the name column is full),
# and each SPEC is there: `--name` listed; `--name=VALUE` listed with its
# default VALUE (CLI11's `TYPE=VALUE`); `--name!` marked REQUIRED; `--name~`
# its explanation says what the default is. (Flags default to off, output
# files to not written.)
check_help() {
  local command=$1 spec name entry
  shift
  "$impactkit" "$command" --help >"$work/help" || fail "impactkit $command --help exited non-zero"
  # CLI11 starts explanations in column 31, or on the next line.
  awk '
    pending != "" && /^                              [^ ]/ { pending = ""; next }
    pending != "" { print pending; bad = 1; pending = "" }
    /^  --/ && !(substr($0, 30, 1) == " " && substr($0, 31, 1) ~ /[^ ]/) { pending = $1 }
    END { if (pending != "") { print pending; bad = 1 }; exit bad }
  ' "$work/help" >"$work/unexplained" || fail "$command --help: no explanation for $(cat "$work/unexplained")"
  for spec in "$@"; do
    name=${spec%%[=!~]*}
    entry=$(grep -A1 -E -- "^  $name( |=|\$)" "$work/help") || fail "$command --help does not list $name"
    case $spec in
      *=*) grep -q -E -- "^  $name [^ ]*=${spec#*=}( |\$)" <<<"$entry" ||
        fail "$command --help: $name does not show its default ${spec#*=}: $entry" ;;
      *!) grep -q REQUIRED <<<"$entry" || fail "$command --help: $name not marked REQUIRED" ;;
      *~) grep -q -i default <<<"$entry" || fail "$command --help: $name does not say its default" ;;
    esac
  done
}

run_help() {
  "$impactkit" --help >"$work/help" || fail "impactkit --help exited non-zero"
  local command
  for command in simulate orbit continue paper sweep impactmap returnmap lyapunov resonance; do
    grep -q -E "^  $command +[A-Z]" "$work/help" || fail "impactkit --help does not describe $command"
  done
  local system=(--system~ --set --omega~ --dof~)
  local seed=(--p~ --q~ --guess~ --transient=500 --jacobian=analytic --no-fallback)
  check_help simulate "${system[@]}" --transient=200 --periods=20 --samples-per-period=200 --x0~ \
    --v0~ --chatter=accumulation --chatter-threshold~ --series --impacts --plot --json
  check_help orbit "${system[@]}" "${seed[@]}" --json
  check_help continue "${system[@]}" "${seed[@]}" --param=omega --from! --to! --start~ \
    --step=0.01 --min-step=1e-07 --max-step=0.02 --max-points=10000 --switch-pd \
    --follow-grazing --out --json --plot
  check_help paper --out=out/paper --quick --threads=0
  check_help sweep "${system[@]}" --param=omega --from! --to! --steps! --transient=500 \
    --record=100 --start=previous --direction=up --x0~ --v0~ --threads~ --chunk=100 --warmup=5 \
    --max-q=64 --out --summary --plot
  check_help impactmap "${system[@]}" --transient=500 --periods=5000 --out --plot
  check_help returnmap "${system[@]}" --transient=500 --periods=5000 --bound=0.3 --fit \
    --fit-from~ --fit-to~ --out --plot --json
  check_help lyapunov "${system[@]}" --transient=500 --transient-impacts=200 --impacts=2000 --json
  check_help resonance "${system[@]}" --from=0.1 --to=2.5 --steps=2401 --out --plot
}

case $check in
  outputs) run_outputs "$3" ;;
  sticking) run_sticking ;;
  plot) run_plot ;;
  vector-plot) run_vector_plot ;;
  examples) run_examples "$3" ;;
  unwritable) run_unwritable ;;
  failed-plot) run_failed_plot ;;
  help) run_help ;;
  *) fail "unknown check '$check'" ;;
esac
echo "ok: $check"
