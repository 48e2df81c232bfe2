"""impactkit.SweepOptions, ContinuationOptions, CurveOptions, DiagramOptions,
MapOptions and BasinsOptions: each holds its function's keywords with the
function's defaults (read from the signature pybind11 writes), passes them
with `**` to the same result as the keywords spelled out, refuses unknown
keywords, and says in help() what each field means (the C++ header's words)
and its default (the header's value)."""

import ast
import os
import pydoc
import re

import numpy as np
import pytest

import impactkit

# Each option set, its function, and the function's arguments that are not
# in the set.
SETS = [
    (impactkit.SweepOptions, "sweep", {"system", "progress"}),
    (impactkit.ContinuationOptions, "continue_branch",
     {"system", "orbit", "start", "user_tests", "progress"}),
    (impactkit.CurveOptions, "continue_curve",
     {"system", "branch", "special_point", "user_tests", "progress"}),
    (impactkit.DiagramOptions, "trace_diagram", {"seeds", "user_tests", "progress"}),
    (impactkit.MapOptions, "parameter_map", {"system", "progress"}),
    (impactkit.BasinsOptions, "basins", {"system", "progress"}),
]
IDS = [cls.__name__ for cls, _, _ in SETS]


def signatures(function):
    """Each signature pybind11 writes in the function's docstring (one per
    overload), parsed as Python: (positional arguments, {keyword: default}
    in order, keywords without a default)."""
    found = []
    for line in getattr(impactkit, function).__doc__.splitlines():
        match = re.match(rf"(?:\d+\. )?{function}\((.*)\) -> ", line)
        if match:
            args = ast.parse(f"def f({match.group(1)}): pass").body[0].args
            pairs = list(zip(args.kwonlyargs, args.kw_defaults))
            found.append(([a.arg for a in args.args],
                          {a.arg: ast.literal_eval(d) for a, d in pairs if d is not None},
                          {a.arg for a, d in pairs if d is None}))
    assert found, function
    return found


def fields(cls):
    return {name for name, value in vars(cls).items() if isinstance(value, property)}


@pytest.mark.parametrize("cls, function, outside", SETS, ids=IDS)
def test_defaults_are_those_of_the_functions_signature(cls, function, outside):
    for positional, defaults, required in signatures(function):
        assert set(positional) <= outside
        expected = {k: v for k, v in defaults.items() if k not in outside}
        assert dict(cls()) == expected
        assert cls().to_dict() == expected
        assert list(cls().keys()) == list(expected)  # in the function's order
        assert fields(cls) == set(expected) | (required - outside)
        for name in required - outside:
            assert getattr(cls(), name) is None and name not in cls().keys()


@pytest.mark.parametrize("cls, function, outside", SETS, ids=IDS)
def test_repr_lists_every_field_and_reads_back(cls, function, outside):
    options = cls()
    text = repr(options)
    assert text.startswith(cls.__name__ + "(")
    for name in fields(cls):
        assert f"{name}={getattr(options, name)!r}" in text
    assert eval(text, {cls.__name__: cls}).to_dict() == options.to_dict()


def test_a_set_is_a_mapping_to_change_and_reuse():
    options = impactkit.ContinuationOptions(from_=1.5, to=1.8, direction="both")
    assert options["from_"] == 1.5 and options.direction == "both"
    assert "to" in options and len(options) == len(options.keys())
    options.to = None  # a required keyword unset: left out of the mapping
    assert "to" not in options.keys()
    with pytest.raises(KeyError):
        options["to"]
    with pytest.raises(KeyError):
        options["nope"]
    options.max_points = 50
    again = impactkit.ContinuationOptions(**options)
    assert dict(again) == dict(options) and again.max_points == 50
    assert {**options, "to": 1.7}["to"] == 1.7


def sweep_arrays_equal(a, b):
    assert a.keys() == b.keys()
    for key in a:
        if key != "report":  # it holds the wall time
            np.testing.assert_array_equal(a[key], b[key], err_msg=key)


def test_sweep_with_a_set_is_the_call_spelled_out():
    paper = impactkit.System.paper()
    spelled = dict(from_=0.6, to=0.62, steps=3, transient_periods=100, recorded_periods=20)
    with_set = impactkit.sweep(paper, **impactkit.SweepOptions(**spelled))
    sweep_arrays_equal(with_set, impactkit.sweep(paper, **spelled))
    assert with_set["values"].size == 3


