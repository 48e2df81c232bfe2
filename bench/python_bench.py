#!/usr/bin/env python3
"""The Python module's cost over the C++ library, on the same computations
in the same run (docs/performance.md):

1. find_orbit: P(1,1) of the paper's system at omega = 1.0 from a seed 1e-2
   away from the orbit in every entry, CPU microseconds per call from Python
   and from C++ (bench/python_peer.cpp), and the difference.
2. 10^6 impacts: simulate() of the paper's system at omega = 0.6 (2 impacts
   per forcing period) until about 10^6 impacts, CPU seconds from Python
   (arrays included) and from C++ (the library's ImpactRecorder), and
   whether the arrays share the C++ buffers (no per-element copy).

    PYTHONPATH=build/python /usr/bin/python3 bench/python_bench.py build/bench/python_peer
"""

import subprocess
import sys
import time

import numpy as np

import impactkit


def peer(binary, *args):
    out = subprocess.run([binary, *map(str, args)], check=True, capture_output=True,
                         text=True).stdout
    return {line.split()[0]: line.split()[1:] for line in out.splitlines()}


def per_call(call, seconds=1.0):
    repeats, start = 0, time.process_time()
    while time.process_time() - start < seconds:
        call()
        repeats += 1
    return (time.process_time() - start) / repeats


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else "build/bench/python_peer"

    system = impactkit.System.paper(1.0)
    seed = impactkit.find_orbit(system, p=1, q=1).eta + 1e-2
    cpp = peer(binary, "orbit", 1.0, *[x.hex() for x in seed])
    orbit = impactkit.find_orbit(system, p=1, q=1, seed=seed)
    same = np.array_equal(orbit.eta, [float.fromhex(x) for x in cpp["eta"]])
    python_us = 1e6 * per_call(lambda: impactkit.find_orbit(system, p=1, q=1, seed=seed))
    cpp_us = float(cpp["microseconds"][0])
    print("| find_orbit P(1,1), omega = 1.0 | Python µs/call | C++ µs/call | overhead µs | "
          "same η bit for bit |")
    print("|---|---|---|---|---|")
    print(f"| seed 1e-2 away | {python_us:.1f} | {cpp_us:.1f} | {python_us - cpp_us:.1f} | "
          f"{'yes' if same else 'NO'} |")

    omega = 0.6
    t_end = 5e5 * 2 * np.pi / omega  # 2 impacts per period: 10^6 impacts
    cpp = peer(binary, "impacts", omega, t_end)
    start = time.process_time()
    result = impactkit.simulate(impactkit.System.paper(omega), t_end)
    python_s = time.process_time() - start
    impacts = result["impacts"]
    shared = not any(impacts[k].flags.owndata for k in impacts)
    print()
    print("| simulate to 10^6 impacts, omega = 0.6 | impacts | Python s (with arrays) | "
          "C++ s (ImpactRecorder) | arrays share the C++ buffers |")
    print("|---|---|---|---|---|")
    print(f"| from rest | {impacts['t'].size} (C++ {cpp['impacts'][0]}) | {python_s:.3f} | "
          f"{float(cpp['seconds'][0]):.3f} | {'yes' if shared else 'NO'} |")


if __name__ == "__main__":
    main()
