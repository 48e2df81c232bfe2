"""examples/python/ run as a user runs them (small sizes), each writing its
figure; the branch example's special points are the library's."""

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
