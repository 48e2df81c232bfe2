"""docs/python.md and the README must not rot: their ```python blocks run
in order, in one namespace per file, from the source tree (their paths are
relative to it), and the errors the comments show are the ones raised."""

import contextlib
import io
import os
import re

SOURCE = os.environ["IMPACTKIT_SOURCE_DIR"]


def run_blocks(path, monkeypatch):
    """Runs the file's python blocks; returns what they print and how many."""
    text = open(os.path.join(SOURCE, path)).read()
    blocks = re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)
    monkeypatch.chdir(SOURCE)
    namespace = {}
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        for block in blocks:
            exec(compile(block, path, "exec"), namespace)
    return out.getvalue(), len(blocks)


def test_readme_block_runs(monkeypatch):
    printed, count = run_blocks("README.md", monkeypatch)
    assert count == 1 and "period_doubling" in printed


def test_python_md_blocks_run_as_shown(monkeypatch):
    printed, count = run_blocks("docs/python.md", monkeypatch)
    assert count >= 8
    assert "r (coefficient of restitution) must be in [0, 1], got 1.5" in printed
    assert "no convergence: residual 1.28e+00 after 2 iterations" in printed
    # The tables: the command line's columns.
    assert "['omega', 'r', 'kind', 'p', 'q', 'max_velocity', 'range_xN', 'lyapunov']" in printed
    assert "['t', 'phase', 'velocity', 'x1', 'x2', 'v1', 'v2', 'stop']" in printed
