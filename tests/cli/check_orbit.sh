#!/usr/bin/env bash
# `impactkit orbit --omega 0.6 --json FILE` prints P(2,1) stable and writes
# JSON with p, q, omega, impacts [{phase, v}], multipliers [[re, im]],
# stable and residual; the residual meets the 1e-11 tolerance. The
# finite-difference Jacobian can be checked and reported.
#
#     check_orbit.sh IMPACTKIT
source "$(dirname "$0")/testlib.sh"
impactkit=$1

"$impactkit" orbit --omega 0.6 --json "$work/orbit.json" >"$work/stdout" ||
  fail "impactkit orbit failed: $(cat "$work/stdout")"
grep -q "P(2,1) at omega = 0.6, stable" "$work/stdout" || fail "unexpected summary: $(cat "$work/stdout")"
json=$(tr -d ' \n' <"$work/orbit.json")
for field in '"p":2' '"q":1' '"omega":0.6' '"stable":true' '"impacts":[{"phase":' '"multipliers":[[' '"residual":'; do
  [[ $json == *"$field"* ]] || fail "JSON lacks $field: $json"
done
[[ $(grep -c '"velocity":' "$work/orbit.json") -eq 2 ]] || fail "expected 2 impacts with velocity"
residual=$(sed -n 's/.*"residual": *\([^,]*\).*/\1/p' "$work/orbit.json")
awk -v r="$residual" 'BEGIN { exit !(r <= 1e-11) }' || fail "residual $residual above 1e-11"

# --check-jacobian: the two Jacobians agree to the finite difference's
# truncation error (~1e-7 relative); --jacobian fd reports the multipliers
# of the finite-difference Jacobian, which differ from the analytic ones
# in their last digits, not the analytic ones again.
"$impactkit" orbit --omega 1.4 --p 1 --q 1 --check-jacobian >"$work/check" ||
  fail "orbit --check-jacobian failed: $(cat "$work/check")"
relative=$(sed -n 's/.*(\([^ ]*\) relative to its largest entry).*/\1/p' "$work/check")
[[ -n $relative ]] || fail "no check line: $(cat "$work/check")"
awk -v d="$relative" 'BEGIN { exit !(d > 0 && d < 1e-6) }' || fail "Jacobians differ by $relative"
"$impactkit" orbit --omega 1.4 --p 1 --q 1 --jacobian fd >"$work/fd" || fail "--jacobian fd failed"
grep -q "^jacobian: *finite-difference" "$work/fd" || fail "method not printed: $(cat "$work/fd")"
analytic_first=$(grep -A1 '^multipliers' "$work/check" | tail -1)
fd_first=$(grep -A1 '^multipliers' "$work/fd" | tail -1)
[[ $analytic_first != "$fd_first" ]] || fail "--jacobian fd printed the analytic multipliers"
echo ok
