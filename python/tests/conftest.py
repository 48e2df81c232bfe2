"""Shared fixtures: orbits of the paper's system."""

import pytest

import impactkit


@pytest.fixture(scope="session")
def paper_orbit():
    """The unstable P(1,1) orbit at omega = 1.65, between a period doubling and a fold."""
    system = impactkit.System.paper(1.65)
    return system, impactkit.find_orbit(system, p=1, q=1)


@pytest.fixture(scope="session")
def stable_orbit():
    """The stable P(1,1) orbit at omega = 1.0 (multipliers of modulus <= 0.54)."""
    system = impactkit.System.paper(1.0)
    return system, impactkit.find_orbit(system, p=1, q=1)
