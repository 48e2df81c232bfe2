"""impactkit.continue_curve: the period-doubling curve of the paper's P(1,1)
in (omega, r). Every sampled point, re-solved by an independent Newton
solve at its (omega, r), has a multiplier -1; and the curve and its files
equal the command line's (`impactkit curve --json --out`)."""

import json
import os
import subprocess

import numpy as np
import pytest

import impactkit


@pytest.fixture(scope="module")
def curve():
    system = impactkit.System.paper(1.6)
    branch = impactkit.continue_branch(system, impactkit.find_orbit(system, p=1, q=1),
                                       from_=0.5, to=3.0, direction="both")
    pd = min((p for p in branch.special_points if p.type == "period_doubling"),
             key=lambda p: abs(p.parameter - 1.6))
    return impactkit.continue_curve(system, branch, pd, parameter2="r", from_=0.5, to=3.0,
                                    from2=0.3, to2=0.95)


def test_arrays(curve):
    n = len(curve)
    assert n > 10 and curve.type == "period_doubling" and (curve.p, curve.q) == (1, 1)
    assert curve.values.shape == (n,) and curve.values2.shape == (n,)
    assert np.all((curve.values2 >= 0.3 - 1e-12) & (curve.values2 <= 0.95 + 1e-12))
    assert curve.begin in {"parameter_bound", "grazing", "sticking"}


def test_points_have_a_multiplier_minus_one_independently(curve):
    for i in range(0, len(curve), 5):
        system = impactkit.System.paper(curve.values[i])
        system["r"] = curve.values2[i]
        orbit = impactkit.find_orbit(system, p=1, q=1, seed=curve.orbits[i].eta)
        assert np.min(np.abs(orbit.multipliers + 1)) < 1e-8


def test_equals_the_command_line(curve, tmp_path):
    out, table = tmp_path / "c.json", tmp_path / "c.csv"
    subprocess.run([os.environ["IMPACTKIT_CLI"], "curve", "--type", "period_doubling", "--p", "1",
                    "--q", "1", "--omega", "1.6", "--param", "omega", "--param2", "r", "--from",
                    "0.5", "--to", "3", "--from2", "0.3", "--to2", "0.95", "--json", str(out),
                    "--out", str(table)],
                   check=True, capture_output=True)
    document = json.loads(out.read_text())
    cli = document["curves"][0]
    assert [point["omega"] for point in cli["points"]] == list(curve.values)
    assert [point["r"] for point in cli["points"]] == list(curve.values2)
    assert (cli["begin_reason"], cli["end_reason"]) == (curve.begin, curve.end)
    # The files' one schema (io/curve_output.hpp): the same document but
    # for the wall time, the provenance and the system, the same rows.
    mine = json.loads(curve.to_json())
    assert mine["codim2_points"] == document["codim2_points"]
    assert mine["params"] == document["params"]
    cli.pop("seconds")
    mine["curves"][0].pop("seconds")
    assert mine["curves"][0] == cli
    py_table = tmp_path / "py.csv"
    curve.write_csv(py_table)

    def data_lines(path):
        return [line for line in path.read_text().splitlines() if not line.startswith("#")]

    assert data_lines(py_table) == data_lines(table)
