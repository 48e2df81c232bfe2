#!/usr/bin/env bash
# The grazing of P(5,8) at Omega = 1.8232386 (docs/continuation.md, "What a
# grazing will do"): the motion past it from sweeps started on P(5,8) below
# the grazing, long transients (6000 periods, 1000 recorded, periods up to
# q = 128), beside the normal form's attractor at the same distances (its map
# iterated with numpy from the normal form the Python module returns). About
# 20 seconds.
#
#   examples/grazing_1823_sequence.sh [impactkit binary] [data folder]
#
# Defaults: ./build/apps/impactkit, ./out/grazing-1823. The Python part needs
# numpy and the impactkit module (installed, or PYTHONPATH=build/python);
# PYTHON names the interpreter (default python3).
set -euo pipefail
impactkit=${1:-./build/apps/impactkit}
data=${2:-./out/grazing-1823}
mkdir -p "$data"
sweep() {  # from, to, steps, summary file
  "$impactkit" sweep --from "$1" --to "$2" --steps "$3" --chunk 0 --transient 6000 \
    --record 1000 --max-q 128 --summary "$4" > /dev/null
}
# From P(5,8) at 1.8228 up through the grazing: every 1e-6 close to it,
# every 5e-5 beyond.
sweep 1.8228 1.82326 461 "$data/near.csv"
sweep 1.8228 1.8240 25 "$data/far.csv"
echo "simulated (omega, motion), past the grazing:"
for file in near far; do
  awk -F, '!/^#/ && $1 > 1.8232386 && $1 != "omega" {
    print "  " $1 ": " ($2 == "periodic" ? "P(" $3 "," $4 ")" : $2) }' "$data/$file.csv"
done
"${PYTHON:-python3}" - <<'PY'
import numpy as np

import impactkit

system = impactkit.System.paper(1.8231)
branch = impactkit.continue_branch(system, impactkit.find_orbit(system, p=5, q=8),
                                   from_=1.8231, to=1.8240, direction="increasing")
form = next(s for s in branch.special_points if s.type == "grazing").normal_form
a, n, w = (np.array(form[k]) for k in ("linear", "normal", "root"))


def step(z, mu):
    depth = n @ z + mu
    return (a @ (z + w * np.sqrt(depth)), True) if depth > 0 else (a @ z, False)


def attractor(distance):
    """The normal form's attractor at omega* + distance: P(5N + I, 8N)."""
    mu, z = form["unfolding"] * distance, np.zeros(len(w))
    for _ in range(20000):
        z, _ = step(z, mu)
    states, contacts = [], []
    for _ in range(3000):
        z, hit = step(z, mu)
        states.append(z)
        contacts.append(hit)
    states = np.array(states)
    for period in range(1, 400):
        if np.abs(states[period:] - states[:-period]).max() < 1e-9 * np.abs(states).max():
            return f"P({5 * period + sum(contacts[:period])},{8 * period})"
    return "aperiodic"


print(f"normal form at the grazing omega* = {form['param']:.10f}, past it:")
for distance in (5e-7, 1.5e-6, 3e-6, 5e-6, 2e-5, 5e-5, 1e-4, 2e-4, 5e-4):
    print(f"  {form['param'] + distance:.7f} (omega* + {distance:.1e}): {attractor(distance)}")
PY