def test_continue_branch_with_a_set_is_the_call_spelled_out():
    system = impactkit.System.paper(1.65)
    orbit = impactkit.find_orbit(system, p=1, q=1)
    with_set = impactkit.continue_branch(
        system, orbit, **impactkit.ContinuationOptions(from_=1.65, to=1.8))
    spelled = impactkit.continue_branch(system, orbit, from_=1.65, to=1.8)
    assert len(with_set) > 2
    np.testing.assert_array_equal(with_set.values, spelled.values)
    assert [s.type for s in with_set.special_points] == [s.type for s in spelled.special_points]


@pytest.mark.parametrize("cls, function, outside", SETS, ids=IDS)
def test_unknown_keywords_and_wrong_types_raise(cls, function, outside):
    with pytest.raises(TypeError, match="unexpected keyword argument 'nope'"):
        cls(nope=1)
    with pytest.raises(TypeError, match="unexpected keyword argument 'user_tests'"):
        cls(user_tests={})
    with pytest.raises(TypeError):
        cls(1)  # keywords only
    name = sorted(fields(cls))[0]
    with pytest.raises(TypeError, match=name):
        setattr(cls(), name, object())


def test_names_of_enums_are_checked():
    with pytest.raises(ValueError, match="each_from must be 'previous' or 'rest'"):
        impactkit.SweepOptions(each_from="fixed")
    with pytest.raises(ValueError, match="direction must be"):
        impactkit.ContinuationOptions(direction="up")


def header_field(header, member):
    """(default, comment) of `member = default;  ///< comment` in a C++ header."""
    path = os.path.join(os.environ["IMPACTKIT_SOURCE_DIR"], "lib/include/impactkit", header)
    match = re.search(rf"\b{member} = ([^;]+);\s*///< (.+)$", open(path).read(), re.M)
    assert match, (header, member)
    value = {"true": "True", "false": "False"}.get(match.group(1), match.group(1))
    return value.replace('"', "'"), match.group(2).strip()


# (class, field, header, the struct's member, whether the class's default is
# the header's: not for required keywords, nor basins' axes, the command
# line's).
DOCUMENTED = [
    (impactkit.SweepOptions, "transient_periods", "analysis/sweep.hpp", "transient_periods", True),
    (impactkit.SweepOptions, "recorded_periods", "analysis/sweep.hpp", "recorded_periods", True),
    (impactkit.ContinuationOptions, "max_points", "continuation/continuation.hpp", "max_points",
     True),
    (impactkit.CurveOptions, "max_points", "continuation/curve.hpp", "max_points", True),
    (impactkit.DiagramOptions, "max_branches", "continuation/diagram.hpp", "max_branches", True),
    (impactkit.DiagramOptions, "switch_period_doubling", "continuation/diagram.hpp",
     "switch_period_doubling", True),
    (impactkit.MapOptions, "steps2", "analysis/parameter_map.hpp", "steps2", False),
    (impactkit.BasinsOptions, "coordinate2", "analysis/basins.hpp", "coordinate2", False),
]


@pytest.mark.parametrize("cls, name, header, member, same_default", DOCUMENTED,
                         ids=[f"{d[0].__name__}.{d[1]}" for d in DOCUMENTED])
def test_help_says_what_each_field_means_and_its_default(cls, name, header, member, same_default):
    default, comment = header_field(header, member)
    doc = getattr(cls, name).__doc__
    assert comment.lower() in doc.lower()
    if same_default:
        assert f"Default: {default}." in doc
    text = pydoc.render_doc(cls, renderer=pydoc.plaintext)
    assert name in text and comment.lower() in " ".join(text.lower().split())


@pytest.mark.parametrize("cls, function, outside", SETS, ids=IDS)
def test_the_function_and_the_class_name_each_other(cls, function, outside):
    assert f"impactkit.{cls.__name__}" in getattr(impactkit, function).__doc__
    assert f"impactkit.{function}" in cls.__doc__


@pytest.mark.parametrize("cls, function, outside", SETS, ids=IDS)
def test_the_stub_has_the_fields_and_defaults(cls, function, outside):
    path = os.path.join(os.path.dirname(impactkit.__file__), "__init__.pyi")
    stub = next(node for node in ast.parse(open(path).read()).body
                if isinstance(node, ast.ClassDef) and node.name == cls.__name__)
    init = next(node for node in stub.body
                if isinstance(node, ast.FunctionDef) and node.name == "__init__")
    defaults = {a.arg: ast.literal_eval(d) for a, d in zip(init.args.kwonlyargs,
                                                            init.args.kw_defaults)}
    options = cls()
    assert defaults == {name: getattr(options, name) for name in fields(cls)}
    annotated = {node.target.id for node in stub.body if isinstance(node, ast.AnnAssign)}
    assert annotated == fields(cls)
