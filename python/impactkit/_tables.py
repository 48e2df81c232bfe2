"""Results as the tables people already use: pandas DataFrames and xarray
Datasets, with the command line's column names (docs/cli.md, "Output
files"), so that a table from Python and a file from `impactkit` read alike.

A table's numbers are the result's, not recomputed: a branch's and a curve's
table is the file write_csv writes (the library's schema,
io/branch_output.hpp and io/curve_output.hpp) read back exactly; a sweep's
summary is the library's rows (io/sweep_output.hpp) the binding hands over
as text; the other tables put the result's arrays under the files' names.
As in the files, a stop and a basin's attractor are counted from 1, and a
period p, q is missing (pandas' <NA>, xarray's NaN) where the motion does
not repeat (q = 0 in the arrays).

pandas and xarray are optional: nothing here imports them until a
conversion is asked for, which then raises ImportError saying what to
install.
"""

import io
import os
import tempfile

import numpy as np

from . import _impactkit


def _require(module, what):
    try:
        return __import__(module)
    except ImportError as error:
        raise ImportError(
            f"{what} needs {module}, which is not installed (Debian: apt-get install "
            f"python3-{module}; with pip: pip install {module}); the rest of impactkit "
            f"works without it") from error


def _read_csv(pandas, source):
    """A table as the command line writes it, every number as written (the
    shortest form that reads back to the same double: pandas' round_trip
    parser reads it exactly), an empty field missing."""
    return pandas.read_csv(source, comment="#", float_precision="round_trip",
                           keep_default_na=False, na_values=[""])


def _motion_kinds(pandas, kinds):
    """The motion class as a categorical over the library's kinds."""
    return pandas.Categorical(kinds, categories=_impactkit._motion_kinds)


def _period(values, q):
    """p or q as the files give them: missing where the motion does not
    repeat (q = 0), as floats with NaN."""
    out = np.asarray(values, dtype=float).copy()
    out[np.asarray(q) == 0] = np.nan
    return out


def _call_options(args, keywords, option_set):
    """The call's keywords, with the library's defaults of its option set
    resolved (simulate, which has none, its keywords as given)."""
    given = {k: v for k, v in keywords.items() if k not in ("system", "progress")}
    if option_set is not None:
        return dict(option_set(**given))
    return dict(zip(("t_end",), args[1:]), **given)


def _provenance(function, system, options):
    """What produced a result, enough to repeat it, as text (netCDF keeps
    it): the version, the function, the system (the JSON System.to_json
    writes) and its named parameters, the options."""
    return {
        "impactkit_version": _impactkit.__version__,
        "function": function,
        "system": system.to_json(),
        "parameters": " ".join(f"{name}={system[name]!r}" for name in system.parameter_names()),
        "options": " ".join(f"{name}={value!r}" for name, value in options.items()),
    }


class _Result(dict):
    """A result dict (the compiled function's, unchanged) that also knows
    what produced it: `options`, the call's keywords with the library's
    defaults resolved, and `provenance`, which its tables carry in `attrs`."""

    def __init__(self, result, options, provenance):
        super().__init__(result)
        self.options = options
        self.provenance = provenance


class SimulationResult(_Result):
    """What impactkit.simulate returns: its dict of arrays, and its samples
    and impacts as DataFrames."""

    def samples_to_pandas(self):
        """The samples as a DataFrame, the columns of `impactkit simulate
        --series`: t, x1..xN, v1..vN, stuck (bool), event ('' on the grid)."""
        pandas = _require("pandas", "SimulationResult.samples_to_pandas")
        samples = self["samples"]
        table = pandas.DataFrame({"t": samples["t"]})
        _add_state(table, samples["x"], samples["v"])
        table["stuck"] = samples["stuck"]
        table["event"] = samples["event"].astype(object)
        table.attrs = dict(self.provenance)
        return table

    def impacts_to_pandas(self):
        """The impacts as a DataFrame, the columns of `impactkit simulate
        --impacts`: t, phase, velocity, x1..xN, v1..vN (just before
        impact), stop (from 1, as in files)."""
        pandas = _require("pandas", "SimulationResult.impacts_to_pandas")
        impacts = self["impacts"]
        table = pandas.DataFrame({name: impacts[name] for name in ("t", "phase", "velocity")})
        _add_state(table, impacts["x"], impacts["v"])
        table["stop"] = impacts["stop"] + 1
        table.attrs = dict(self.provenance)
        return table


def _add_state(table, x, v):
    for i in range(x.shape[1]):
        table[f"x{i + 1}"] = x[:, i]
    for i in range(v.shape[1]):
        table[f"v{i + 1}"] = v[:, i]


