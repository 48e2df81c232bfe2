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
    return impactkit.trace_diagram([(system, orbit)], from_=1.5, to=1.8, max_depth=2)


def test_graph_shape(diagram):
    assert diagram.parameter == "omega" and len(diagram.branches) >= 2
    edges = len(diagram.edge_from)
    for array in (diagram.edge_to, diagram.edge_branch, diagram.edge_first, diagram.edge_last):
        assert array.shape == (edges,)
    assert np.all(diagram.edge_from < len(diagram.nodes))
    assert np.all(diagram.edge_to < len(diagram.nodes))
    assert np.all(diagram.edge_first <= diagram.edge_last)
    assert diagram.branches[0].origin == "seed 1" and diagram.branches[0].parent == -1
    # max_depth 2 stops the switching below the doubled branches' own doublings.
    assert diagram.termination == "max_points" and diagram.message == "max_depth (2) reached"


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
    # The files' one schema (io/diagram_output.hpp): the same document but
    # for the wall times, the seed's origin (its caller's words) and what
    # only the command line adds.
    mine = json.loads(diagram.to_json())
    for document in (mine, cli):
        document.pop("seconds")
        for branch in document["branches"]:
            branch.pop("seconds")
            if branch["label"] == "main":
                branch.pop("origin")
    for key in mine:
        assert mine[key] == cli[key], key


def test_period_doublings_resolved_independently(diagram):
    doublings = [n for n in diagram.nodes if n.type == "period_doubling"]
    assert doublings
    for node in doublings:
        system = impactkit.System.paper(node.parameter)
        orbit = impactkit.find_orbit(system, p=node.p, q=node.q, seed=node.eta)
        assert np.min(np.abs(orbit.multipliers + 1)) < 1e-6


def test_pitchfork_of_a_symmetric_clearance_starts_the_asymmetric_branch():
    """One mass between two stops (docs/several-stops.md): the symmetric
    P(2,1)'s pitchfork at Omega = 1.0376 and the asymmetric P(2,1) it starts,
    whose two impacts have different speeds."""
    clearance = impactkit.System.chain(n=1, forcing=[1.0], omega=1.0).with_stops([
        {"dof": 0, "side": "upper", "position": 0.5, "restitution": 0.8},
        {"dof": 0, "side": "lower", "position": -0.5, "restitution": 0.8}])
    orbit = impactkit.find_orbit(clearance)
    diagram = impactkit.trace_diagram([(clearance, orbit)], from_=0.9, to=1.2, max_depth=1)
    pitchforks = [node for node in diagram.nodes if node.type == "pitchfork"]
    assert len(pitchforks) == 1
    assert pitchforks[0].parameter == pytest.approx(1.037642583, abs=1e-8)
    born = [b for b in diagram.branches if b.parent >= 0 and b.branch.p == 2]
    assert born, [b.origin for b in diagram.branches]
    speeds = born[0].branch.orbits[-1].impact_velocities
    assert abs(speeds[0] - speeds[1]) > 1e-4


def test_sticking_family_beside_the_chatter_orbits_that_accumulate_on_it():
    # Seeds: the paper's sticking orbit at Omega = 0.2 and the chatter orbit
    # P(10,1) at 0.309, switched at its grazings to P(9,1), P(11,1), ...
    # The sticking branch ends at no_sticking where continue_branch ends it,
    # and every chatter branch lies above that end.
    sticking_system = impactkit.System.paper(0.2)
    sticking = impactkit.find_orbit(sticking_system)
    chatter_system = impactkit.System.paper(0.309)
    chatter = impactkit.find_orbit(chatter_system, p=10, q=1)
    diagram = impactkit.trace_diagram([(sticking_system, sticking), (chatter_system, chatter)],
                                      from_=0.2, to=0.5, max_depth=2)
    family = impactkit.continue_branch(sticking_system, sticking, from_=0.2, to=0.5)
    released = [b.branch for b in diagram.branches if b.branch.section == "release"]
    assert len(released) == 1 and released[0].end == "no_sticking"
    end = max(released[0].values)
    assert end == pytest.approx(family.values[-1], abs=1e-8)
    impacting = [b.branch for b in diagram.branches if b.branch.section == "impact"]
    assert {b.p for b in impacting} >= {9, 10}
    assert all(min(b.values) > end for b in impacting)


def test_a_user_test_reaches_every_branch_of_the_diagram(paper_orbit):
    # The impact speed of P(1,1) crossing a level between its values at the
    # main branch's ends, located in the network traced on two threads: each
    # node's orbit, solved afresh at its omega, has that speed (1e-9).
    system, orbit = paper_orbit
    main = impactkit.continue_branch(system, orbit, from_=1.5, to=1.8, direction="both")
    level = 0.5 * (main.orbits[0].impact_velocities[0] + main.orbits[-1].impact_velocities[0])
    network = impactkit.trace_diagram(
        [(system, orbit)], from_=1.5, to=1.8, max_depth=1, threads=2,
        user_tests={"speed": lambda o: o.impact_velocities[0] - level})
    nodes = [n for n in network.nodes if n.type == "user_test"]
    assert all(n.user_test == "speed" for n in nodes)
    assert any(n.p == 1 for n in nodes)
    for node in nodes:
        if node.p != 1:
            continue
        again = impactkit.find_orbit(impactkit.System.paper(node.parameter), p=1, q=1,
                                     seed=node.eta)
        assert abs(again.impact_velocities[0] - level) < 1e-9


def test_grazing_nodes_carry_their_normal_form_as_the_branches_special_points(diagram):
    grazings = [n for n in diagram.nodes if n.type == "grazing"]
    assert grazings
    for node in diagram.nodes:
        if node.type != "grazing":
            assert node.normal_form is None
    for node in grazings:
        located = [s for s in diagram.branches[node.branch].branch.special_points
                   if s.type == "grazing" and s.parameter == node.parameter]
        assert located and node.normal_form == located[0].normal_form
        assert node.normal_form["prediction"]["motion"]


def test_swept_diagram_equals_the_command_line_diagram(tmp_path):
    """impactkit.swept_diagram is `impactkit diagram` with no --start: the
    same nodes and edges from the library's recipe (refined sweep included),
    with the command line's defaults for what it is not given."""
    system = impactkit.System.paper(0.8)
    mine = impactkit.swept_diagram(system, from_=0.8, to=0.9, sweep_values=41, sweep_record=20,
                                   max_depth=3, threads=2)
    out = tmp_path / "d.json"
    subprocess.run([os.environ["IMPACTKIT_CLI"], "diagram", "--from", "0.8", "--to", "0.9",
                    "--sweep-values", "41", "--sweep-record", "20", "--max-depth", "3",
                    "--threads", "2", "--json", str(out)], check=True, capture_output=True)
    cli = json.loads(out.read_text())
    assert [n["type"] for n in cli["nodes"]] == [n.type for n in mine.nodes]
    assert [n["param"] for n in cli["nodes"]] == [n.parameter for n in mine.nodes]
    assert [(e["from"], e["to"]) for e in cli["edges"]] == list(zip(mine.edge_from, mine.edge_to))
    origins = [b.origin for b in mine.branches]
    assert any(o.startswith("sweep window P(3,2)") for o in origins)
