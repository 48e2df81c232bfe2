#!/usr/bin/env bash
# `impactkit curve`: the paper's P(1,1) period-doubling curve in (omega, r)
# from the issue's example runs from bound to bound; its JSON has the
# documented fields (docs/curves-json.md), its CSV a header named after the
# parameters and one row per point; the grazing curve in (omega, A1)
# reports its two meetings with period doubling as codim2_points keyed by
# the parameter names; a start read from `impactkit continue --json` gives
# the same curve as the direct start; P(1,2)'s vanishing impact is the
# non-impacting response's grazing, and its fold curve begins at a corner
# on it; a curve stopped by --max-points names the impact vanishing
# nearby; a sticking family's JSON is refused as a start, with its reason;
# a system with two stops (one mass in a clearance) has curves too, from
# the direct start and from `continue --json`, whose special point names
# the stop its eta is at.
#
#     check_curve.sh IMPACTKIT SOURCE_DIR
source "$(dirname "$0")/testlib.sh"
impactkit=$1
systems=$2/examples/systems

"$impactkit" curve --type period_doubling --p 1 --q 1 --omega 1.6 --param omega --param2 r \
  --from2 0.5 --to2 0.95 --json "$work/pd.json" --out "$work/pd.csv" >"$work/stdout" ||
  fail "impactkit curve failed: $(cat "$work/stdout")"
grep -q "start:      period doubling at omega = 1.61304" "$work/stdout" || fail "start: $(cat "$work/stdout")"
grep -q "begins:   parameter_bound (reached omega = 1.61564" "$work/stdout" ||
  fail "no bound at r = 0.5: $(cat "$work/stdout")"
json=$(tr -d ' \n' <"$work/pd.json")
for field in '"curves":[{' '"type":"period_doubling"' '"params":["omega","r"]' '"end_reason":"parameter_bound"' \
             '"points":[{"multipliers":[[' '"omega":1.6156' '"outside":0' '"codim2_points":[]' '"system":{'; do
  [[ $json == *"$field"* ]] || fail "JSON lacks $field"
done
run_line_of "$work/pd.csv" | grep -q '^curve --type period_doubling --param omega --param2 r' ||
  fail "CSV provenance missing: $(run_line_of "$work/pd.csv")"
columns_of "$work/pd.csv" | grep -q '^omega,r,arclength,mod1,mod2,mod3,mod4,outside,codim2$' ||
  fail "unexpected CSV header: $(columns_of "$work/pd.csv")"
(($(wc -l <"$work/pd.csv") > 20)) || fail "too few CSV rows"

"$impactkit" curve --type grazing --param2 A1 --from 0.5 --to 3 --from2 0.1 --to2 0.6 \
  --json "$work/g.json" >"$work/stdout" || fail "grazing curve failed: $(cat "$work/stdout")"
json=$(tr -d ' \n' <"$work/g.json")
for field in '"type":"grazing"' '"codim2_points":[{' '"type":"period_doubling_grazing"' '"A1":0.389644' \
             '"A1":0.173921'; do
  [[ $json == *"$field"* ]] || fail "grazing JSON lacks $field"
done

"$impactkit" continue --from 0.5 --to 2 --start 1 --json "$work/b.json" >/dev/null || fail "continue failed"
"$impactkit" curve --start-json "$work/b.json" --point 2 --param2 r --from2 0.5 --to2 0.95 \
  >"$work/stdout" || fail "--start-json failed: $(cat "$work/stdout")"
grep -q "begins:   parameter_bound (reached omega = 1.61564" "$work/stdout" ||
  fail "--start-json gave another curve: $(cat "$work/stdout")"
# The start line shows the point's multiplier as the JSON has it.
grep -q "^start:      period doubling at omega = .* (multiplier -1.000000000" "$work/stdout" ||
  fail "--start-json lost the multiplier: $(cat "$work/stdout")"
# P(1,2)'s impact vanishes: followed as the non-impacting response touching
# the stop (p = 0 in the JSON, points without multipliers).
"$impactkit" curve --type grazing --p 1 --q 2 --omega 2.0 --param2 xs --from 0.5 --to 3 \
  --from2 0.05 --to2 0.2 --json "$work/v.json" >"$work/stdout" || fail "vanishing impact: $(cat "$work/stdout")"
grep -q "curve:      grazing of the non-impacting response in (omega, xs)" "$work/stdout" ||
  fail "not the response's grazing: $(cat "$work/stdout")"