class SweepResult(_Result):
    """What impactkit.sweep returns: its dict of arrays, and its tables as
    DataFrames."""

    def to_pandas(self):
        """One row per value, the table `impactkit sweep --summary` writes
        (the library's rows): PARAMETER, kind (categorical), p, q (missing
        where the motion does not repeat), range_xN, range_x1,
        range_xN_min, range_x1_min, impacts, velocity_min, velocity_max,
        lyapunov, restarted (bool)."""
        pandas = _require("pandas", "SweepResult.to_pandas")
        table = _read_csv(pandas, io.StringIO(self["summary_csv"]))
        table["kind"] = _motion_kinds(pandas, table["kind"])
        table["p"] = table["p"].astype("Int64")
        table["q"] = table["q"].astype("Int64")
        table["restarted"] = table["restarted"].astype(bool)
        table.attrs = dict(self.provenance)
        return table

    def impacts_to_pandas(self):
        """One row per recorded impact, the table `impactkit sweep --out`
        writes: PARAMETER, t (from the start of that value's run), phase,
        velocity, stop (from 1)."""
        pandas = _require("pandas", "SweepResult.impacts_to_pandas")
        parameter = self.options["parameter"]
        counts = np.diff(self["impact_offsets"])
        table = pandas.DataFrame({
            parameter: np.repeat(self["values"], counts),
            "t": self["impact_t"],
            "phase": self["impact_phase"],
            "velocity": self["impact_velocity"],
            "stop": self["impact_stop"] + 1,
        })
        table.attrs = dict(self.provenance)
        return table


class _GridResult(_Result):
    _first = _second = None  # the option naming each axis

    def _axes(self):
        return self.options[self._first], self.options[self._second]

    def _cells(self):
        """The cells' variables as the files name them, arrays (rows, columns)."""
        return {
            "kind": self["kind"],
            "p": _period(self["p"], self["q"]),
            "q": _period(self["q"], self["q"]),
            "max_velocity": self["max_velocity"],
            "range_xN": self["range_xN"],
            "lyapunov": self["lyapunov"],
        }

    def to_xarray(self):
        """The grid as an xarray.Dataset over the two named coordinates
        (the row's along the second dimension): the cells' variables of
        the command line's table (kind by name, p, q with NaN where the
        motion does not repeat, ...), the provenance in attrs."""
        xarray = _require("xarray", f"{type(self).__name__}.to_xarray")
        first, second = self._axes()
        dims = (second, first)
        cells = self._cells()
        data = {name: (dims, values) for name, values in cells.items()}
        dataset = xarray.Dataset(
            data, coords={first: self["values"], second: self["values2"]},
            attrs=dict(self.provenance, **self._extra_attrs()))
        dataset["kind"].attrs["categories"] = " ".join(_impactkit._motion_kinds)
        return dataset

    def to_pandas(self):
        """One row per cell in the command line's order (each row of the
        grid in turn): the rows of its table, kind categorical, p and q
        missing where the motion does not repeat."""
        pandas = _require("pandas", f"{type(self).__name__}.to_pandas")
        first, second = self._axes()
        rows, columns = self["kind"].shape
        table = pandas.DataFrame({first: np.tile(self["values"], rows),
                                  second: np.repeat(self["values2"], columns)})
        for name, values in self._cells().items():
            table[name] = np.ravel(values)
        table["kind"] = _motion_kinds(pandas, table["kind"])
        table["p"] = table["p"].astype("Int64")
        table["q"] = table["q"].astype("Int64")
        table.attrs = dict(self.provenance, **self._extra_attrs())
        return table

    def _extra_attrs(self):
        return {}


class MapResult(_GridResult):
    """What impactkit.parameter_map returns: its dict of arrays, and the
    map as an xarray.Dataset over (parameter2, parameter) or as the
    command line's table."""

    _first, _second = "parameter", "parameter2"


class BasinsResult(_GridResult):
    """What impactkit.basins returns: its dict of arrays, and the picture
    as an xarray.Dataset over (coordinate2, coordinate) or as the command
    line's table, with each cell's attractor counted from 1 as in it."""

    _first, _second = "coordinate", "coordinate2"

    def _cells(self):
        cells = {"attractor": self["attractor"] + 1}
        cells.update(super()._cells())
        return cells

    def _extra_attrs(self):
        return {"attractors": "; ".join(
            f"{number}: {a['kind']} p={a['p']} q={a['q']} cells={a['cells']}"
            for number, a in enumerate(self["attractors"], start=1))}


