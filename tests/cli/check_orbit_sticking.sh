#!/usr/bin/env bash
# `impactkit orbit --omega 0.2 --json FILE` refines the paper's sticking
# motion into a sticking orbit: prints "sticking P(inf,1) ... stable" and
# writes JSON with kind "sticking", q, stick_phases, release_phases,
# stuck_durations, chatter and multipliers, residual <= 1e-11. The same
# orbit from its own release state with --sticking --guess has the same
# release phase, and the analytic Jacobian agrees with finite differences.
# With a second stop (paper-mass1-stop.toml: under mass 1, struck between
# releases) the orbit sticks at stop 2 and says so, in the JSON too, and a
# guess there needs --stop 2; a clearance's mass sticks at both stops in
# one orbit, released where the contact force vanishes in closed form.
#
#     check_orbit_sticking.sh IMPACTKIT
source "$(dirname "$0")/testlib.sh"
impactkit=$1

"$impactkit" orbit --omega 0.2 --json "$work/orbit.json" >"$work/stdout" ||
  fail "impactkit orbit failed: $(cat "$work/stdout")"
grep -q "sticking P(inf,1) at omega = 0.2, 1 sticking phase, stable" "$work/stdout" ||
  fail "unexpected summary: $(cat "$work/stdout")"
json=$(tr -d ' \n' <"$work/orbit.json")
for field in '"kind":"sticking"' '"q":1' '"releases":1' '"stable":true' '"stick_phases":[' \
  '"release_phases":[' '"stuck_durations":[' '"chatter":[{' '"fast_impacts":[{' \
  '"multipliers":[['; do
  [[ $json == *"$field"* ]] || fail "JSON lacks $field: $json"
done
residual=$(sed -n 's/.*"residual": *\([^,]*\).*/\1/p' "$work/orbit.json")
awk -v r="$residual" 'BEGIN { exit !(r <= 1e-11) }' || fail "residual $residual above 1e-11"

# The release state (x1, v1, t) of the JSON as a guess: the same orbit.
state=$(tr -d ' \n' <"$work/orbit.json" | sed -n 's/.*"state":\[\([^]]*\)\].*/\1/p')
[[ -n $state ]] || fail "no state in the JSON"
"$impactkit" orbit --omega 0.2 --sticking --q 1 --guess "$state" --check-jacobian \
  >"$work/guess" || fail "orbit --sticking --guess failed: $(cat "$work/guess")"
release() { grep -A1 '^sticking:' "$1" | tail -1 | awk '{ print $2 }'; }
[[ $(release "$work/guess") == $(release "$work/stdout") ]] ||
  fail "release phase $(release "$work/guess") from the guess, $(release "$work/stdout") seeded"
relative=$(sed -n 's/.*(\([^ ]*\) relative to its largest entry).*/\1/p' "$work/guess")
awk -v d="$relative" 'BEGIN { exit !(d > 0 && d < 1e-6) }' || fail "Jacobians differ by $relative"
systems="$(dirname "$0")/../../examples/systems"
"$impactkit" orbit --system "$systems/paper-mass1-stop.toml" --sticking --json "$work/two.json" \
  >"$work/two" || fail "orbit --sticking on two stops failed: $(cat "$work/two")"
grep -q "1 sticking phase at stop 2, stable" "$work/two" || fail "unexpected summary: $(cat "$work/two")"
grep -q "velocity .*  stop 1$" "$work/two" || fail "no impact at stop 1 listed: $(cat "$work/two")"
[[ $(tr -d ' \n' <"$work/two.json") == *'"stop":2,"stuck_durations"'* ]] ||
  fail "the JSON does not name stop 2: $(cat "$work/two.json")"
state=$(tr -d ' \n' <"$work/two.json" | sed -n 's/.*"state":\[\([^]]*\)\].*/\1/p')
"$impactkit" orbit --system "$systems/paper-mass1-stop.toml" --sticking --q 1 --guess "$state" \
  --stop 2 >"$work/two-guess" || fail "orbit --sticking --guess --stop 2 failed: $(cat "$work/two-guess")"
[[ $(release "$work/two-guess") == $(release "$work/two") ]] ||
  fail "release phase $(release "$work/two-guess") from the guess, $(release "$work/two") seeded"
refused "the system has 2 stops" "$impactkit" orbit --system "$systems/paper-mass1-stop.toml" \
  --sticking --q 1 --guess "$state" --stop 3
# The clearance's mass sticks at both stops: released from +0.5 where
# Fs = cos(0.2 t) - 0.5 falls through 0 (0.2 t = pi/3) and from -0.5 where
# -(cos(0.2 t) + 0.5) does (0.2 t = 4 pi/3).
"$impactkit" orbit --sticking --system "$systems/clearance-1dof.toml" --omega 0.2 \
  >"$work/both" || fail "sticking at both stops failed: $(cat "$work/both")"
grep -q "2 sticking phases at stops 1 and 2, stable" "$work/both" ||
  fail "unexpected summary: $(cat "$work/both")"
awk '/^sticking:/ { getline a; getline b; print a; print b }' "$work/both" |
  awk 'function abs(x) { return x < 0 ? -x : x }
       { want = ($4 == 1 ? 1 : 4) * atan2(0, -1) / 0.6; stops[$4] = 1
         if (abs($2 - want) > 1e-9) { print "release " $2 " at stop " $4 ", want " want; bad = 1 } }
       END { exit bad || !(1 in stops) || !(2 in stops) }' ||
  fail "release phases: $(cat "$work/both")"
echo ok
