"""The type stub names everything the package exports, and everything it
exports has a docstring."""

import ast
import inspect
import pathlib

import mrd


def _stub_names():
    stub = pathlib.Path(mrd.__file__).with_name("__init__.pyi")
    names = set()
    for node in ast.parse(stub.read_text()).body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
    return names


def test_stub_covers_the_exports():
    assert set(mrd.__all__) <= _stub_names()


def test_exports_have_docstrings():
    for name in mrd.__all__:
        obj = getattr(mrd, name)
        if inspect.isfunction(obj) or inspect.isclass(obj):
            assert inspect.getdoc(obj), name
    for cls in (mrd.Building, mrd.Damper, mrd.Fluid, mrd.Record):
        for method in ("from_file", "file"):
            assert inspect.getdoc(getattr(cls, method)), f"{cls.__name__}.{method}"
