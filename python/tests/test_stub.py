"""The type stub of the native module names exactly what the module has."""

import ast
import pathlib

import wingedge
from wingedge import _wingedge

STUB = pathlib.Path(wingedge.__file__).with_name("_wingedge.pyi")


def _stub_names():
    tree = ast.parse(STUB.read_text())
    top, members = set(), {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            top.add(node.name)
        if isinstance(node, ast.ClassDef):
            members[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
        if isinstance(node, ast.AnnAssign):
            top.add(node.target.id)
    return top, members


def test_the_stub_is_installed_and_matches_the_native_module():
    assert STUB.is_file()
    assert STUB.with_name("py.typed").is_file()
    top, members = _stub_names()
    native = {n for n in dir(_wingedge) if not n.startswith("__") or n == "__version__"}
    assert top == native
    for cls in ("NativeSolid", "NativeScene", "Report", "Violation"):
        have = {n for n in vars(getattr(_wingedge, cls)) if not n.startswith("__")}
        assert members[cls] == have, cls