def wrap(function, result_class, option_set=None):
    """The compiled `function`, its result wrapped in `result_class` with
    its provenance: the same keywords, checks, defaults and docstring."""

    def call(*args, **keywords):
        result = function(*args, **keywords)
        options = _call_options(args, keywords, option_set)
        system = keywords["system"] if "system" in keywords else args[0]
        return result_class(result, options, _provenance(function.__name__, system, options))

    call.__name__ = call.__qualname__ = function.__name__
    call.__doc__ = function.__doc__
    call.__module__ = "impactkit"
    return call


def _branch_like_to_pandas(self, what):
    pandas = _require("pandas", what)
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "table.csv")
        self.write_csv(path)
        table = _read_csv(pandas, path)
    if "stable" in table:
        table["stable"] = table["stable"].astype(bool)
    if "special" in table:
        table["special"] = table["special"].astype("category")
    return table


def _branch_attrs(branch):
    return {"impactkit_version": _impactkit.__version__, "parameter": branch.parameter,
            "section": branch.section, "p": branch.p, "q": branch.q, "end": branch.end}


def branch_to_pandas(self):
    """One row per point, the table `impactkit continue --out` writes (the
    library's schema, io/branch_output.hpp): the parameter (its column
    named by it), arclength, the leading impacts' impact_phase1.. and
    impact_velocity1.. (a sticking family's stick and release phases
    first), range_xN, the multipliers' moduli mod1.., stable (bool),
    clearance, depth (contact_margin), special (the special point's type,
    missing for an ordinary point). The fixed points and the complex
    multipliers, row for row, are Branch.eta and Branch.multipliers."""
    table = _branch_like_to_pandas(self, "Branch.to_pandas")
    table.attrs = _branch_attrs(self)
    return table


def special_points_to_pandas(self):
    """One row per special point, in order along the branch: type
    (categorical), the parameter (its column named by it), multiplier
    (complex: the critical one of a fold, period doubling or
    Neimark-Sacker point), monitor, user_test (a user test's name), stable,
    and the line the command line prints (description)."""
    pandas = _require("pandas", "Branch.special_points_to_pandas")
    points = self.special_points
    table = pandas.DataFrame({
        "type": pandas.Series([s.type for s in points], dtype="category"),
        self.parameter: np.array([s.parameter for s in points], dtype=float),
        "multiplier": np.array([s.multiplier for s in points], dtype=complex),
        "monitor": np.array([s.monitor for s in points], dtype=float),
        "user_test": [s.user_test for s in points],
        "stable": np.array([s.orbit.stable for s in points], dtype=bool),
        "description": [s.describe(self.parameter) for s in points],
    })
    table.attrs = _branch_attrs(self)
    return table


def curve_to_pandas(self):
    """One row per point, the table `impactkit curve --out` writes (the
    library's schema, io/curve_output.hpp)."""
    table = _branch_like_to_pandas(self, "Curve.to_pandas")
    table.attrs = {"impactkit_version": _impactkit.__version__}
    return table


def nodes_to_pandas(self):
    """One row per node (its index the node's, as edge_from and edge_to
    give it), the fields of `impactkit diagram --json`'s nodes: type
    (categorical), the parameter (its column named by it), p, q, branch
    (an index into branches), multiplier (complex), monitor, user_test."""
    pandas = _require("pandas", "Diagram.nodes_to_pandas")
    nodes = self.nodes
    table = pandas.DataFrame({
        "type": pandas.Series([n.type for n in nodes], dtype="category"),
        self.parameter: np.array([n.parameter for n in nodes], dtype=float),
        "p": np.array([n.p for n in nodes], dtype=np.int64),
        "q": np.array([n.q for n in nodes], dtype=np.int64),
        "branch": np.array([n.branch for n in nodes], dtype=np.int64),
        "multiplier": np.array([n.multiplier for n in nodes], dtype=complex),
        "monitor": np.array([n.monitor for n in nodes], dtype=float),
        "user_test": [n.user_test for n in nodes],
    })
    table.attrs = {"impactkit_version": _impactkit.__version__, "parameter": self.parameter}
    return table


def edges_to_pandas(self):
    """One row per edge, the fields of `impactkit diagram --json`'s edges:
    from and to (node indices), branch (an index into branches)."""
    pandas = _require("pandas", "Diagram.edges_to_pandas")
    table = pandas.DataFrame({"from": self.edge_from, "to": self.edge_to,
                              "branch": self.edge_branch})
    table.attrs = {"impactkit_version": _impactkit.__version__, "parameter": self.parameter}
    return table


def add_methods(module):
    """The conversions as methods of the compiled classes."""
    module.Branch.to_pandas = branch_to_pandas
    module.Branch.special_points_to_pandas = special_points_to_pandas
    module.Curve.to_pandas = curve_to_pandas
    module.Diagram.nodes_to_pandas = nodes_to_pandas
    module.Diagram.edges_to_pandas = edges_to_pandas
