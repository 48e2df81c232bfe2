"""impactkit.continue_branch: each point re-solved by Newton on its own, and
the special points' multipliers at their critical values."""

import json
import os

import numpy as np
import pytest

import impactkit

TYPES = {"fold", "period_doubling", "neimark_sacker", "grazing", "sticking", "branch_point"}


@pytest.fixture(scope="module")
def branch(paper_orbit):
    system, orbit = paper_orbit
    return impactkit.continue_branch(system, orbit, from_=1.5, to=1.8, direction="both")


def test_arrays(branch):
    n = len(branch)
    assert n > 10 and branch.parameter == "omega" and (branch.p, branch.q) == (1, 1)
    assert branch.values.shape == (n,) and branch.eta.shape == (n, 4)
    assert branch.multipliers.shape == (n, 4) and branch.multipliers.dtype == np.complex128
    assert branch.stable.dtype == np.bool_
    np.testing.assert_array_equal(branch.stable, np.all(np.abs(branch.multipliers) < 1, axis=1))
    assert np.all((branch.values >= 1.5) & (branch.values <= 1.8))
    assert branch.begin is not None and branch.end in {"parameter_bound", "grazing"}


def test_points_are_orbits_by_an_independent_newton_solve(branch):
    for i in range(0, len(branch), 10):
        system = impactkit.System.paper(branch.values[i])
        orbit = impactkit.find_orbit(system, p=1, q=1, seed=branch.eta[i])
        np.testing.assert_allclose(orbit.eta, branch.eta[i], rtol=0, atol=1e-9)


def test_special_points_are_objects_at_their_critical_multipliers(branch):
    assert branch.special_points
    for sp in branch.special_points:
        assert sp.type in TYPES
        assert sp.describe("omega").startswith(sp.type.replace("_", " "))
        if sp.type == "period_doubling":
            assert abs(sp.multiplier + 1) < 1e-6
            assert np.min(np.abs(sp.multipliers + 1)) < 1e-6
            assert sp.eigenvector.shape == (4,)
        if sp.type == "fold":
            assert abs(sp.multiplier - 1) < 1e-6


def test_period_doubling_switches_to_a_genuinely_doubled_branch():
    system = impactkit.System.paper(1.0)
    single = impactkit.continue_branch(system, impactkit.find_orbit(system, p=1, q=1),
                                       from_=0.5, to=2.0, direction="both")
    pd = next(sp for sp in single.special_points if sp.type == "period_doubling")
    start = impactkit.doubled_branch_start(system, single, pd)
    assert start is not None and (start.orbit.p, start.orbit.q) == (2, 2)
    doubled = impactkit.continue_branch(start, from_=1.5, to=1.8, max_points=40)
    assert (doubled.p, doubled.q) == (2, 2) and len(doubled) > 5
    # A point away from the doubling, re-solved by Newton on its own, has two
    # distinct impact speeds (not P(1,1) traversed twice).
    i = len(doubled) - 1
    orbit = impactkit.find_orbit(impactkit.System.paper(doubled.values[i]), p=2, q=2,
                                 seed=doubled.eta[i])
    np.testing.assert_allclose(orbit.eta, doubled.eta[i], rtol=0, atol=1e-9)
    assert abs(orbit.impact_velocities[0] - orbit.impact_velocities[1]) > 1e-3
    with pytest.raises(ValueError, match="period_doubling"):
        impactkit.doubled_branch_start(system, single, single.special_points[0])


