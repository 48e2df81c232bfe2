"""No memory leak over 10^4 calls: the resident set stays put."""

import numpy as np

import impactkit


def resident_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * 4096


def test_no_leak_over_ten_thousand_calls(paper_orbit):
    system, orbit = paper_orbit

    def calls(n):
        for _ in range(n):
            o = impactkit.find_orbit(system, p=1, q=1, seed=orbit.eta)
            o.multipliers, o.jacobian, o.impact_times
            impactkit.simulate(system, 20.0)["impacts"]["x"]
            try:
                system.set("r", 2.0)
            except ValueError:
                pass

    calls(1000)  # allocator pools and caches reach their steady size
    before = resident_bytes()
    calls(10000)
    # Leaking what one round returns (over 1 kB: an orbit, its arrays, the
    # simulation's dict) would add over 10 MB; 1 MB leaves room for the
    # allocator's own noise.
    assert resident_bytes() - before < 1 << 20
