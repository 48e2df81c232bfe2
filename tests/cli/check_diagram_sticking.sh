#!/usr/bin/env bash
# `impactkit diagram --from 0.2 --to 0.5` on the paper's system: its sweep
# seeds the sticking window's family P(inf,1) beside the chatter orbits'
# windows. The sticking branch ends at no_sticking where `impactkit
# continue` ends it from another start (to 1e-8), and the chatter orbits
# P(n,1) accumulate on that end from above: each family's lowest Omega lies
# above it, nearer the more impacts it has, the longest within 3e-3. A
# --start where the motion sticks seeds the sticking family as continue's.
#
#     check_diagram_sticking.sh IMPACTKIT
source "$(dirname "$0")/testlib.sh"
impactkit=$1

"$impactkit" diagram --from 0.2 --to 0.5 --json "$work/d.json" >"$work/stdout" ||
  fail "impactkit diagram failed: $(cat "$work/stdout")"
"$impactkit" continue --from 0.25 --to 0.5 >"$work/continue" ||
  fail "impactkit continue failed: $(cat "$work/continue")"
end=$(sed -n 's/^  no sticking at omega = \([0-9.]*\).*/\1/p' "$work/continue")
[[ -n $end ]] || fail "continue: no no_sticking end: $(cat "$work/continue")"
python3 - "$work/d.json" "$end" <<'PY' || fail "the diagram's sticking and chatter families"
import json, sys

diagram = json.load(open(sys.argv[1]))
end = float(sys.argv[2])
sticking = [e for e in diagram["edges"] if e["section"] == "release"]
assert sticking and all((e["releases"], e["q"]) == (1, 1) for e in sticking), sticking
ends = [n["param"] for n in diagram["nodes"] if n["type"] == "no_sticking"]
assert len(ends) == 1 and abs(ends[0] - end) < 1e-8, (ends, end)
lowest = {}
for e in diagram["edges"]:
    if e["section"] == "impact" and e["q"] == 1:
        low = min(point["param"] for point in e["points"])
        lowest[e["p"]] = min(low, lowest.get(e["p"], low))
chatter = sorted(p for p in lowest if p >= 5)
assert len(chatter) >= 4, lowest
gaps = [lowest[p] - end for p in chatter]
assert all(g > 0 for g in gaps), gaps
assert all(a > b for a, b in zip(gaps, gaps[1:])), gaps
assert gaps[-1] < 3e-3, gaps
PY
"$impactkit" diagram --from 0.15 --to 0.35 --start 0.2 --sweep-values 0 >"$work/start" ||
  fail "diagram --start at a sticking motion: $(cat "$work/start")"
grep -q "^  main *P(inf,1) from 0.15 to 0.306282" "$work/start" ||
  fail "diagram --start at a sticking motion: $(cat "$work/start")"
echo ok
