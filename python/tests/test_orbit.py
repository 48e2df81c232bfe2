"""impactkit.find_orbit (impacting and sticking orbits) against a long
simulation that settles on the orbit, and the analytic multipliers against
the finite-difference ones."""

import warnings

import numpy as np
import pytest

import impactkit


def test_stable_orbit_is_where_the_simulation_settles(stable_orbit):
    system, orbit = stable_orbit
    assert (orbit.p, orbit.q, orbit.omega) == (1, 1, 1.0)
    assert orbit.stable and orbit.residual < 1e-11
    assert orbit.eta.shape == (4,) and orbit.jacobian.shape == (4, 4)
    assert orbit.multipliers.dtype == np.complex128
    assert np.all(np.abs(orbit.multipliers) < 1)
    # Multipliers of modulus <= 0.54: 0.54^2000 -- after 2000 periods the
    # simulation is on the orbit to machine precision.
    r = impactkit.simulate(system, 2000 * system.forcing_period)
    np.testing.assert_allclose(r["impacts"]["velocity"][-1], orbit.impact_velocities[0], rtol=1e-9)
    np.testing.assert_allclose(r["impacts"]["phase"][-1], orbit.impact_phases[0], rtol=1e-9)


def test_seeded_from_simulation_without_p_and_q():
    system = impactkit.System.paper(0.6)
    orbit = impactkit.find_orbit(system)
    r = impactkit.simulate(system, 1000 * system.forcing_period)
    # The paper's P(2,1) at omega = 0.6: two impact speeds per period.
    assert (orbit.p, orbit.q) == (2, 1)
    np.testing.assert_allclose(np.sort(r["impacts"]["velocity"][-2:]),
                               np.sort(orbit.impact_velocities), rtol=1e-8)


def test_unstable_orbit(paper_orbit):
    system, orbit = paper_orbit
    assert not orbit.stable and np.max(np.abs(orbit.multipliers)) > 1


def test_analytic_and_finite_difference_multipliers_agree(paper_orbit):
    system, orbit = paper_orbit
    fd = impactkit.find_orbit(system, p=1, q=1, seed=orbit.eta, jacobian="finite_difference")
    np.testing.assert_allclose(np.sort_complex(fd.multipliers),
                               np.sort_complex(orbit.multipliers), rtol=0, atol=1e-6)


def test_an_impact_below_the_arrival_resolution_is_warned_of():
    # One mass 1e-7 below the grazing of its P(1,1) (tests/test_orbit_grazing.cpp):
    # the impact, speed 7.4e-9, rises 4e-17 above the stop, which a
    # simulation cannot resolve; the orbit is returned with a warning.
    system = impactkit.System.general([[2.0]], [[0.1]], [[3.0]], [1.2],
                                      omega=3.674043151526545, xs=0.05, r=0.75)
    with pytest.warns(RuntimeWarning, match="below the arrival resolution"):
        orbit = impactkit.find_orbit(system, seed=[0.8509, 7.4e-9])
    np.testing.assert_allclose(orbit.impact_velocities[0], 7.4228e-9, rtol=1e-4)
    farther = impactkit.System.general([[2.0]], [[0.1]], [[3.0]], [1.2],
                                       omega=3.674033251526545, xs=0.05, r=0.75)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        impactkit.find_orbit(farther, seed=[0.8509130733897027, 7.422846623612595e-07])


def test_sticking_orbit_is_the_simulations_steady_sticking():
    # Omega = 0.2: the motion sticks once per period, so find_orbit without
    # a seed returns the sticking orbit P(inf,1) on the release section.
    system = impactkit.System.paper(0.2)
    period = system.forcing_period
    orbit = impactkit.find_orbit(system)
    assert orbit.section == "release" and (orbit.releases, orbit.q) == (1, 1)
    assert orbit.stable and orbit.eta.shape == (3,)
    # Independent: the simulation's last whole stuck interval, 300 periods
    # from rest, begins and ends at the orbit's stick and release phases.
    r = impactkit.simulate(system, 300 * period, record_from=297 * period)
    begin, end = r["sticking"][-2]
    np.testing.assert_allclose(np.mod(begin, period), orbit.stick_phases[0], rtol=0, atol=1e-8)
    np.testing.assert_allclose(np.mod(end, period), orbit.release_phases[0], rtol=0, atol=1e-8)
    # The same solve from a later release time, and with the central-
    # difference Jacobian (the multipliers agree).
    again = impactkit.find_orbit(system, releases=1, q=1, seed=orbit.eta + [0.0, 0.0, 1e-3])
    np.testing.assert_allclose(again.eta, orbit.eta, rtol=0, atol=1e-9)
    fd = impactkit.find_orbit(system, releases=1, q=1, seed=orbit.eta,
                              jacobian="finite_difference")
    np.testing.assert_allclose(np.sort_complex(fd.multipliers),
                               np.sort_complex(orbit.multipliers), rtol=0, atol=1e-6)


def test_a_mass_sticking_at_both_stops_of_a_clearance():
    # One mass between +-0.5 at omega = 0.2 sticks at each stop once per
    # period: one orbit of two releases. Held at +0.5 the stop pushes with
    # Fs = cos(omega t) - 0.5, released at omega t = pi/3; at -0.5 with
    # -(cos(omega t) + 0.5), released at omega t = 4 pi/3.
    omega = 0.2
    clearance = impactkit.System.chain(n=1, forcing=[1.0], omega=omega).with_stops([
        {"dof": 0, "side": "upper", "position": 0.5, "restitution": 0.8},
        {"dof": 0, "side": "lower", "position": -0.5, "restitution": 0.8}])
    orbit = impactkit.find_orbit(clearance)
    assert orbit.section == "release" and (orbit.releases, orbit.q) == (2, 1)
    assert sorted(orbit.stuck_stops) == [0, 1]
    expected = np.where(orbit.stuck_stops == 0, np.pi / 3, 4 * np.pi / 3) / omega
    np.testing.assert_allclose(orbit.release_phases, expected, rtol=0, atol=1e-10)
