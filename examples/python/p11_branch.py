#!/usr/bin/env python3
"""The paper's P(1,1) branch from Python (its Fig. 5): impact velocity
against omega, stable solid and unstable dashed, special points marked.

    python3 examples/python/p11_branch.py [figure.png]

Default: out/figures/p11_branch_python.png (a second or two).
"""

import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import impactkit


def main():
    figure = sys.argv[1] if len(sys.argv) > 1 else "out/figures/p11_branch_python.png"
    system = impactkit.System.paper(1.0)
    orbit = impactkit.find_orbit(system, p=1, q=1)
    branch = impactkit.continue_branch(system, orbit, parameter="omega", from_=0.5, to=2.0,
                                       direction="both")
    print(branch)
    for sp in branch.special_points:
        print("  " + sp.describe("omega"))

    # The impact velocity is the last coordinate of eta (v_2 before impact).
    velocity = branch.eta[:, -1]
    fig, ax = plt.subplots(figsize=(7, 4))
    stable = np.where(branch.stable, velocity, np.nan)
    unstable = np.where(branch.stable, np.nan, velocity)
    ax.plot(branch.values, stable, "-k", label="stable")
    ax.plot(branch.values, unstable, "--k", label="unstable")
    colours = {}  # one colour and one legend entry per type
    for sp in branch.special_points:
        label = sp.type.replace("_", " ")
        new = label not in colours
        colours.setdefault(label, f"C{len(colours)}")
        ax.plot(sp.parameter, sp.orbit.impact_velocities[0], "o", color=colours[label],
                label=label if new else None)
    ax.set_xlabel(r"$\Omega$")
    ax.set_ylabel("impact velocity")
    ax.set_title("P(1,1) branch")
    ax.legend()
    os.makedirs(os.path.dirname(os.path.abspath(figure)), exist_ok=True)
    fig.savefig(figure, dpi=150)
    print(f"wrote {figure}")


if __name__ == "__main__":
    main()