def test_a_period_doubling_not_located_is_listed_with_its_step():
    # P(160,128), doubled from P(80,64) at its period doubling (eta recorded
    # from `impactkit diagram --from 0.4 --to 2.3`), doubles again where its
    # orbits are at their rounding floor: not located there, it is listed
    # with the step that holds it, which the cascade's ratio (Feigenbaum's
    # 4.6692, from P(40,32)'s and P(80,64)'s doublings) predicts to ~1e-9.
    omega, p40_doubling = 1.7060150349934093, 1.706015065643547
    system = impactkit.System.paper(omega)
    eta = [0.13809216395673257, 2.353563004550682, -1.3356099128280987, 0.06652775885643308]
    orbit = impactkit.find_orbit(system, p=80, q=64, seed=eta)
    single = impactkit.continue_branch(system, orbit, from_=omega - 8e-4, to=omega + 8e-4,
                                       direction="both")
    pd = next(sp for sp in single.special_points
              if sp.type == "period_doubling" and abs(sp.parameter - omega) < 1e-6)
    start = impactkit.doubled_branch_start(system, single, pd)
    doubled = impactkit.continue_branch(start, from_=omega - 8e-4, to=omega + 8e-4)
    assert (doubled.p, doubled.q) == (160, 128)
    [step] = doubled.unlocated
    assert step.type == "period_doubling"
    predicted = omega - (p40_doubling - omega) / 4.6692
    assert min(step.values) - 1e-9 < predicted < max(step.values) + 1e-9
    assert json.loads(doubled.to_json())["unlocated"] == [
        {"type": "period_doubling", "from": step.values[0], "to": step.values[1],
         "description": step.describe("omega")}]


def test_grazing_seeds_refine_to_orbits_with_one_impact_more_or_fewer():
    system = impactkit.System.paper(1.0)
    single = impactkit.continue_branch(system, impactkit.find_orbit(system, p=1, q=1),
                                       from_=0.5, to=2.0, direction="both")
    graze = next(sp for sp in single.special_points if sp.type == "grazing")
    seeds = impactkit.seeds_at_grazing(system, single, graze)
    assert seeds and all(s.p in (0, 2) and s.q == 1 for s in seeds)
    refined = []
    for seed in seeds:
        try:
            refined.append(impactkit.find_orbit(seed.system, p=seed.p, q=seed.q, stop=seed.stop,
                                                seed=seed.eta))
        except impactkit.NumericalError:
            pass  # a side of the grazing where that orbit does not exist
    assert refined and all(o.residual < 1e-10 and o.p == 2 for o in refined)



def test_grazing_seed_at_the_second_stop_refines_with_its_stop():
    # The clearance example's P(16,6) loses an impact at the lower stop
    # near 1.258: the seed for P(15,6) lies there, and refined at that stop
    # its family has its new contact where P(16,6)'s impact vanishes.
    path = os.path.join(os.environ["IMPACTKIT_SOURCE_DIR"], "examples/systems/clearance-1dof.toml")
    system = impactkit.System.from_file(path).with_parameter("omega", 1.29)
    single = impactkit.continue_branch(system, impactkit.find_orbit(system, p=8, q=3),
                                       from_=1.25, to=1.29, direction="decreasing")
    pd = next(sp for sp in single.special_points if sp.type == "period_doubling")
    doubled = impactkit.continue_branch(impactkit.doubled_branch_start(system, single, pd),
                                        from_=1.25, to=1.29)
    assert doubled.end == "grazing"
    end = doubled.special_points[-1]
    seed = next(s for s in impactkit.seeds_at_grazing(system, doubled, end)
                if s.p == 15 and s.system.get("omega") < end.parameter)
    assert seed.stop == 1 and seed.releases == 0
    orbit = impactkit.find_orbit(seed.system, p=seed.p, q=seed.q, stop=seed.stop, seed=seed.eta)
    reduced = impactkit.continue_branch(seed.system, orbit, from_=1.25, to=1.29)
    assert reduced.end == "grazing"
    assert abs(reduced.values[-1] - end.parameter) < 1e-9

def test_sticking_family_ends_where_the_simulation_stops_sticking():
    # The paper's sticking orbit at Omega = 0.2, continued as any orbit is:
    # its family ends at no_sticking near 0.30628 (docs/continuation.md), and
    # the simulation from rest (find_orbit's own seed where the motion sticks) sticks 1e-3
    # below the end and not 1e-3 above it.
    system = impactkit.System.paper(0.2)
    orbit = impactkit.find_orbit(system)
    assert orbit.section == "release" and (orbit.releases, orbit.q) == (1, 1)
    branch = impactkit.continue_branch(system, orbit, from_=0.2, to=0.5)
    assert branch.section == "release" and branch.releases == 1 and branch.p == 0
    assert branch.end == "no_sticking" and branch.special_points[-1].type == "no_sticking"
    end = branch.values[-1]
    assert 0.305 < end < 0.308
    below = impactkit.find_orbit(impactkit.System.paper(end - 1e-3), releases=1)
    assert below.contact_margin > 0
    with pytest.raises(ValueError, match="does not stick periodically"):
        impactkit.find_orbit(impactkit.System.paper(end + 1e-3), releases=1)


