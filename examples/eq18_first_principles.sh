#!/usr/bin/env bash
# The paper's conjecture (its §3.5.1): do the chaotic attractors near grazing
# at Ω = 1.701, 1.72, 1.75 and 1.81 obey a one-dimensional square-root map
# like its Eq. 18? Sets the map computed from first principles at the nearby
# grazing orbits (the discontinuity-map normal form of every grazing the
# connected diagram locates in Ω 1.6-1.9, reduced to Eq. 18 where one real
# multiplier dominates) beside Eq. 18 fitted to the simulated low-velocity
# return map (`impactkit returnmap --fit`), coefficient by coefficient.
# docs/paper-reproduction.md shows and explains the table. About 3 minutes on
# 2 cores (the diagram).
#
#   examples/eq18_first_principles.sh [impactkit binary] [data folder]
#
# Defaults: ./build/apps/impactkit, ./out/eq18.
set -euo pipefail
impactkit=${1:-./build/apps/impactkit}
data=${2:-./out/eq18}
mkdir -p "$data"
"$impactkit" diagram --from 1.6 --to 1.9 --json "$data/diagram.json" > "$data/diagram.txt"
for omega in 1.701 1.72 1.75 1.81; do
  # A periodic attractor gives no map to fit (no slow impacts, or one point):
  # the table says so.
  "$impactkit" returnmap --omega "$omega" --periods 20000 --fit \
    --json "$data/returnmap-$omega.json" > "$data/returnmap-$omega.txt" 2>&1 || true
done
python3 - "$data" <<'EOF'
import json
import os
import sys

data = sys.argv[1]
diagram = json.load(open(os.path.join(data, "diagram.json")))
# One row per grazing orbit (a grazing seen from both its branches is one).
grazings = {}
for branch in diagram["branches"]:
    for s in branch["special_points"]:
        form = s.get("normal_form")
        if s["type"] == "grazing" and form:
            grazings[(round(form["param"], 8), form["p"], form["q"])] = form
forms = sorted(grazings.values(), key=lambda f: f["param"])
reduced = [f for f in forms if f["reduced"]]
print(f"grazing orbits in Omega 1.6-1.9: {len(forms)}; reducing to Eq. 18: {len(reduced)} "
      f"(dominance |l2/l1| at most {max(f['reduced']['dominance'] for f in reduced):.3g}); "
      f"stable: {sum(not f['prediction']['unstable_grazing_orbit'] for f in forms)}")


def describe(form, omega):
    modulus = abs(complex(*form["eigenvalues"][0]))
    prediction = form["prediction"]
    line = (f"  P({form['p']},{form['q']}) touches at {form['param']:.7f}: "
            f"leading |multiplier| {modulus:.4g}, "
            + ("unstable" if prediction["unstable_grazing_orbit"] else "stable")
            + f" (past it: {prediction['motion']}, "
            + ("near it" if prediction["local"] else "a jump") + ")")
    red = form["reduced"]
    if not red:
        return line + "; no reduction (" + form["reduction_note"] + ")"
    past = form["unfolding"] * (omega - form["param"]) > 0
    where = (f"Omega {omega} is past it: d = {red['break_rate'] * (omega - form['param']):.4g}"
             if past else f"Omega {omega} is before it (no contact)")
    return (line + f"; Eq. 18: lambda = {red['lambda']:.4g}, s = {red['s']:+.0f}, "
            f"kappa = {red['kappa']:.4g}, dominance {red['dominance']:.3g}; {where}")


for omega in (1.701, 1.72, 1.75, 1.81):
    print(f"Omega = {omega}")
    path = os.path.join(data, f"returnmap-{omega}.json")
    fit = json.load(open(path)) if os.path.exists(path) else None
    if fit and fit["termination"] == "converged":
        p, e = fit["parameters"], fit["standard_error"]
        print(f"  fitted Eq. 18: lambda = {p['lambda']:.4f} +- {e['lambda']:.4f}, "
              f"s = {p['s']:.4f} +- {e['s']:.4f}, d = {p['d']:.4f} +- {e['d']:.4f}, "
              f"rms {fit['rms_residual']:.3g} over {fit['points']} pairs")
    else:
        pairs = fit["points"] if fit else 0
        print(f"  fitted Eq. 18: none (a periodic attractor: {pairs} slow-impact pairs"
              + (", all one point" if pairs else "") + ")")
    below = [f for f in forms if f["param"] <= omega][-1:]
    above = [f for f in forms if f["param"] > omega][:1]
    stable = [f for f in forms if not f["prediction"]["unstable_grazing_orbit"]]
    nearest_stable = min(stable, key=lambda f: abs(f["param"] - omega))
    shown = below + above
    for form in shown + ([nearest_stable] if nearest_stable not in shown else []):
        print(describe(form, omega))
EOF
