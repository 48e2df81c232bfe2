"""The module's results equal the C++ library's bit for bit: the paper's
P(1,1) orbit at omega = 1.65 and its branch over [1.5, 1.8], as printed in
hexadecimal by reference_values.cpp."""

import os
import subprocess

import numpy as np
import pytest

import impactkit


@pytest.fixture(scope="module")
def reference():
    out = subprocess.run([os.environ["IMPACTKIT_REFERENCE"]], check=True, capture_output=True,
                         text=True).stdout
    lines = {}
    for line in out.splitlines():
        key, *fields = line.split()
        lines.setdefault(key, []).append(fields)
    return lines


def test_orbit(reference):
    fields = reference["orbit"][0]
    values = [float.fromhex(f) for f in fields[2:]]
    system = impactkit.System.paper(1.65)
    orbit = impactkit.find_orbit(system, p=1, q=1)
    assert (orbit.p, orbit.q) == (int(fields[0]), int(fields[1]))
    assert orbit.omega == values[0]
    np.testing.assert_array_equal(orbit.eta, values[1:5])
    m = np.array(values[5:]).reshape(-1, 2)
    np.testing.assert_array_equal(orbit.multipliers, m[:, 0] + 1j * m[:, 1])


def test_branch(reference):
    fields = reference["branch"][0]
    system = impactkit.System.paper(1.65)
    orbit = impactkit.find_orbit(system, p=1, q=1)
    branch = impactkit.continue_branch(system, orbit, from_=1.5, to=1.8, direction="both")
    assert len(branch) == int(fields[0])
    np.testing.assert_array_equal(branch.values, [float.fromhex(f) for f in fields[1:]])
    specials = [(t, float.fromhex(v)) for t, v in reference.get("special", [])]
    assert [(s.type, s.parameter) for s in branch.special_points] == specials
