#!/usr/bin/env bash
# `impactkit continue --from 0.2 --to 0.5` from the paper's sticking motion
# follows the sticking family P(inf,1) in omega up to where its chatter
# stops ending in sticking (omega ~ 0.3063, docs/continuation.md): the end
# is a no_sticking special point, the CSV has one row per point, and the
# simulation 1e-3 below the end still sticks while 1e-3 above it does not.
# Then the sticking family in c at omega = 0.27 with --switch-pd and --plot:
# it period-doubles (c ~ 0.0342), the doubled family P(inf,2) with two
# sticking phases is followed, and a point of it is the sticking orbit that
# `impactkit orbit` seeds from the simulation there (stick phases to 1e-8).
#
#     check_continue_sticking.sh IMPACTKIT
source "$(dirname "$0")/testlib.sh"
impactkit=$1

"$impactkit" continue --from 0.2 --to 0.5 --out "$work/b.csv" --json "$work/b.json" \
  >"$work/stdout" || fail "impactkit continue failed: $(cat "$work/stdout")"
grep -q '^start: *sticking P(inf,1) at omega = 0.2, stable' "$work/stdout" ||
  fail "unexpected start: $(cat "$work/stdout")"
grep -q '^  ends: *no_sticking' "$work/stdout" || fail "unexpected end: $(cat "$work/stdout")"
json=$(tr -d ' \n' <"$work/b.json")
for field in '"section":"release"' '"releases":1' '"end_reason":"no_sticking"' \
  '"type":"no_sticking"' '"stick_phases":[' '"parameter":"omega"' '"param_range":[0.2,'; do
  [[ $json == *"$field"* ]] || fail "JSON lacks $field"
done
columns_of "$work/b.csv" |
  grep -q '^omega,arclength,stick_phase1,release_phase1,stuck1,impact_phase1,impact_velocity1,range_xN,mod1,mod2,stable,clearance,contact_margin,special' ||
  fail "unexpected CSV header: $(columns_of "$work/b.csv")"
end=$(sed -n 's/^  no sticking at omega = \([0-9.]*\).*/\1/p' "$work/stdout")
awk -v e="$end" 'BEGIN { exit !(e > 0.305 && e < 0.308) }' || fail "end at omega = $end"
below=$(awk -v e="$end" 'BEGIN { printf "%.6f", e - 1e-3 }')
above=$(awk -v e="$end" 'BEGIN { printf "%.6f", e + 1e-3 }')
"$impactkit" orbit --omega "$below" --sticking >"$work/below" ||
  fail "no sticking orbit at omega = $below, below the end: $(cat "$work/below")"
if "$impactkit" orbit --omega "$above" --sticking >"$work/above" 2>&1; then
  fail "a sticking orbit at omega = $above, above the end"
fi
grep -q "does not stick periodically" "$work/above" || fail "unexpected: $(cat "$work/above")"

"$impactkit" continue --omega 0.27 --param c --from 0.1 --to 0.01 --switch-pd \
  --plot "$work/pd.png" --out "$work/pd.csv" >"$work/pd" || fail "--switch-pd: $(cat "$work/pd")"
grep -q '^  period doubling at c = 0.034' "$work/pd" || fail "no period doubling: $(cat "$work/pd")"
grep -q '^branch pd1: *P(inf,2) k=2 doubled' "$work/pd" || fail "not doubled: $(cat "$work/pd")"
[[ -s $work/pd.png && -s $work/pd.pd1.csv ]] || fail "no figure or doubled branch's CSV"
# The doubled family's fifth point: c, then its two stick phases (sorted).
read -r c s1 s2 < <(grep -v '^#' "$work/pd.pd1.csv" | sed -n 6p |
  awk -F, '{ a = $3; b = $4; if (a > b) { t = a; a = b; b = t } print $1, a, b }')
"$impactkit" orbit --omega 0.27 --set "c=$c" >"$work/o" || fail "orbit at c = $c: $(cat "$work/o")"
grep -q 'sticking P(inf,2) at omega = 0.27, 2 sticking phases' "$work/o" ||
  fail "the simulation's orbit at c = $c: $(cat "$work/o")"
read -r o1 o2 < <(sed -n '/^sticking:/{n;p;n;p}' "$work/o" | awk '{ print $1 }' | sort -g | xargs)
awk -v a="$s1" -v b="$s2" -v c="$o1" -v d="$o2" \
  'BEGIN { exit !((a - c) ^ 2 < 1e-16 && (b - d) ^ 2 < 1e-16) }' ||
  fail "stick phases $s1 $s2 on the branch, $o1 $o2 from the simulation"
echo ok
