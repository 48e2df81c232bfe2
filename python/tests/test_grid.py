"""impactkit.parameter_map and impactkit.basins: cell for cell what
`impactkit map --out` and `impactkit basins --out` write (the command-line
tool's CSVs), for 1 and 2 threads."""

import csv
import math
import os
import subprocess

import numpy as np
import pytest

import impactkit


def read_rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def same_number(text, value):
    return math.isnan(value) if text in ("", "nan") else float(text) == value


def check_cells(rows, result, names):
    k = len(result["values"])
    assert len(rows) == k * len(result["values2"])
    for index, row in enumerate(rows):
        i, j = divmod(index, k)
        assert float(row[names[0]]) == result["values"][j] and float(row[names[1]]) == result["values2"][i]
        assert row["kind"] == result["kind"][i, j]
        assert result["kinds"][result["kind_code"][i, j]] == row["kind"]
        for key in ("max_velocity", "range_xN", "lyapunov"):
            assert same_number(row[key], result[key][i, j]), (index, key)


@pytest.mark.parametrize("threads", [1, 2])
def test_map_equals_the_command_line(tmp_path, threads):
    out = tmp_path / "m.csv"
    subprocess.run([os.environ["IMPACTKIT_CLI"], "map", "--param", "omega", "--from", "1.7",
                    "--to", "1.9", "--steps", "3", "--param2", "r", "--from2", "0.6", "--to2",
                    "0.8", "--steps2", "2", "--transient", "200", "--record", "40",
                    "--threads", "1", "--out", str(out)], check=True, capture_output=True)
    result = impactkit.parameter_map(impactkit.System.paper(), parameter="omega", from_=1.7,
                                     to=1.9, steps=3, parameter2="r", from2=0.6, to2=0.8,
                                     steps2=2, transient_periods=200, recorded_periods=40,
                                     threads=threads)
    assert result["kind"].shape == (2, 3) and result["p"].shape == (2, 3)
    check_cells(read_rows(out), result, ("omega", "r"))


def test_basins_equal_the_command_line(tmp_path):
    out = tmp_path / "b.csv"
    subprocess.run([os.environ["IMPACTKIT_CLI"], "basins", "--omega", "2", "--coord", "x2",
                    "--from", "-0.5", "--to", "0.1", "--steps", "4", "--coord2", "v2",
                    "--from2", "-0.5", "--to2", "0.5", "--steps2", "3", "--transient", "100",
                    "--record", "30", "--threads", "1", "--out", str(out)],
                   check=True, capture_output=True)
    result = impactkit.basins(impactkit.System.paper(2.0), coordinate="x2", from_=-0.5, to=0.1,
                              steps=4, coordinate2="v2", from2=-0.5, to2=0.5, steps2=3,
                              transient_periods=100, recorded_periods=30)
    rows = read_rows(out)
    check_cells(rows, result, ("x2", "v2"))
    attractor = result["attractor"].ravel()
    assert [int(row["attractor"]) for row in rows] == list(attractor + 1)
    assert sum(a["cells"] for a in result["attractors"]) == attractor.size


def test_map_and_basins_with_their_defaults_equal_the_command_line(tmp_path):
    # No run flag given on either side: both take the library's defaults
    # (they once differed, 300 transient periods in Python, 500 on the
    # command line, and so did the cells near a transition).
    cli = os.environ["IMPACTKIT_CLI"]
    out = tmp_path / "m.csv"
    subprocess.run([cli, "map", "--param", "omega", "--from", "1.66", "--to", "1.7", "--steps",
                    "3", "--param2", "r", "--from2", "0.7", "--to2", "0.75", "--steps2", "2",
                    "--out", str(out)], check=True, capture_output=True)
    result = impactkit.parameter_map(impactkit.System.paper(), parameter="omega", from_=1.66,
                                     to=1.7, steps=3, parameter2="r", from2=0.7, to2=0.75,
                                     steps2=2)
    check_cells(read_rows(out), result, ("omega", "r"))
    out = tmp_path / "b.csv"
    subprocess.run([cli, "basins", "--omega", "2", "--from", "-0.5", "--to", "0.1", "--steps", "3",
                    "--from2", "-0.5", "--to2", "0.5", "--steps2", "2", "--out", str(out)],
                   check=True, capture_output=True)
    result = impactkit.basins(impactkit.System.paper(2.0), from_=-0.5, to=0.1, steps=3,
                              from2=-0.5, to2=0.5, steps2=2)
    check_cells(read_rows(out), result, ("x2", "v2"))


def test_bad_input_is_a_value_error():
    with pytest.raises(ValueError, match="unknown parameter"):
        impactkit.parameter_map(impactkit.System.paper(), parameter="q", from_=1, to=2,
                                steps=2, from2=0.5, to2=0.6, steps2=2)
