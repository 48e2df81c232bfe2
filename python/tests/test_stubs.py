"""The type stubs (python/impactkit.pyi, the package's __init__.pyi beside
py.typed) name every public name of the package with the same parameters,
and every function has a docstring."""

import ast
import inspect
import os

import impactkit


def stub_tree():
    path = os.path.join(os.path.dirname(impactkit.__file__), "__init__.pyi")
    return ast.parse(open(path).read())


def test_version_is_the_cmake_project_version():
    cmake = open(os.path.join(os.environ["IMPACTKIT_SOURCE_DIR"], "CMakeLists.txt")).read()
    assert f"project(impactkit VERSION {impactkit.__version__} " in cmake


def test_every_public_name_has_a_stub_and_a_docstring():
    tree = stub_tree()
    stubbed = {node.name for node in tree.body
               if isinstance(node, (ast.FunctionDef, ast.ClassDef))}
    public = {name for name in dir(impactkit) if not name.startswith("_")}
    assert public <= stubbed
    for name in public:
        obj = getattr(impactkit, name)
        assert obj.__doc__, name
        if inspect.isclass(obj):
            for member, value in vars(obj).items():
                if not member.startswith("_") and callable(value):
                    assert value.__doc__, f"{name}.{member}"


def test_function_stubs_have_the_module_keywords():
    tree = stub_tree()
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            # pybind11 puts each overload's signature in the docstring.
            doc = getattr(impactkit, node.name).__doc__
            for arg in node.args.args + node.args.kwonlyargs:
                assert f"{arg.arg}: " in doc, f"{node.name}({arg.arg})"
