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


def test_a_resonant_grazing_carries_its_normal_form_as_the_command_line_writes_it(tmp_path):
    # Where P(1,1)'s impact vanishes the curve is the response's grazing; on
    # it the period-doubling curve of P(1,1) leaves at omega = 1.2352,
    # xs = 0.3863 (docs/continuation.md). The grazing orbit there is the
    # response, so the normal form's multipliers are the free flow's over a
    # period, exp(s T) for the eigenvalues s of the first-order matrix of
    # M = I, K = [[2, -1], [-1, 1]], C = 0.1 K: another computation.
    system = impactkit.System.paper(1.2)
    system["xs"] = 0.37
    branch = impactkit.continue_branch(system, impactkit.find_orbit(system, p=1, q=1),
                                       from_=1.2, to=2.0, direction="increasing")
    graze = branch.special_points[-1]
    assert graze.type == "grazing" and graze.vanishing_impact == 0
    curve = impactkit.continue_curve(system, branch, graze, parameter2="xs", from_=0.5, to=3.0,
                                     from2=0.0, to2=8.0)
    resonant = [c for c in curve.codim2_points if c.type == "resonant_grazing_period_doubling"]
    assert len(resonant) == 1
    point = resonant[0]
    assert abs(point.parameter - 1.235190036) < 1e-8
    stiffness = np.array([[2.0, -1.0], [-1.0, 1.0]])
    first_order = np.block([[np.zeros((2, 2)), np.eye(2)], [-stiffness, -0.1 * stiffness]])
    period = 2 * np.pi / point.parameter
    expected = np.exp(np.linalg.eigvals(first_order) * period)
    form = point.normal_form
    eigenvalues = np.array([complex(re, im) for re, im in form["eigenvalues"]])
    assert np.max([np.min(np.abs(expected - e)) for e in eigenvalues]) < 1e-10
    assert form["prediction"]["motion"]
    out = tmp_path / "c.json"
    subprocess.run([os.environ["IMPACTKIT_CLI"], "curve", "--type", "grazing", "--p", "1",
                    "--q", "1", "--omega", "1.2", "--set", "xs=0.37", "--param2", "xs",
                    "--from", "0.5", "--to", "3", "--from2", "0", "--to2", "8", "--json",
                    str(out)], check=True, capture_output=True)
    cli = [c for c in json.loads(out.read_text())["codim2_points"]
           if c["type"] == "resonant_grazing_period_doubling"]
    assert [c["normal_form"] for c in cli] == [form]