def test_sticking_family_period_doubles_onto_the_simulations_period_two_sticking():
    # In c at Omega = 0.27 the sticking family period-doubles near c = 0.0342;
    # a point of the doubled family, P(inf,2) with two sticking phases, is the
    # sticking orbit seeded by the simulation there.
    system = impactkit.System.paper(0.27)
    single = impactkit.continue_branch(system, impactkit.find_orbit(system),
                                       parameter="c", from_=0.01, to=0.1,
                                       direction="decreasing")
    pd = next(sp for sp in single.special_points if sp.type == "period_doubling")
    assert 0.03 < pd.parameter < 0.04
    start = impactkit.doubled_branch_start(system, single, pd)
    assert start is not None and start.orbit.releases == 2
    doubled = impactkit.continue_branch(start, parameter="c", from_=0.01, to=0.1)
    assert doubled.section == "release" and (doubled.releases, doubled.q) == (2, 2)
    i = len(doubled) // 2
    c = doubled.values[i]
    seeded = impactkit.find_orbit(system.with_parameter("c", c))
    assert (seeded.releases, seeded.q) == (2, 2)
    np.testing.assert_allclose(np.sort(seeded.stick_phases),
                               np.sort(doubled.orbits[i].stick_phases), rtol=0, atol=1e-8)


def test_a_branch_with_its_defaults_equals_the_command_line(tmp_path):
    # No step flag on either side: both take the library's defaults, and
    # write the library's schema (io/branch_output.hpp), row for row and
    # field for field.
    import json
    import os
    import subprocess

    def data_lines(path):
        with open(path) as f:
            return [line for line in f if not line.startswith("#")]

    cli_csv, cli_json = tmp_path / "cli.csv", tmp_path / "cli.json"
    subprocess.run([os.environ["IMPACTKIT_CLI"], "continue", "--p", "1",
                    "--q", "1", "--from", "1.65", "--to", "1.8", "--out", str(cli_csv),
                    "--json", str(cli_json)], check=True, capture_output=True)
    system = impactkit.System.paper(1.65)
    branch = impactkit.continue_branch(system, impactkit.find_orbit(system, p=1, q=1),
                                       from_=1.65, to=1.8)
    py_csv = tmp_path / "py.csv"
    branch.write_csv(py_csv)
    assert data_lines(py_csv) == data_lines(cli_csv)
    with open(cli_json) as f:
        cli = json.load(f)
    mine = json.loads(branch.to_json())
    for key in ("section", "p", "q", "points", "end_reason", "end_message", "param_range",
                "special_points"):
        assert mine[key] == cli[key], key
    with pytest.raises(OSError):
        branch.write_csv(tmp_path / "missing" / "x.csv")


def test_a_branch_followed_both_ways_equals_continue_start(tmp_path):
    # `continue --start` finds the orbit at --start and follows it both
    # ways, with the library's defaults: Python's branch through the same
    # orbit, direction both, is the same file row for row.
    import os
    import subprocess

    cli_csv = tmp_path / "cli.csv"
    subprocess.run([os.environ["IMPACTKIT_CLI"], "continue", "--p", "1", "--q", "1", "--from",
                    "1.65", "--to", "1.8", "--start", "1.7", "--out", str(cli_csv)], check=True,
                   capture_output=True)
    system = impactkit.System.paper(1.7)
    branch = impactkit.continue_branch(system, impactkit.find_orbit(system, p=1, q=1),
                                       from_=1.65, to=1.8, direction="both")
    assert branch.begin is not None
    py_csv = tmp_path / "py.csv"
    branch.write_csv(py_csv)
    with open(py_csv) as mine, open(cli_csv) as theirs:
        assert ([line for line in mine if not line.startswith("#")] ==
                [line for line in theirs if not line.startswith("#")])



