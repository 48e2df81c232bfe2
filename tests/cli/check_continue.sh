#!/usr/bin/env bash
# `impactkit continue` on the paper's P(1,1) branch from Omega = 1 both ways:
# the summary names the grazing near 0.856 and the period doubling near
# 1.613; the JSON has special_points with types and end_reason; the CSV has
# a header with the parameters and one row per point; --switch-pd writes the
# P(2,2) branch beside it; --follow-grazing says when the branch meets no
# grazing; a period doubling not located is printed under its branch and
# listed in the JSON's "unlocated". A start that does not converge fails
# with exit 1 and a one-line reason.
#
#     check_continue.sh IMPACTKIT
source "$(dirname "$0")/testlib.sh"
impactkit=$1

"$impactkit" continue --from 0.5 --to 2 --start 1 --switch-pd --out "$work/b.csv" \
  --json "$work/b.json" >"$work/stdout" || fail "impactkit continue failed: $(cat "$work/stdout")"
grep -q "grazing at omega = 0.85643" "$work/stdout" || fail "no grazing near 0.856: $(cat "$work/stdout")"
grep -q "period doubling at omega = 1.61304" "$work/stdout" || fail "no PD near 1.613: $(cat "$work/stdout")"
json=$(tr -d ' \n' <"$work/b.json")
for field in '"special_points":[{' '"type":"grazing"' '"type":"period_doubling"' '"end_reason":"grazing"' \
             '"begin_reason":"grazing"' '"label":"pd1"'; do
  [[ $json == *"$field"* ]] || fail "JSON lacks $field"
done
run_line_of "$work/b.csv" | grep -q '^continue --param omega' || fail "CSV provenance missing"
columns_of "$work/b.csv" | grep -q '^omega,arclength,impact_phase1,impact_velocity1,range_xN,mod1,mod2,mod3,mod4,stable' ||
  fail "unexpected CSV header: $(columns_of "$work/b.csv")"
(($(wc -l <"$work/b.csv") > 50)) || fail "too few CSV rows"
[[ -s "$work/b.pd1.csv" ]] || fail "the period-doubled branch's CSV is missing"
columns_of "$work/b.pd1.csv" | grep -q '^omega,arclength,impact_phase1,impact_phase2,impact_velocity1,impact_velocity2,' || fail "P(2,2) CSV header"

# --follow-grazing where the branch meets no grazing says so, and what to try.
"$impactkit" continue --from 1.0 --to 1.2 --start 1.1 --follow-grazing >"$work/stdout" ||
  fail "impactkit continue --follow-grazing failed"
grep -q "^note: *--follow-grazing: the branch meets no grazing in this range" "$work/stdout" ||
  fail "no note that no grazing was met: $(cat "$work/stdout")"
# ... and nothing of the kind where it followed one.
"$impactkit" continue --from 0.5 --to 1.2 --start 1 --follow-grazing >"$work/stdout" ||
  fail "impactkit continue --follow-grazing failed"
! grep -q "^note:" "$work/stdout" || fail "a note where a grazing was followed: $(cat "$work/stdout")"

# P(160,128), doubled from P(80,64) at its doubling (eta recorded from
# `impactkit diagram --from 0.4 --to 2.3`), doubles again where its orbits
# are at their rounding floor: the step is printed and in the JSON, and holds
# the doubling the cascade's ratio (Feigenbaum's 4.6692, from P(40,32)'s at
# 1.706015065643547 and P(80,64)'s) predicts, 1.70601502843, to 1e-9.
"$impactkit" continue --start 1.7060150349934093 --from 1.7052150349934093 \
  --to 1.7068150349934093 --p 80 --q 64 --switch-pd --json "$work/u.json" \
  --guess 0.13809216395673257,2.353563004550682,-1.3356099128280987,0.06652775885643308 \
  >"$work/stdout" || fail "impactkit continue from P(80,64) failed: $(cat "$work/stdout")"
python3 - "$work/u.json" "$work/stdout" <<'PY' || fail "the unlocated doubling: see above"
import json, sys
branches = json.load(open(sys.argv[1]))["branches"]
doubled = next(b for b in branches if (b["p"], b["q"]) == (160, 128))
[step] = doubled["unlocated"]
assert step["type"] == "period_doubling", step
assert min(step["from"], step["to"]) - 1e-9 < 1.70601502843 < max(step["from"], step["to"]) + 1e-9, step
assert "  " + step["description"] + "\n" in open(sys.argv[2]).read(), step["description"]
PY

if "$impactkit" continue --from 1 --to 2 --p 3 --q 1 --guess 0.3,1,0.5,0.01 2>"$work/stderr"; then
  fail "a start that does not converge was accepted"
else
  rc=$?
fi
((rc == 1)) || fail "exit status $rc, expected 1"
grep -q "^impactkit: error: no P(3,1) orbit found" "$work/stderr" || fail "unclear error: $(cat "$work/stderr")"
echo ok
