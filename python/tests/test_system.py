"""impactkit.System against the paper's parameters and the chain's closed form."""

import os

import numpy as np
import pytest

import impactkit


def coupling(n):
    """E of docs/theory.md §1: tridiagonal, E_ii = 2 (i < n), E_nn = 1, off-diagonals -1."""
    e = 2.0 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1)
    e[-1, -1] = 1.0
    return e


def test_default_is_the_paper_system():
    s = impactkit.System()
    assert s.dof == 2 and s.is_chain and s.stops[0]["dof"] == 1
    assert [s[n] for n in ("omega", "xs", "r", "A1", "A2", "m", "k", "c", "n")] == [
        1.0, 0.1, 0.7, 0.5, 0.0, 1.0, 1.0, 0.1, 2.0]
    np.testing.assert_array_equal(s.stiffness, coupling(2))
    np.testing.assert_array_equal(s.damping, 0.1 * coupling(2))
    np.testing.assert_array_equal(s.mass, np.eye(2))
    assert s.forcing_period == pytest.approx(2 * np.pi, rel=1e-15)


def test_chain_matrices_are_the_uniform_chain():
    s = impactkit.System.chain(n=4, m=2.0, k=3.0, c=0.2, forcing=[1, 0, 0, 0.5])
    np.testing.assert_array_equal(s.mass, 2.0 * np.eye(4))
    np.testing.assert_allclose(s.stiffness, 3.0 * coupling(4), rtol=0, atol=1e-15)
    np.testing.assert_allclose(s.damping, 0.2 * coupling(4), rtol=0, atol=1e-15)
    np.testing.assert_array_equal(s.forcing, [1, 0, 0, 0.5])
    assert s.stops[0]["dof"] == 3


def test_general_system_keeps_its_matrices():
    m = np.diag([1.0, 0.8, 1.2])
    k = np.array([[2.5, -1.5, 0], [-1.5, 2.5, -1], [0, -1, 1]])
    c = np.array([[0.15, -0.05, 0], [-0.05, 0.1, -0.05], [0, -0.05, 0.05]])
    s = impactkit.System.general(m, c, k, [0.5, 0, 0], omega=1.2, contact_dof=1)
    np.testing.assert_array_equal(s.mass, m)
    np.testing.assert_array_equal(s.stiffness, k)
    np.testing.assert_array_equal(s.damping, c)
    assert not s.is_chain and s.stops[0]["dof"] == 1 and s["omega"] == 1.2
    assert "m" not in s.parameter_names()


def test_from_file_reads_the_shipped_three_mass_system():
    path = os.path.join(os.environ["IMPACTKIT_SOURCE_DIR"], "examples/systems/three-mass.toml")
    s = impactkit.System.from_file(path)
    # The file's values (1-based contact_dof = 3 in the file).
    np.testing.assert_array_equal(s.mass, np.diag([1.0, 0.8, 1.2]))
    assert s.stops[0]["dof"] == 2 and s["omega"] == 1.2 and s["xs"] == 0.1


def test_parameters_by_name():
    s = impactkit.System.paper()
    s["omega"] = 1.3
    s.set("k", 2.0)
    assert s.get("omega") == 1.3
    np.testing.assert_array_equal(s.stiffness, 2.0 * coupling(2))
    s["n"] = 3
    assert s.dof == 3 and list(s.forcing) == [0.5, 0.0, 0.0]
    copy = s.with_parameter("r", 0.5)
    assert copy["r"] == 0.5 and s["r"] == 0.7


def test_invalid_set_leaves_the_system_unchanged():
    s = impactkit.System.paper()
    with pytest.raises(ValueError, match=r"r \(coefficient of restitution\) must be in \[0, 1\]"):
        s["r"] = 1.5
    assert s["r"] == 0.7
    with pytest.raises(ValueError, match="unknown"):
        s.get("zeta")


def test_json_round_trip(tmp_path):
    s = impactkit.System.chain(n=3, c=0.05, omega=0.9)
    path = tmp_path / "s.json"
    path.write_text(s.to_json())
    back = impactkit.System.from_file(path)
    np.testing.assert_array_equal(back.damping, s.damping)
    assert back["omega"] == 0.9


def test_stops_as_dicts_and_impacts_name_their_stop():
    clearance = impactkit.System.chain(n=1, forcing=[1.0]).with_stops([
        {"dof": 0, "side": "upper", "position": 0.5, "restitution": 0.8},
        {"dof": 0, "side": "lower", "position": -0.5}])
    assert clearance.stops == [
        {"dof": 0, "side": "upper", "position": 0.5, "restitution": 0.8},
        {"dof": 0, "side": "lower", "position": -0.5, "restitution": 0.7}]
    assert clearance["xs2"] == -0.5 and clearance["r2"] == 0.7
    impacts = impactkit.simulate(clearance, 200 * clearance.forcing_period,
                                 record_from=190 * clearance.forcing_period)["impacts"]
    # Each impact is at its stop's position, moving into it.
    upper, lower = impacts["stop"] == 0, impacts["stop"] == 1
    assert upper.any() and lower.any() and (upper | lower).all()
    np.testing.assert_array_equal(impacts["x"][upper, 0], 0.5)
    np.testing.assert_array_equal(impacts["x"][lower, 0], -0.5)
    assert (impacts["v"][upper, 0] > 0).all() and (impacts["v"][lower, 0] < 0).all()
    with pytest.raises(ValueError, match="leave it no room"):
        clearance.with_stops([{"dof": 0, "position": 0.1}, {"dof": 0, "side": "lower", "position": 0.2}])
    with pytest.raises(ValueError, match="unknown key 'sid'"):
        clearance.with_stops([{"dof": 0, "position": 0.1, "sid": "lower"}])


def test_orbit_of_a_clearance_names_the_stop_of_each_impact():
    clearance = impactkit.System.chain(n=1, forcing=[1.0], omega=1.0).with_stops([
        {"dof": 0, "side": "upper", "position": 0.5, "restitution": 0.8},
        {"dof": 0, "side": "lower", "position": -0.5, "restitution": 0.8}])
    orbit = impactkit.find_orbit(clearance)  # seeded by simulation, at whichever stop
    assert (orbit.p, orbit.q) == (2, 1)
    assert sorted(orbit.impact_stops.tolist()) == [0, 1]
    # Symmetric: the same speed at both stops, half a period apart.
    assert orbit.impact_velocities[0] == pytest.approx(orbit.impact_velocities[1], rel=1e-12)
    gap = (orbit.impact_times[1] - orbit.impact_times[0]) % clearance.forcing_period
    assert gap == pytest.approx(clearance.forcing_period / 2, rel=1e-10)
    # A seed given by hand says its stop (0-based).
    again = impactkit.find_orbit(clearance, p=2, q=1, seed=orbit.eta, stop=int(orbit.impact_stops[0]))
    np.testing.assert_allclose(again.eta, orbit.eta, rtol=0, atol=1e-12)
    with pytest.raises(ValueError, match="stop must be in"):
        impactkit.find_orbit(clearance, p=2, q=1, seed=orbit.eta, stop=2)