json=$(tr -d ' \n' <"$work/v.json")
[[ $json == *'"multipliers":[],"omega":'* && $json == *'"p":0'* ]] || fail "response JSON: $json"
# P(1,2)'s fold curve in (omega, xs) begins at its corner on that curve: a
# point without an orbit (null outside, empty CSV cells).
"$impactkit" curve --type fold --p 1 --q 2 --omega 2.0 --param2 xs --from 0.5 --to 3 \
  --from2 0 --to2 0.3 --json "$work/f.json" --out "$work/f.csv" >"$work/stdout" ||
  fail "fold curve: $(cat "$work/stdout")"
grep -q "begins:   grazing (fold_grazing at omega = 2.37786842" "$work/stdout" ||
  fail "no fold_grazing corner: $(cat "$work/stdout")"
json=$(tr -d ' \n' <"$work/f.json")
[[ $json == *'"multipliers":[],"omega":2.37786842'*'"outside":null'* ]] || fail "corner JSON: $json"
grep -v "^#" "$work/f.csv" | sed -n 2p | grep -q '^2.37786842[0-9]*,0.0314465[0-9]*,[-0-9.e]*,,,,,,fold_grazing$' ||
  fail "corner CSV row: $(grep -v "^#" "$work/f.csv" | sed -n 2p)"
# A curve cut off by --max-points beside a vanishing impact says so: P(5,2)'s
# fold curve in (omega, xs) creeps there (docs/continuation.md, known limits).
"$impactkit" curve --type fold --p 5 --q 2 --omega 1.67526 \
  --guess=-0.54522,3.62549,1.06863,0.0181567 --param2 xs --from2 0 --to2 0.2 --from 1.5 \
  --to 1.9 --max-points 60 >"$work/stdout" 2>/dev/null || fail "P(5,2) fold curve: $(cat "$work/stdout")"
grep -q "max_points (60 points reached; impact 1 vanishes nearby (depth " "$work/stdout" ||
  fail "max_points without the vanishing impact: $(cat "$work/stdout")"
# A sticking family's JSON is refused, saying why, with exit status 2.
"$impactkit" continue --from 0.2 --to 0.5 --json "$work/s.json" >/dev/null || fail "sticking family failed"
status=0
"$impactkit" curve --start-json "$work/s.json" --param2 r --from2 0.3 --to2 0.9 >/dev/null \
  2>"$work/stderr" || status=$?
((status == 2)) && grep -q "a sticking family P(inf,q) (.continue --sticking.); curve follows" \
  "$work/stderr" || fail "sticking JSON: exit $status, $(cat "$work/stderr")"
# Two stops: the clearance's symmetric P(2,1) grazes both stops at once at
# omega = 0.7010019931; its grazing curve in (omega, A1) runs from bound to
# bound (docs/several-stops.md).
"$impactkit" curve --system "$systems/clearance-1dof.toml" --omega 1 --type grazing \
  --param2 A1 --from 0.5 --to 1.2 --from2 0.8 --to2 1.2 --json "$work/c2.json" \
  >"$work/stdout" || fail "two-stop curve: $(cat "$work/stdout")"
grep -q "start:      grazing at omega = 0.7010019931" "$work/stdout" ||
  fail "two-stop curve start: $(cat "$work/stdout")"
grep -q "ends:     parameter_bound (reached omega = .*, A1 = 1.2)" "$work/stdout" ||
  fail "two-stop curve end: $(cat "$work/stdout")"
"$impactkit" continue --system "$systems/clearance-1dof.toml" --start 1 --from 0.5 --to 1 \
  --json "$work/c2-branch.json" >/dev/null || fail "two-stop continue failed"
json=$(tr -d ' \n' <"$work/c2-branch.json")
[[ $json == *'"stop":'[12]* ]] || fail "special point without its stop: $json"
"$impactkit" curve --start-json "$work/c2-branch.json" --point 1 --param2 A1 --from 0.5 --to 1.2 \
  --from2 0.8 --to2 1.2 >"$work/stdout2" || fail "two-stop --start-json: $(cat "$work/stdout2")"
[[ $(grep "^  ends:" "$work/stdout") == $(grep "^  ends:" "$work/stdout2") ]] ||
  fail "--start-json gave another two-stop curve: $(cat "$work/stdout2")"
# A start JSON whose stop the system lacks is refused with the reason.
sed 's/"stop": *[12]/"stop": 7/g' "$work/c2-branch.json" >"$work/c2-bad.json"
status=0
"$impactkit" curve --start-json "$work/c2-bad.json" --point 1 --param2 A1 --from 0.5 --to 1.2 \
  --from2 0.8 --to2 1.2 >/dev/null 2>"$work/stderr" || status=$?
((status == 2)) && grep -q "stop 7 is not one of the system's 2 stops" "$work/stderr" ||
  fail "a stop the system lacks: exit $status, $(cat "$work/stderr")"
echo ok
