#!/usr/bin/env bash
# Several stops on the command line (docs/several-stops.md):
#  - simulate on the paper's system in a clearance writes a `stop` column
#    naming both stops, each row's x2 at that stop's position;
#  - orbit on one mass between two stops finds the asymmetric P(2,1) with
#    one impact at each stop (text and JSON), also from --guess --stop;
#  - continue finds the symmetric P(2,1)'s two pitchforks and marks them in
#    its CSV;
#  - --stop without --guess, or beyond the system's stops, is a one-line
#    error with status 2.
#
#     check_stops.sh IMPACTKIT SOURCE_DIR
source "$(dirname "$0")/testlib.sh"
impactkit=$1
systems=$2/examples/systems

"$impactkit" simulate --system "$systems/paper-two-stops.toml" --omega 0.8 \
  --impacts "$work/impacts.csv" >/dev/null || fail "simulate failed"
[[ $(columns_of "$work/impacts.csv") == "t,phase,velocity,x1,x2,v1,v2,stop" ]] ||
  fail "impact columns: $(columns_of "$work/impacts.csv")"
awk -F, '!/^#/ && ++row > 1 {
           n[$8]++
           if (($8 == 1 && $5 != 0.1) || ($8 == 2 && $5 != -0.1) || ($8 != 1 && $8 != 2)) bad = 1
         }
         END { exit bad || n[1] != 60 || n[2] != 60 }' "$work/impacts.csv" ||
  fail "impacts are not 60 at each stop, each at its position"

"$impactkit" orbit --system "$systems/clearance-1dof.toml" --omega 1.5 \
  --json "$work/orbit.json" >"$work/orbit.txt" || fail "orbit failed: $(cat "$work/orbit.txt")"
grep -q "P(2,1) at omega = 1.5, stable" "$work/orbit.txt" || fail "orbit: $(cat "$work/orbit.txt")"
grep -q " 1 (x1 <= 0.5)$" "$work/orbit.txt" && grep -q " 2 (x1 >= -0.5)$" "$work/orbit.txt" ||
  fail "orbit lists no impact at each stop: $(cat "$work/orbit.txt")"
json=$(tr -d ' \n' <"$work/orbit.json")
[[ $json == *'"stop":1'* && $json == *'"stop":2'* ]] || fail "orbit JSON: $json"
# The same orbit from a guess at the lower stop: its impact there first.
guess=$(grep -m1 ' 2 (x1 >= -0.5)$' "$work/orbit.txt" | awk '{ printf "%s,-%s\n", $1, $2 }')
"$impactkit" orbit --system "$systems/clearance-1dof.toml" --omega 1.5 --p 2 --q 1 \
  --guess "$guess" --stop 2 >"$work/guessed.txt" || fail "orbit --guess --stop 2 failed"
sed -n '4p' "$work/guessed.txt" | grep -q " 2 (x1 >= -0.5)$" ||
  fail "the guessed orbit does not start at stop 2: $(cat "$work/guessed.txt")"

"$impactkit" continue --system "$systems/clearance-1dof.toml" --start 1.0 --from 0.8 --to 2.2 \
  --out "$work/branch.csv" >"$work/continue.txt" || fail "continue failed"
[[ $(grep -c '^  pitchfork at omega = ' "$work/continue.txt") -eq 2 ]] ||
  fail "expected two pitchforks: $(cat "$work/continue.txt")"
[[ $(grep -c ',pitchfork$' "$work/branch.csv") -eq 2 ]] || fail "the CSV marks no two pitchforks"

expect_error() {
  local expected=$1
  shift
  local status=0
  "$impactkit" "$@" >"$work/out" 2>"$work/err" || status=$?
  [[ $status -eq 2 ]] || fail "$*: status $status, expected 2"
  [[ $(wc -l <"$work/err") -eq 1 ]] && grep -qF -- "$expected" "$work/err" ||
    fail "$*: $(cat "$work/err")"
}
expect_error "--stop goes with --guess" orbit --system "$systems/clearance-1dof.toml" --stop 2
expect_error "--stop 3: the system has 2 stops" orbit --system "$systems/clearance-1dof.toml" \
  --p 2 --q 1 --guess 4.09,0.8 --stop 3
echo "ok: several stops on the command line"
