#!/usr/bin/env bash
# A run that could not produce what was asked must say so: `impactkit
# COMMAND ARGS...` exits with status 1 (not 0, not 2: the input was good)
# and prints exactly one line on stderr, starting "impactkit: error: " and
# containing EXPECTED. What it printed on stdout before is allowed.
#
#     expect_no_result.sh IMPACTKIT COMMAND EXPECTED ARGS...
source "$(dirname "$0")/testlib.sh"
impactkit=$1
command=$2
expected=$3
shift 3

status=0
"$impactkit" "$command" "$@" >"$work/stdout" 2>"$work/stderr" || status=$?
message=$(cat "$work/stderr")
[[ $status -eq 1 ]] || fail "exit status $status, expected 1; stderr: $message"
lines=$(wc -l <"$work/stderr")
[[ $lines -eq 1 ]] || fail "$lines lines on stderr, expected 1: $message"
[[ $message == "impactkit: error: "* ]] || fail "stderr does not start with 'impactkit: error: ': $message"
[[ $message == *"$expected"* ]] || fail "stderr does not mention '$expected': $message"
echo "ok: $message"
