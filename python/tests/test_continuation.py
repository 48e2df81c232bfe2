"""impactkit.continue_branch: each point re-solved by Newton on its own, and
the special points' multipliers at their critical values."""

import numpy as np
import pytest

import impactkit

TYPES = {"fold", "period_doubling", "neimark_sacker", "grazing", "sticking", "branch_point"}


@pytest.fixture(scope="module")
def branch(paper_orbit):
    system, orbit = paper_orbit
    return impactkit.continue_branch(system, orbit, lower=1.5, upper=1.8, direction="both")


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
