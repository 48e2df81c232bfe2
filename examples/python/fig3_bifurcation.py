#!/usr/bin/env python3
"""Wagg & Bishop (2001) Fig. 3 from Python: the sweep of omega from 0.1 to
2.5, (a) the max - min of x2 in every recorded forcing period, (b) every
recorded impact speed.

    python3 examples/python/fig3_bifurcation.py [figure.png] [--steps K]

Defaults: out/figures/fig3_python.png, K = 2401.
"""

import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import impactkit


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("figure", nargs="?", default="out/figures/fig3_python.png")
    parser.add_argument("--steps", type=int, default=2401)
    parser.add_argument("--threads", type=int, default=os.cpu_count() or 1)
    args = parser.parse_args()

    result = impactkit.sweep(impactkit.System.paper(), parameter="omega", from_=0.1, to=2.5,
                             steps=args.steps, transient_periods=500, recorded_periods=100,
                             threads=args.threads)
    print(result["report"])
    values = result["values"]
    # One omega per entry: value k owns entries offsets[k] .. offsets[k+1].
    range_omega = np.repeat(values, np.diff(result["range_offsets"]))
    impact_omega = np.repeat(values, np.diff(result["impact_offsets"]))

    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7, 6))
    top.plot(range_omega, result["range_contact"], ",k")
    top.set_ylabel("max - min of $x_2$")
    top.set_title("(a)")
    bottom.plot(impact_omega, result["impact_velocity"], ",k")
    bottom.set_xlabel(r"$\Omega$")
    bottom.set_ylabel("impact velocity")
    bottom.set_title("(b)")
    os.makedirs(os.path.dirname(os.path.abspath(args.figure)), exist_ok=True)
    fig.savefig(args.figure, dpi=150)
    print(f"wrote {args.figure}")


if __name__ == "__main__":
    main()
