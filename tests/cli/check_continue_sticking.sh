#!/usr/bin/env bash
# `impactkit continue --from 0.2 --to 0.5` from the paper's sticking motion
# follows the sticking family P(inf,1) in omega up to where its chatter
# stops ending in sticking (omega ~ 0.3063, docs/continuation.md): the end
# is a no_sticking special point, the CSV has one row per point, and the
# simulation 1e-3 below the end still sticks while 1e-3 above it does not.
#
#     check_continue_sticking.sh IMPACTKIT
source "$(dirname "$0")/testlib.sh"
impactkit=$1

"$impactkit" continue --from 0.2 --to 0.5 --out "$work/b.csv" --json "$work/b.json" \
  >"$work/stdout" || fail "impactkit continue failed: $(cat "$work/stdout")"
grep -q '^start: *sticking P(inf,1) at omega = 0.2, stable' "$work/stdout" ||
  fail "unexpected start: $(cat "$work/stdout")"
grep -q '^end: *no_sticking' "$work/stdout" || fail "unexpected end: $(cat "$work/stdout")"
json=$(tr -d ' \n' <"$work/b.json")
for field in '"kind":"sticking"' '"end_reason":"no_sticking"' '"type":"no_sticking"' \
  '"points":[{"clearance":' '"param":0.2,' '"parameter":"omega"' '"param_range":[0.2,'; do
  [[ $json == *"$field"* ]] || fail "JSON lacks $field"
done
columns_of "$work/b.csv" | grep -q '^omega,stick_phase,release_phase,stuck_duration,contact_margin' ||
  fail "unexpected CSV header: $(columns_of "$work/b.csv")"
end=$(sed -n 's/^special: *no_sticking at omega = \([0-9.]*\).*/\1/p' "$work/stdout")
awk -v e="$end" 'BEGIN { exit !(e > 0.305 && e < 0.308) }' || fail "end at omega = $end"
below=$(awk -v e="$end" 'BEGIN { printf "%.6f", e - 1e-3 }')
above=$(awk -v e="$end" 'BEGIN { printf "%.6f", e + 1e-3 }')
"$impactkit" orbit --omega "$below" --sticking >"$work/below" ||
  fail "no sticking orbit at omega = $below, below the end: $(cat "$work/below")"
if "$impactkit" orbit --omega "$above" --sticking >"$work/above" 2>&1; then
  fail "a sticking orbit at omega = $above, above the end"
fi
grep -q "does not stick periodically" "$work/above" || fail "unexpected: $(cat "$work/above")"
echo ok