def test_a_user_test_of_python_is_located_along_the_branch(branch):
    # The impact speed crossing a level between its values at the branch's
    # ends: located like a bifurcation, and the orbit solved afresh at the
    # located omega has that speed (1e-9).
    level = 0.5 * (branch.orbits[0].impact_velocities[0] + branch.orbits[-1].impact_velocities[0])
    system = impactkit.System.paper(1.65)
    start = impactkit.find_orbit(system, p=1, q=1)
    tests = {"speed": lambda orbit: orbit.impact_velocities[0] - level}
    mine = impactkit.continue_branch(system, start, from_=1.5, to=1.8, direction="both",
                                     user_tests=tests)
    found = [s for s in mine.special_points if s.type == "user_test"]
    assert found and all(s.user_test == "speed" for s in found)
    for s in found:
        again = impactkit.find_orbit(impactkit.System.paper(s.parameter), p=1, q=1, seed=s.orbit.eta)
        assert abs(again.impact_velocities[0] - level) < 1e-9
    assert "user_test" in [p["type"] for p in json.loads(mine.to_json())["special_points"]]
    with pytest.raises(ValueError, match="not callable"):
        impactkit.continue_branch(system, start, from_=1.5, to=1.8, user_tests={"x": 1})

    def broken(orbit):
        raise ZeroDivisionError("from the user's test")

    with pytest.raises(ZeroDivisionError, match="from the user's test"):
        impactkit.continue_branch(system, start, from_=1.5, to=1.8,
                                  user_tests={"broken": broken})


def test_a_grazing_carries_its_normal_form_and_prediction_as_the_command_line_writes_them(
        tmp_path):
    # P(1,1) grazes the stop at omega = 0.8564 (a new contact). Its normal
    # form's multipliers are the orbit's, by another computation (the impact
    # map's Jacobian); past the grazing no attractor stays near it and the
    # motion jumps to P(3,2) (docs/continuation.md, "What a grazing will do").
    import os
    import subprocess

    system = impactkit.System.paper(0.9)
    branch = impactkit.continue_branch(system, impactkit.find_orbit(system, p=1, q=1),
                                       from_=0.9, to=0.8, direction="decreasing")
    graze = branch.special_points[-1]
    assert graze.type == "grazing"
    form = graze.normal_form
    eigenvalues = np.array([complex(re, im) for re, im in form["eigenvalues"]])
    np.testing.assert_allclose(eigenvalues, graze.multipliers, atol=1e-8)
    assert form["prediction"]["local"] is False
    assert form["prediction"]["motion"] == "P(3,2)"
    assert form["prediction"]["side"] == -1.0
    assert all(s.normal_form is None for s in branch.special_points if s.type != "grazing")
    cli_json = tmp_path / "cli.json"
    subprocess.run([os.environ["IMPACTKIT_CLI"], "continue", "--p", "1", "--q", "1",
                    "--from", "0.9", "--to", "0.8", "--json", str(cli_json)],
                   check=True, capture_output=True)
    with open(cli_json) as f:
        cli = json.load(f)
    assert cli["special_points"][-1]["normal_form"] == form


def test_a_sticking_familys_grazing_carries_its_normal_form_through_chatter_and_release():
    # On paper-mass1-stop.toml the sticking family from omega = 0.2 meets a
    # fourth impact of mass 1 at 0.1901614 going down. Its normal form's
    # monodromy runs through the chatter, the stuck phase and the release:
    # its multipliers are the release map's (another computation: the
    # section's Jacobian) and two zeros. Just past it the new contact comes
    # every other period (docs/theory.md §6b).
    import os

    path = os.path.join(os.environ["IMPACTKIT_SOURCE_DIR"], "examples", "systems",
                        "paper-mass1-stop.toml")
    system = impactkit.System.from_file(path)
    start = impactkit.find_orbit(system)
    assert start.releases == 1
    branch = impactkit.continue_branch(system, start, from_=0.2, to=0.18,
                                       direction="decreasing")
    graze = branch.special_points[-1]
    assert graze.type == "grazing"
    form = graze.normal_form
    assert form["releases"] == 1
    eigenvalues = np.array([complex(re, im) for re, im in form["eigenvalues"]])
    np.testing.assert_allclose(eigenvalues[:2], graze.multipliers, atol=1e-8)
    assert np.all(np.abs(eigenvalues[2:]) < 1e-12)
    assert form["prediction"]["local"] is True
    assert form["prediction"]["motion"] == "P(inf,2)"
