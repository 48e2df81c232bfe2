#!/usr/bin/env bash
# Bad input must fail cleanly: `impactkit COMMAND ARGS...`, with outputs of
# COMMAND requested (each unless ARGS name it, as tests of output paths do),
# exits with status 2, prints exactly one line on stderr, starting
# "impactkit: error: " and containing EXPECTED, prints nothing on stdout, and
# leaves no file behind (not even a temporary one). COMMAND may be a word
# that is no subcommand.
#
#     expect_bad_input.sh IMPACTKIT COMMAND EXPECTED ARGS...
source "$(dirname "$0")/testlib.sh"
impactkit=$1
command=$2
expected=$3
shift 3

mkdir "$work/out"
case $command in
  simulate) outputs=(--series "$work/out/series.csv" --impacts "$work/out/impacts.csv"
                     --plot "$work/out/plot.png" --json "$work/out/summary.json") ;;
  sweep) outputs=(--out "$work/out/impacts.csv" --summary "$work/out/summary.csv") ;;
  map | basins) outputs=(--out "$work/out/cells.csv" --json "$work/out/summary.json") ;;
  resonance | impactmap | returnmap) outputs=(--out "$work/out/table.csv") ;;
  orbit | continue | curve | diagram | lyapunov) outputs=(--json "$work/out/result.json") ;;
  paper) outputs=(--out "$work/out/paper") ;;
  *) outputs=() ;;  # not a subcommand: its message is the test
esac
# An output flag among ARGS (the subject of the test) is not given twice.
given=()
for ((i = 0; i < ${#outputs[@]}; i += 2)); do
  [[ " $* " == *" ${outputs[i]} "* || " $* " == *" ${outputs[i]}="* ]] ||
    given+=("${outputs[i]}" "${outputs[i + 1]}")
done
status=0
"$impactkit" "$command" "$@" ${given[@]+"${given[@]}"} >"$work/stdout" 2>"$work/stderr" || status=$?

message=$(cat "$work/stderr")
[[ $status -eq 2 ]] || fail "exit status $status, expected 2; stderr: $message"
lines=$(wc -l <"$work/stderr")
[[ $lines -eq 1 ]] || fail "$lines lines on stderr, expected 1: $message"
[[ $message == "impactkit: error: "* ]] || fail "stderr does not start with 'impactkit: error: ': $message"
[[ $message == *"$expected"* ]] || fail "stderr does not mention '$expected': $message"
[[ ! -s $work/stdout ]] || fail "unexpected output on stdout: $(cat "$work/stdout")"
leftovers=$(ls -A "$work/out")
[[ -z $leftovers ]] || fail "files left behind: $leftovers"
echo "ok: $message"
