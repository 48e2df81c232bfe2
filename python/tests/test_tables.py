"""Results as pandas and xarray objects: the command line's columns, the
numpy arrays' values, and the command line's CSV files cell for cell (each
run here through IMPACTKIT_CLI with the same settings); a map's coordinates
are its grid's values. Without pandas or xarray the module works and only
the conversions raise ImportError."""

import os
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest
import xarray as xr

import impactkit


def cli(*args):
    subprocess.run([os.environ["IMPACTKIT_CLI"], *map(str, args)], check=True,
                   capture_output=True)


def read_cli(path):
    """A CSV the command line wrote, every number exact (docs/cli.md)."""
    return pd.read_csv(path, comment="#", float_precision="round_trip", keep_default_na=False,
                       na_values=[""])


def assert_same_cells(table, written):
    """The same columns in the same order and, column by column, the same
    numbers (NaN where a field is empty) or the same text."""
    assert list(table.columns) == list(written.columns)
    assert len(table) == len(written)
    for name in table.columns:
        ours, theirs = table[name], written[name]
        if pd.api.types.is_numeric_dtype(theirs) and not isinstance(
                ours.dtype, pd.CategoricalDtype):
            np.testing.assert_array_equal(ours.to_numpy(dtype=float, na_value=np.nan),
                                          theirs.to_numpy(dtype=float, na_value=np.nan),
                                          err_msg=name)
        else:
            def text(column):
                return ["" if pd.isna(v) else str(v) for v in column]
            assert text(ours) == text(theirs), name


@pytest.fixture(scope="module")
def branch():
    system = impactkit.System.paper(1.7)
    return impactkit.continue_branch(system, impactkit.find_orbit(system, p=1, q=1),
                                     from_=1.5, to=1.8, direction="both")


def test_branch_table_has_the_arrays_values(branch):
    table = branch.to_pandas()
    assert len(table) == len(branch)
    np.testing.assert_array_equal(table["omega"], branch.values)
    np.testing.assert_array_equal(table["arclength"], branch.arclength)
    np.testing.assert_array_equal(table["stable"], branch.stable)
    assert table["stable"].dtype == bool
    # The moduli the library took (std::abs), numpy's within an ulp or so.
    moduli = np.abs(branch.multipliers)
    for i in range(moduli.shape[1]):
        np.testing.assert_allclose(table[f"mod{i + 1}"], moduli[:, i], rtol=1e-15)
    phases = [orbit.impact_phases[0] for orbit in branch.orbits]
    np.testing.assert_array_equal(table["impact_phase1"], phases)
    # Each special point is the row of its parameter value, typed.
    marked = table[table["special"].notna()]
    assert list(marked["special"]) == [s.type for s in branch.special_points]
    np.testing.assert_array_equal(marked["omega"], [s.parameter for s in branch.special_points])
    assert table.attrs["parameter"] == "omega" and table.attrs["p"] == 1


def test_branch_table_equals_continue_out(branch, tmp_path):
    cli("continue", "--p", 1, "--q", 1, "--from", 1.5, "--to", 1.8, "--start", 1.7, "--out",
        tmp_path / "b.csv")
    assert_same_cells(branch.to_pandas(), read_cli(tmp_path / "b.csv"))


def test_special_points_table(branch):
    table = branch.special_points_to_pandas()
    points = branch.special_points
    # An independent fact (docs/paper-reproduction.md, claim 12): this
    # stretch of P(1,1) holds its period doubling at omega = 1.613045.
    assert list(table["type"]).count("period_doubling") == 1
    assert isinstance(table["type"].dtype, pd.CategoricalDtype)
    assert list(table["type"]) == [s.type for s in points]
    np.testing.assert_array_equal(table["omega"], [s.parameter for s in points])
    np.testing.assert_array_equal(table["multiplier"], [s.multiplier for s in points])
    assert list(table["description"]) == [s.describe("omega") for s in points]
    flip = table[table["type"] == "period_doubling"]
    assert abs(flip["omega"].item() - 1.613045) < 1e-6
    assert abs(flip["multiplier"].item() + 1) < 1e-6


