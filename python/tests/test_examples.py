"""examples/python/ run as a user runs them (small sizes), each writing its
figure; the branch example's special points are the library's."""

import json
import os
import subprocess
import sys

import impactkit

EXAMPLES = os.path.join(os.environ["IMPACTKIT_SOURCE_DIR"], "examples", "python")


def run(script, *args):
    return subprocess.run([sys.executable, os.path.join(EXAMPLES, script), *args], check=True,
                          capture_output=True, text=True).stdout


def test_fig3(tmp_path):
    figure = tmp_path / "fig3.png"
    out = run("fig3_bifurcation.py", str(figure), "--steps", "25", "--threads", "2")
    assert "25 values" in out
    assert figure.stat().st_size > 10000


def test_p11_branch(tmp_path):
    figure = tmp_path / "p11.png"
    out = run("p11_branch.py", str(figure))
    system = impactkit.System.paper(1.0)
    branch = impactkit.continue_branch(system, impactkit.find_orbit(system, p=1, q=1),
                                       from_=0.5, to=2.0, direction="both")
    for sp in branch.special_points:
        assert sp.describe("omega") in out
    assert figure.stat().st_size > 10000


def test_grazing_table_rows_from_checks_and_notes(tmp_path):
    # Three checks of a made-up diagram: one followed and agreeing (a
    # complex pair), one unstable and not followed, one stable and not
    # followed whose reason only the earlier table knows; and a fourth, at a
    # vanishing impact of a family other than P(p+1,q), with no reason yet.
    def check(param, orbit, contact, follows, agrees, unstable):
        return {"param": param, "grazing_orbit": orbit, "contact": contact,
                "prediction": {"scenario": "jump", "unstable_grazing_orbit": unstable},
                "sweeps": {"expected": "P(3,1)", "past": "P(3,1)", "follows": follows,
                           "agrees": agrees, "hysteresis": True}}

    def node(param, p, q, vanishing, eigenvalue):
        return {"type": "grazing", "param": param, "p": p, "q": q,
                "vanishing_impact": 1 if vanishing else None,
                "normal_form": {"eigenvalues": [eigenvalue]}}

    grazings = tmp_path / "g.json"
    grazings.write_text(json.dumps({"grazings": [
        check(0.5, "P(2,1)", "new", True, True, False),
        check(0.25, "P(4,1)", "vanishing", False, False, True),
        check(0.75, "P(1,1)", "new", False, False, False),
        check(0.875, "P(2,1)", "vanishing", False, False, False)]}))
    diagram = tmp_path / "d.json"
    diagram.write_text(json.dumps({"nodes": [
        node(0.5, 2, 1, False, [0.3, 0.4]), node(0.25, 5, 1, True, [-2.5, 0.0]),
        node(0.75, 1, 1, False, [0.9, 0.0]), node(0.875, 7, 3, True, [0.125, 0.0]),
        {"type": "fold", "param": 0.6}]}))
    notes = tmp_path / "notes.md"
    notes.write_text("| 0.7500000 | P(1,1), new contact | 0.9 | x | x | x | a coexisting P(3,1) |\n")
    script = os.path.join(os.environ["IMPACTKIT_SOURCE_DIR"], "examples", "grazing_table.py")
    done = subprocess.run([sys.executable, script, str(grazings), str(diagram), "--notes",
                           str(notes)], check=True, capture_output=True, text=True)
    rows = done.stdout.splitlines()[2:]
    assert rows == [
        "| 0.2500000 | P(4,1), vanishing impact | −2.50 | P(3,1) (jump) | P(3,1) | "
        "not followed; hysteresis | unstable |",
        "| 0.5000000 | P(2,1), new contact | 0.500 (pair) | P(3,1) (jump) | P(3,1) | "
        "agrees; hysteresis |  |",
        "| 0.7500000 | P(1,1), new contact | 0.900 | P(3,1) (jump) | P(3,1) | "
        "not followed; hysteresis | a coexisting P(3,1) |",
        "| 0.8750000 | P(2,1), vanishing impact (P(7,3)'s) | 0.125 | P(3,1) (jump) | P(3,1) | "
        "not followed; hysteresis |  |"]
    assert done.stderr == "needs a note: 0.8750000 P(2,1), vanishing impact (P(7,3)'s)\n"


def test_grazing_table_refuses_files_it_cannot_use(tmp_path):
    script = os.path.join(os.environ["IMPACTKIT_SOURCE_DIR"], "examples", "grazing_table.py")
    diagram = tmp_path / "d.json"
    diagram.write_text(json.dumps({"nodes": []}))
    wrong = tmp_path / "w.json"
    wrong.write_text(json.dumps({"branches": []}))
    for args, message in (([str(tmp_path / "missing.json"), str(diagram)], "cannot read"),
                          ([str(wrong), str(diagram)], "has no 'grazings' list"),
                          ([str(diagram), str(diagram)], "has no 'grazings' list")):
        done = subprocess.run([sys.executable, script, *args], capture_output=True, text=True)
        assert done.returncode != 0 and message in done.stderr and "Traceback" not in done.stderr
