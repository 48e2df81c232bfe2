#!/usr/bin/env bash
# `impactkit orbit --omega 0.6 --json FILE` prints P(2,1) stable and writes
# JSON with p, q, omega, impacts [{phase, v}], multipliers [[re, im]],
# stable and residual; the residual meets the 1e-11 tolerance.
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
[[ $(grep -c '"v":' "$work/orbit.json") -eq 2 ]] || fail "expected 2 impacts with v"
residual=$(sed -n 's/.*"residual": *\([^,]*\).*/\1/p' "$work/orbit.json")
awk -v r="$residual" 'BEGIN { exit !(r <= 1e-11) }' || fail "residual $residual above 1e-11"
echo ok