def test_diagram_nodes_and_edges():
    system = impactkit.System.paper(1.65)
    network = impactkit.trace_diagram([(system, impactkit.find_orbit(system, p=1, q=1))],
                                      from_=1.5, to=1.8, max_depth=1)
    nodes = network.nodes_to_pandas()
    assert len(nodes) == len(network.nodes)
    assert list(nodes["type"]) == [n.type for n in network.nodes]
    np.testing.assert_array_equal(nodes["omega"], [n.parameter for n in network.nodes])
    np.testing.assert_array_equal(nodes["p"], [n.p for n in network.nodes])
    np.testing.assert_array_equal(nodes["branch"], [n.branch for n in network.nodes])
    edges = network.edges_to_pandas()
    np.testing.assert_array_equal(edges["from"], network.edge_from)
    np.testing.assert_array_equal(edges["to"], network.edge_to)
    np.testing.assert_array_equal(edges["branch"], network.edge_branch)


def test_sweep_tables_equal_sweep_summary_and_out(tmp_path):
    cli("sweep", "--from", 0.6, "--to", 0.64, "--steps", 5, "--summary", tmp_path / "s.csv",
        "--out", tmp_path / "o.csv")
    run = impactkit.sweep(impactkit.System.paper(), from_=0.6, to=0.64, steps=5)
    summary = run.to_pandas()
    assert_same_cells(summary, read_cli(tmp_path / "s.csv"))
    np.testing.assert_array_equal(summary["omega"], run["values"])
    assert list(summary["kind"]) == run["kind"]
    # The categories are every kind docs/cli.md ("Motion kinds") names.
    assert list(summary["kind"].cat.categories) == [
        "periodic", "sticking", "chaotic", "non_impacting", "unresolved"]
    np.testing.assert_array_equal(summary["p"], run["p"])
    impacts = run.impacts_to_pandas()
    assert_same_cells(impacts, read_cli(tmp_path / "o.csv"))
    np.testing.assert_array_equal(impacts["velocity"], run["impact_velocity"])
    assert summary.attrs["function"] == "sweep" and "steps=5" in summary.attrs["options"]
    assert summary.attrs["impactkit_version"] == impactkit.__version__


def test_map_dataset_and_table_equal_map_out(tmp_path):
    cli("map", "--param", "omega", "--from", 1.7, "--to", 1.9, "--steps", 3, "--param2", "r",
        "--from2", 0.6, "--to2", 0.8, "--steps2", 2, "--transient", 200, "--record", 40,
        "--out", tmp_path / "m.csv")
    grid = impactkit.parameter_map(impactkit.System.paper(), parameter="omega", from_=1.7,
                                   to=1.9, steps=3, parameter2="r", from2=0.6, to2=0.8, steps2=2,
                                   transient_periods=200, recorded_periods=40)
    data = grid.to_xarray()
    assert data["kind"].dims == ("r", "omega")
    np.testing.assert_array_equal(data["omega"], grid["values"])
    np.testing.assert_array_equal(data["r"], grid["values2"])
    np.testing.assert_allclose(data["omega"], np.linspace(1.7, 1.9, 3), rtol=1e-15)
    np.testing.assert_array_equal(data["kind"], grid["kind"])
    for name in ("max_velocity", "range_xN", "lyapunov"):
        np.testing.assert_array_equal(data[name], grid[name])
    periodic = grid["q"] > 0
    np.testing.assert_array_equal(data["p"].values[periodic], grid["p"][periodic])
    assert np.isnan(data["p"].values[~periodic]).all()
    # A cell by its coordinates.
    assert data["kind"].sel(omega=1.9, r=0.6).item() == grid["kind"][0, 2]
    assert data.attrs["function"] == "parameter_map"
    assert "transient_periods=200" in data.attrs["options"]
    assert data.attrs["parameters"].startswith("omega=")
    table = grid.to_pandas()
    assert isinstance(table["kind"].dtype, pd.CategoricalDtype)
    assert_same_cells(table, read_cli(tmp_path / "m.csv"))
    # The Dataset's own table is the same cells in the same order.
    assert_same_cells(data.to_dataframe().reset_index()[list(table.columns)], table)


