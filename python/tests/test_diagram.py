"""impactkit.trace_diagram: the same network as `impactkit diagram --start`
(the command-line tool's JSON), and its period doublings at multiplier -1
when re-solved by an independent Newton solve."""

import json
import os
import subprocess

import numpy as np
import pytest

import impactkit


@pytest.fixture(scope="module")
def diagram(paper_orbit):
    system, orbit = paper_orbit
    return impactkit.trace_diagram([(system, orbit)], lower=1.5, upper=1.8, max_depth=2)


def test_graph_shape(diagram):
    assert diagram.parameter == "omega" and len(diagram.branches) >= 2
    edges = len(diagram.edge_from)
    for array in (diagram.edge_to, diagram.edge_branch, diagram.edge_first, diagram.edge_last):
        assert array.shape == (edges,)
    assert np.all(diagram.edge_from < len(diagram.nodes))
    assert np.all(diagram.edge_to < len(diagram.nodes))
    assert np.all(diagram.edge_first <= diagram.edge_last)
    assert diagram.branches[0].origin == "seed 1" and diagram.branches[0].parent == -1


def test_equals_the_command_line_diagram(diagram, tmp_path):
    out = tmp_path / "d.json"
    subprocess.run([os.environ["IMPACTKIT_CLI"], "diagram", "--from", "1.5", "--to", "1.8",
                    "--start", "1.65", "--p", "1", "--q", "1", "--sweep-values", "0",
                    "--max-depth", "2", "--threads", "1", "--json", str(out)],
                   check=True, capture_output=True)
    cli = json.loads(out.read_text())
    assert [n["type"] for n in cli["nodes"]] == [n.type for n in diagram.nodes]
    assert [n["param"] for n in cli["nodes"]] == [n.parameter for n in diagram.nodes]
    assert [(e["from"], e["to"]) for e in cli["edges"]] == list(zip(diagram.edge_from,
                                                                    diagram.edge_to))


def test_period_doublings_resolved_independently(diagram):
    doublings = [n for n in diagram.nodes if n.type == "period_doubling"]
    assert doublings
    for node in doublings:
        system = impactkit.System.paper(node.parameter)
        orbit = impactkit.find_orbit(system, p=node.p, q=node.q, seed=node.eta)
        assert np.min(np.abs(orbit.multipliers + 1)) < 1e-6
