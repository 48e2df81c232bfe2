"""impactkit.simulate against closed forms: the steady response of a single
mass with its stop out of reach, and the impact law at every impact."""

import numpy as np
import pytest

import impactkit


def test_free_single_mass_follows_the_closed_form_steady_response():
    m, k, c, a, omega = 1.0, 1.0, 0.1, 0.5, 0.8
    s = impactkit.System.chain(n=1, m=m, k=k, c=c, forcing=[a], omega=omega, xs=100.0)
    # Transients decay like exp(-c t / 2m): below 1e-12 after t = 600.
    r = impactkit.simulate(s, 700.0, record_from=600.0, dt=0.25)
    big_x = a / (k - omega**2 * m + 1j * omega * c)
    t = r["samples"]["t"]
    np.testing.assert_allclose(t, 600.0 + 0.25 * np.arange(401), rtol=0, atol=1e-9)
    exact_x = np.real(big_x * np.exp(1j * omega * t))
    exact_v = np.real(1j * omega * big_x * np.exp(1j * omega * t))
    np.testing.assert_allclose(r["samples"]["x"][:, 0], exact_x, rtol=0, atol=1e-10)
    np.testing.assert_allclose(r["samples"]["v"][:, 0], exact_v, rtol=0, atol=1e-10)
    assert r["impacts"]["t"].size == 0


def test_arrays_shapes_dtypes_and_impact_law():
    s = impactkit.System.paper(0.6)
    r = impactkit.simulate(s, 400.0, record_from=200.0, dt=0.5)
    imp = r["impacts"]
    n = imp["t"].size
    assert n > 10
    assert imp["x"].shape == (n, 2) and imp["v"].shape == (n, 2)
    assert imp["t"].dtype == np.float64
    assert r["samples"]["x"].shape == (401, 2) and r["samples"]["stuck"].dtype == np.bool_
    assert r["sticking"].shape[1] == 2
    # The impacting mass is at the stop moving towards it, phase = t mod T.
    np.testing.assert_allclose(imp["x"][:, 1], 0.1, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(imp["velocity"], imp["v"][:, 1])
    assert np.all(imp["velocity"] > 0)
    period = 2 * np.pi / 0.6
    np.testing.assert_allclose(imp["phase"], np.mod(imp["t"], period), rtol=0, atol=1e-9)
    # Stroboscopic points at whole forcing periods inside the window.
    k = r["strobe"]["t"] / period
    np.testing.assert_allclose(k, np.round(k), rtol=0, atol=1e-12)
    assert r["termination"] == "completed"


def test_impact_arrays_are_not_copies():
    r = impactkit.simulate(impactkit.System.paper(0.6), 100.0)
    for key in ("t", "phase", "velocity", "x", "v"):
        assert not r["impacts"][key].flags.owndata  # owned by the C++ vector


def test_initial_state_is_used():
    s = impactkit.System.chain(n=1, c=0.0, forcing=[0.0], xs=10.0)
    # Undamped, unforced, k = m = 1: x = cos t from x0 = 1.
    r = impactkit.simulate(s, 3.0, x0=[1.0], dt=0.5)
    np.testing.assert_allclose(r["samples"]["x"][:, 0], np.cos(r["samples"]["t"]), atol=1e-12)


def test_bad_state_is_a_value_error():
    with pytest.raises(ValueError):
        impactkit.simulate(impactkit.System.paper(), 10.0, x0=[0.0, 0.5])  # beyond the stop
    with pytest.raises(ValueError, match="chatter"):
        impactkit.simulate(impactkit.System.paper(), 10.0, chatter="sometimes")


def test_sticking_intervals_match_the_stuck_time_and_the_samples():
    # Omega = 0.2: the paper's sticking regime (chatter, then held at the stop).
    s = impactkit.System.paper(0.2)
    period = s.forcing_period
    r = impactkit.simulate(s, 60 * period, record_from=50 * period, dt=0.01)
    intervals = r["sticking"]
    assert intervals.shape[0] > 0 and r["chatter_jumps"] > 0
    np.testing.assert_allclose(np.sum(intervals[:, 1] - intervals[:, 0]), r["stuck_time"],
                               rtol=1e-12)
    samples = r["samples"]
    inside = np.zeros_like(samples["stuck"])
    for begin, end in intervals:
        inside |= (samples["t"] >= begin) & (samples["t"] <= end)
    # Every stuck sample is at the stop at rest, inside an interval.
    stuck = samples["stuck"]
    assert stuck.any() and np.all(inside[stuck])
    np.testing.assert_allclose(samples["x"][stuck, 1], 0.1, rtol=0, atol=1e-12)
    np.testing.assert_allclose(samples["v"][stuck, 1], 0.0, rtol=0, atol=1e-12)


def test_work_bound_and_landings_are_reachable():
    """The work bound of docs/theory.md §4 ends a run with its termination; a mass
    resting on the stop lands instead of impacting at zero speed."""
    system = impactkit.System.paper(1.3)
    system["xs"] = 0.0
    system["c"] = 0.0
    system["r"] = 1.0
    run = impactkit.simulate(system, 20 * 2 * np.pi / 1.3)
    assert run["termination"] == "completed" and run["landings"] >= 1
    assert np.all(run["impacts"]["velocity"] > 1e-8)
    bounded = impactkit.simulate(impactkit.System.paper(0.2), 100.0, max_events_per_period=5)
    assert bounded["termination"] == "work_limit"


def test_events_are_samples_of_their_own_in_time_order():
    s = impactkit.System.paper(0.2)
    period = 2 * np.pi / 0.2
    grid_only = impactkit.simulate(s, 103 * period, record_from=100 * period, dt=0.5)
    r = impactkit.simulate(s, 103 * period, record_from=100 * period, dt=0.5, events=True)
    samples, imp = r["samples"], r["impacts"]
    event = samples["event"]
    assert set(np.unique(event)) == {"", "impact_before", "impact_after", "stick", "release"}
    assert np.all(np.diff(samples["t"]) >= 0)
    # The grid is the one recorded without events.
    grid = event == ""
    np.testing.assert_array_equal(samples["t"][grid], grid_only["samples"]["t"])
    assert set(np.unique(grid_only["samples"]["event"])) == {""}
    # Each impact twice at its instant: before it the impacts' arrays, after
    # it v_c = -r v_c (the impact law, r = 0.7).
    before, after = event == "impact_before", event == "impact_after"
    np.testing.assert_array_equal(samples["t"][before], imp["t"])
    np.testing.assert_array_equal(samples["t"][after], imp["t"])
    np.testing.assert_array_equal(samples["v"][before, 1], imp["velocity"])
    np.testing.assert_allclose(samples["v"][after, 1], -0.7 * imp["velocity"], rtol=0, atol=1e-15)
    # Sticking begins where each interval of r["sticking"] does (inside the
    # window) and releases where it ends.
    sticks, releases = samples["t"][event == "stick"], samples["t"][event == "release"]
    inside = r["sticking"][r["sticking"][:, 0] > 100 * period]
    np.testing.assert_allclose(sticks, inside[:, 0], rtol=0, atol=1e-9)
    assert np.all(samples["stuck"][event == "stick"])
    assert releases.size >= 3