def test_basins_dataset_and_table_equal_basins_out(tmp_path):
    cli("basins", "--omega", 2, "--coord", "x2", "--from", -0.5, "--to", 0.1, "--steps", 4,
        "--coord2", "v2", "--from2", -0.5, "--to2", 0.5, "--steps2", 3, "--transient", 100,
        "--record", 30, "--out", tmp_path / "b.csv")
    found = impactkit.basins(impactkit.System.paper(2.0), coordinate="x2", from_=-0.5, to=0.1,
                             steps=4, coordinate2="v2", from2=-0.5, to2=0.5, steps2=3,
                             transient_periods=100, recorded_periods=30)
    data = found.to_xarray()
    assert data["attractor"].dims == ("v2", "x2")
    np.testing.assert_array_equal(data["x2"], found["values"])
    np.testing.assert_array_equal(data["v2"], found["values2"])
    np.testing.assert_array_equal(data["attractor"], found["attractor"] + 1)
    assert_same_cells(found.to_pandas(), read_cli(tmp_path / "b.csv"))


def test_simulation_tables_equal_simulate_impacts_and_series(tmp_path):
    system = impactkit.System.paper(1.4)
    period = system.forcing_period
    # The command line's series has every event's rows (events=True) on a
    # grid of 200 samples per period (its default).
    cli("simulate", "--omega", 1.4, "--transient", 50, "--periods", 5, "--impacts",
        tmp_path / "i.csv", "--series", tmp_path / "s.csv")
    run = impactkit.simulate(system, 55 * period, record_from=50 * period, dt=period / 200,
                             events=True)
    impacts = run.impacts_to_pandas()
    assert_same_cells(impacts, read_cli(tmp_path / "i.csv"))
    np.testing.assert_array_equal(impacts["x2"], run["impacts"]["x"][:, 1])
    np.testing.assert_array_equal(impacts["stop"], run["impacts"]["stop"] + 1)
    samples = run.samples_to_pandas()
    assert_same_cells(samples, read_cli(tmp_path / "s.csv"))
    assert samples["stuck"].dtype == bool
    assert set(samples["event"]) == {"", "impact_before", "impact_after"}
    np.testing.assert_array_equal(samples["t"], run["samples"]["t"])
    np.testing.assert_array_equal(samples["v1"], run["samples"]["v"][:, 0])
    assert samples.attrs["function"] == "simulate"


def test_without_pandas_and_xarray_the_core_works_and_tables_say_what_is_missing():
    code = """
import sys
sys.modules["pandas"] = None   # import pandas now raises ImportError
sys.modules["xarray"] = None
import impactkit
run = impactkit.simulate(impactkit.System.paper(0.6), 50.0)
assert run["impacts"]["t"].size > 0
grid = impactkit.parameter_map(impactkit.System.paper(), from_=1.7, to=1.8, steps=2, from2=0.7,
                               to2=0.7, steps2=1, transient_periods=20, recorded_periods=5)
for convert in (run.impacts_to_pandas, grid.to_xarray):
    try:
        convert()
    except ImportError as error:
        print(error)
"""
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True,
                         text=True).stdout.splitlines()
    assert out[0].startswith("SimulationResult.impacts_to_pandas needs pandas, which is not "
                             "installed (Debian: apt-get install python3-pandas")
    assert out[1].startswith("MapResult.to_xarray needs xarray")
    assert len(out) == 2


def test_curve_table_equals_curve_out(tmp_path):
    cli("curve", "--type", "period_doubling", "--p", 1, "--q", 1, "--omega", 1.6, "--param",
        "omega", "--param2", "r", "--from", 0.5, "--to", 3, "--from2", 0.3, "--to2", 0.95,
        "--out", tmp_path / "c.csv")
    system = impactkit.System.paper(1.6)
    p11 = impactkit.continue_branch(system, impactkit.find_orbit(system, p=1, q=1), from_=1.5,
                                    to=1.8, direction="both")
    flip = next(s for s in p11.special_points if s.type == "period_doubling")
    curve = impactkit.continue_curve(system, p11, flip, parameter2="r", from_=0.5, to=3.0,
                                     from2=0.3, to2=0.95)
    table = curve.to_pandas()
    assert_same_cells(table, read_cli(tmp_path / "c.csv"))
    np.testing.assert_array_equal(table["omega"], curve.values)
    np.testing.assert_array_equal(table["r"], curve.values2)
