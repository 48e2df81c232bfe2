"""Exceptions: ValueError with the library's message (the same line the
command-line tool prints for the same input), NumericalError for numerical
failures, KeyboardInterrupt out of long calls."""

import os
import signal
import subprocess

import numpy as np
import pytest

import impactkit


def cli_error(*args):
    """The one-line error the `impactkit` tool prints for the same input."""
    if "IMPACTKIT_CLI" not in os.environ:
        pytest.skip("the impactkit tool is not built (IMPACTKIT_BUILD_APPS=OFF)")
    run = subprocess.run([os.environ["IMPACTKIT_CLI"], *args], capture_output=True, text=True)
    assert run.returncode == 2
    return run.stderr.strip()


@pytest.mark.parametrize("name,value,flag", [("r", 1.5, "r=1.5"), ("m", 0.0, "m=0"),
                                             ("omega", -1.0, "omega=-1")])
def test_value_error_has_the_library_message(name, value, flag):
    s = impactkit.System.paper()
    with pytest.raises(ValueError) as error:
        s[name] = value
    assert str(error.value)
    assert str(error.value) in cli_error("simulate", "--set", flag)


def test_numerical_error_is_a_runtime_error_with_the_summary():
    s = impactkit.System.paper(1.65)
    with pytest.raises(impactkit.NumericalError) as error:
        impactkit.find_orbit(s, p=1, q=1, seed=[0.0, 0.5, 0.1, 0.1], max_iterations=1,
                             least_squares_fallback=False)
    assert isinstance(error.value, RuntimeError)
    assert str(error.value).startswith("no convergence: residual")
    # One Newton iteration on the map, then one on the fixed-time equations
    # (FindOrbit's fallback near grazing, docs/theory.md §5b).
    assert "after 2 iterations" in str(error.value)
    assert "fixed-time formulation" in str(error.value)


@pytest.mark.parametrize("kwargs, message", [
    ({"seed": [0.0, 0.0, 0.1], "releases": 0}, "releases must be >= 1"),
    ({"seed": [0.0, 0.0, 0.1], "releases": 1, "q": 0}, "releases and q must be >= 1"),
    ({"releases": 1, "p": 2}, "give p (an impacting orbit) or releases"),
    ({"seed": [0.0, 0.0], "releases": 1}, "has 3 entries, got 2"),
    ({"seed": [0.0, 0.0, float("nan")], "releases": 1}, "NaN or infinite entry"),
    ({"seed": [0.0, 0.0, 1.0], "releases": 1, "stop": 3}, "stop must be in [0, 0]"),
    ({"releases": 1, "transient": -1}, "transient must be >= 0"),
])
def test_find_orbit_refuses_bad_sticking_input(kwargs, message):
    with pytest.raises(ValueError) as error:
        impactkit.find_orbit(impactkit.System.paper(0.2), **kwargs)
    assert message in str(error.value)


def interrupt_after(seconds):
    """A SIGALRM that raises KeyboardInterrupt, as Ctrl-C does."""
    def handler(signum, frame):
        raise KeyboardInterrupt
    signal.signal(signal.SIGALRM, handler)
    signal.setitimer(signal.ITIMER_REAL, seconds)


def test_ctrl_c_stops_a_long_simulation():
    interrupt_after(0.2)
    # About 10^8 impacts: minutes unless the interrupt stops it.
    with pytest.raises(KeyboardInterrupt):
        impactkit.simulate(impactkit.System.paper(0.6), 3e8)


def test_ctrl_c_interrupts_a_run_without_impacts():
    """No events at all: the simulator still asks its observers every 1000
    forcing periods."""
    far = impactkit.System.paper(1.0)
    far["xs"] = 10.0
    interrupt_after(0.5)
    with pytest.raises(KeyboardInterrupt):
        impactkit.simulate(far, 1e13, record_from=1e13 - 10)


def test_ctrl_c_stops_a_long_continuation(paper_orbit):
    system, orbit = paper_orbit
    interrupt_after(0.2)
    with pytest.raises(KeyboardInterrupt):
        impactkit.continue_branch(system, orbit, from_=1.6, to=1.7, initial_step=1e-7,
                                  max_step=1e-7, min_step=1e-8, max_points=100000000,
                                  locate_bifurcations=False)


def test_ctrl_c_stops_a_long_sweep():
    interrupt_after(0.2)
    with pytest.raises(KeyboardInterrupt):
        impactkit.sweep(impactkit.System.paper(), steps=2000, threads=2, chunk_values=5)


@pytest.mark.parametrize("call,message", [
    (lambda: impactkit.simulate(impactkit.System.paper(), 1e9, dt=1e-9), r"at most 1e\+08"),
    (lambda: impactkit.System.general(np.eye(2), np.zeros((2, 2)), np.eye(2), [1, 0],
                                      contact_dof=2), r"contact_dof must be in \[0, 1\]"),
    (lambda: impactkit.find_orbit(impactkit.System.paper(), seed=[1, 2]), "has 4 entries, got 2"),
    (lambda: impactkit.sweep(impactkit.System.paper(), steps=0), "steps must be >= 1"),
    (lambda: impactkit.lyapunov(impactkit.System.paper(), [1, 2, 3]), "has 4 entries, got 3"),
])
def test_bad_input_is_refused_before_any_work(call, message):
    with pytest.raises(ValueError, match=message):
        call()
