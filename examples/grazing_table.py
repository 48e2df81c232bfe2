#!/usr/bin/env python3
"""The grazing checks of one diagram as the Markdown table of
docs/continuation.md ("What a grazing will do"): one row per check of
`impactkit diagram --grazings`, with the grazing orbit's leading multiplier
from the diagram's JSON.

    examples/grazing_table.py GRAZINGS.json DIAGRAM.json [--notes TABLE.md]

The last column says why a row is not followed or disagrees. It is taken
from --notes, a Markdown file holding an earlier table of the same form (the
row with the same Ω to 7 digits, grazing orbit and contact), else "unstable"
where the grazing orbit is; rows still without a reason are listed on
standard error, for someone to find out.
"""

import argparse
import json
import sys


def multiplier_text(eigenvalue):
    """The leading multiplier, to 3 digits: signed, or a complex pair's modulus."""
    re, im = eigenvalue
    if abs(im) > 1e-12:
        return f"{abs(complex(re, im)):#.3g}".rstrip(".") + " (pair)"
    return f"{re:#.3g}".rstrip(".").replace("-", "−")


def orbit_text(check, node):
    """The grazing orbit and its contact; at a vanishing impact also the
    family that loses it where that is not the orbit with one impact more."""
    kind = "new contact" if check["contact"] == "new" else "vanishing impact"
    label = check["grazing_orbit"]
    if check["contact"] != "new" and node and label.startswith("P(") and "inf" not in label:
        p, q = (int(x) for x in label[2:-1].split(","))
        if (node["p"], node["q"]) != (p + 1, q):
            return f"{label}, {kind} (P({node['p']},{node['q']})'s)"
    return f"{label}, {kind}"


def result_text(sweeps):
    if sweeps["follows"]:
        result = "agrees" if sweeps["agrees"] else "**disagrees**"
        if not sweeps["agrees"] and not sweeps.get("expected_within_reach", True):
            result += " beyond the normal form's reach"
    elif another_orbit(sweeps):
        result = f"not followed: another {sweeps['past']}"
    else:
        result = "not followed"
    return result + ("; hysteresis" if sweeps["hysteresis"] else "")


def another_orbit(sweeps):
    """The sweep holds an orbit with the grazing orbit's label that is not
    on its family: impact speeds farther than 3 steps of it (the check's
    own rule for `follows`)."""
    gap, step = sweeps.get("family_speed_gap"), sweeps.get("family_speed_step")
    return gap is not None and step is not None and gap > 3 * step


def take_node(check, nodes):
    """The diagram node the check was made at, removed from `nodes`: of
    the same kind of contact, its parameter the nearest (the same number,
    but where a sticking family's vanishing impact is checked at the
    neighbouring family's touch, within 1e-6 of it)."""
    vanishing = check["contact"] != "new"
    kind = [i for i, n in enumerate(nodes) if (n.get("vanishing_impact") is not None) == vanishing]
    if not kind:
        return None
    nearest = min(kind, key=lambda i: abs(nodes[i]["param"] - check["param"]))
    if abs(nodes[nearest]["param"] - check["param"]) > 1e-6 * max(1.0, abs(check["param"])):
        return None
    return nodes.pop(nearest)


def read_notes(path):
    """(Ω to 7 digits, grazing orbit cell) -> the reasons of the rows with
    them in an earlier table, in order."""
    notes = {}
    if not path:
        return notes
    with open(path, encoding="utf-8") as f:
        for line in f:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) == 7 and cells[0][:1].isdigit():
                notes.setdefault((cells[0], cells[1]), []).append(cells[6])
    return notes


def read_json(path, key, writer):
    """The list `key` of the JSON file at `path`, or exit with why not."""
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)[key]
    except (OSError, ValueError) as e:
        sys.exit(f"grazing_table.py: cannot read {path}: {e}")
    except (KeyError, TypeError):
        sys.exit(f"grazing_table.py: {path} has no '{key}' list: is it what {writer} writes?")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("grazings")
    parser.add_argument("diagram")
    parser.add_argument("--notes", help="an earlier table whose last column to keep")
    args = parser.parse_args()
    checks = read_json(args.grazings, "grazings", "impactkit diagram --grazings")
    nodes = [n for n in read_json(args.diagram, "nodes", "impactkit diagram --json")
             if n.get("type") == "grazing"]
    try:
        notes = read_notes(args.notes)
    except OSError as e:
        sys.exit(f"grazing_table.py: cannot read the notes: {e}")
    print("| Ω | grazing orbit | λ | predicted | swept | result | why, where not followed or disagreeing |")
    print("|---|---|---|---|---|---|---|")
    for check in sorted(checks, key=lambda c: c["param"]):
        node = take_node(check, nodes)
        form = node.get("normal_form") if node else None
        sweeps, prediction = check["sweeps"], check["prediction"]
        omega = f"{check['param']:.7f}"
        orbit = orbit_text(check, node)
        earlier = notes.get((omega, orbit))
        why = earlier.pop(0) if earlier else ""
        if not why and not sweeps["follows"] and prediction.get("unstable_grazing_orbit"):
            why = "unstable"
        if not why and not (sweeps["follows"] and sweeps["agrees"]):
            print(f"needs a note: {omega} {orbit}", file=sys.stderr)
        multiplier = multiplier_text(form["eigenvalues"][0]) if form else "—"
        predicted = f"{sweeps['expected']} ({prediction['scenario']})"
        print(
            f"| {omega} | {orbit} | {multiplier} | {predicted} | {sweeps['past']} | "
            f"{result_text(sweeps)} | {why} |"
        )


if __name__ == "__main__":
    main()
