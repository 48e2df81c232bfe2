#!/usr/bin/env bash
# The map commands as a user meets them:
#  - `resonance` for the one-mass chain (n = 1) writes the textbook range
#    2A / sqrt((k - m w^2)^2 + (c w)^2), recomputed here by awk, to 1e-12;
#  - `lyapunov` writes JSON with 4 negative exponents on the P(1,1) at 1.2,
#    a positive largest one at 1.77, and in chatter valid = false, the
#    reason on stdout and stderr, and exit status 1;
#  - `impactmap` writes a provenance line, t,phase,velocity rows (as many as it
#    reports, phases in [0, T)); `returnmap --fit` writes pairs below the
#    bound and the fit as JSON;
#  - bad input exits 2 with one line on stderr and writes nothing.
#
#     check_maps.sh IMPACTKIT
source "$(dirname "$0")/testlib.sh"
impactkit=$1

"$impactkit" resonance --set n=1 --from 0.5 --to 1.5 --steps 11 --out "$work/res.csv" >"$work/out" ||
  fail "resonance failed: $(cat "$work/out")"
run_line_of "$work/res.csv" | grep -q '^resonance --from 0.5 --to 1.5 --steps 11$' ||
  fail "no provenance line: $(run_line_of "$work/res.csv")"
[[ $(columns_of "$work/res.csv") == "omega,range_x1,phase_x1" ]] || fail "header: $(columns_of "$work/res.csv")"
[[ $(grep -v '^#' "$work/res.csv" | tail -n +2 | wc -l) -eq 11 ]] || fail "expected 11 rows"
awk -F, '!/^#/ && ++row > 1 { w = $1; want = 2 * 0.5 / sqrt((1 - w * w)^2 + (0.1 * w)^2);
  if (($2 - want)^2 > (1e-12 * want)^2) { print "row " NR ": " $2 " vs " want; bad = 1 } }
  END { exit bad }' "$work/res.csv" || fail "resonance range differs from the closed form"
grep -q 'x1     1.0' "$work/out" || grep -q 'x1     0.99' "$work/out" || fail "peak near 1 not reported: $(cat "$work/out")"

"$impactkit" lyapunov --omega 1.2 --impacts 500 --json "$work/ly.json" >"$work/out" ||
  fail "lyapunov failed: $(cat "$work/out")"
json=$(tr -d ' \n' <"$work/ly.json")
[[ $json == *'"valid":true'* && $json == *'"largest":-0.1'* ]] || fail "P(1,1) at 1.2: $json"
exponents=$(grep -o '"exponents":\[[^]]*\]' <<<"$json")
[[ $(grep -o -- '-0\.1[0-9]*' <<<"$exponents" | wc -l) -eq 4 ]] || fail "expected 4 exponents near -0.1: $json"
"$impactkit" lyapunov --omega 1.77 >"$work/out" || fail "lyapunov 1.77 failed"
grep -q 'positive: chaotic' "$work/out" || fail "1.77 not chaotic: $(cat "$work/out")"
status=0
"$impactkit" lyapunov --omega 0.2 --json "$work/ly.json" >"$work/out" 2>"$work/err" || status=$?
((status == 1)) || fail "lyapunov 0.2: exit $status, expected 1 (no exponents)"
grep -q '^impactkit: error: Lyapunov exponents not computed: .*chatter' "$work/err" ||
  fail "no reason on stderr: $(cat "$work/err")"
grep -q '"valid": false' "$work/ly.json" || fail "chatter not recorded: $(cat "$work/ly.json")"
grep -q 'not computed: .*chatter' "$work/out" || fail "no reason printed: $(cat "$work/out")"

"$impactkit" impactmap --omega 1.72 --periods 200 --out "$work/im.csv" >"$work/out" ||
  fail "impactmap failed: $(cat "$work/out")"
run_line_of "$work/im.csv" | grep -q '^impactmap --transient 500 --periods 200$' ||
  fail "no provenance line: $(run_line_of "$work/im.csv")"
grep -qx '# parameters: omega=1.72 .*' "$work/im.csv" || fail "no parameters line in im.csv"
reported=$(sed -n 's/^impacts: *\([0-9]*\) with speed.*/\1/p' "$work/out")
[[ -n $reported && $(grep -v '^#' "$work/im.csv" | tail -n +2 | wc -l) -eq $reported ]] ||
  fail "rows differ from the $reported impacts reported"
awk -F, -v T=$(awk 'BEGIN { print 2 * 3.141592653589793 / 1.72 }') \
  '!/^#/ && ++row > 1 && ($2 < 0 || $2 >= T || $3 <= 0) { bad = 1 } END { exit bad }' "$work/im.csv" ||
  fail "a phase outside [0, T) or a non-positive speed"

"$impactkit" returnmap --omega 1.72 --periods 1000 --bound 0.3 --fit --out "$work/rm.csv" \
  --json "$work/fit.json" >"$work/out" || fail "returnmap failed: $(cat "$work/out")"
[[ $(columns_of "$work/rm.csv") == "v_j,v_next" ]] || fail "header: $(columns_of "$work/rm.csv")"
awk -F, '!/^#/ && ++row > 1 && ($1 >= 0.3 || $2 >= 0.3) { bad = 1 } END { exit bad }' "$work/rm.csv" ||
  fail "a pair at or above the bound"
json=$(tr -d ' \n' <"$work/fit.json")
for field in '"termination":"converged"' '"parameters":{"d":' '"standard_error":' '"rms_residual":'; do
  [[ $json == *"$field"* ]] || fail "fit JSON lacks $field: $json"
done

# expect_bad MESSAGE ARGS...: exit 2, one line naming MESSAGE, no file left.
expect_bad() {
  local expected=$1 status=0
  shift
  mkdir -p "$work/bad"
  "$impactkit" "$@" --out "$work/bad/x.csv" >"$work/stdout" 2>"$work/stderr" || status=$?
  [[ $status -eq 2 && $(wc -l <"$work/stderr") -eq 1 ]] ||
    fail "$*: exit $status, stderr: $(cat "$work/stderr")"
  grep -qF -- "$expected" "$work/stderr" || fail "$*: stderr lacks '$expected': $(cat "$work/stderr")"
  [[ -z $(ls -A "$work/bad") ]] || fail "$*: left $(ls -A "$work/bad")"
}
expect_bad "--steps must be >= 1, got 0" resonance --steps 0
expect_bad "from = to = 1 with steps = 5" resonance --from 1 --to 1 --steps 5
expect_bad "--from and --to must satisfy 0 < --from <= --to" resonance --from 2 --to 1
expect_bad "--transient must be >= 0" impactmap --transient -1
expect_bad "--periods must be >= 1" impactmap --periods 0
expect_bad "need --fit" returnmap --fit-to 0.2
echo ok
