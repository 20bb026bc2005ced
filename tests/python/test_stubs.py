"""The type stubs list exactly the public API: a name added to the module without a stub (or a stub
left after a name was removed) fails here, and every public function has a docstring."""
import ast
import inspect
import pathlib

import limsurf


def stub_names():
    stub = pathlib.Path(limsurf.__file__).with_name("__init__.pyi")
    tree = ast.parse(stub.read_text(encoding="utf-8"))
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
    return names


def test_every_public_name_has_a_stub_and_a_docstring():
    public = set(limsurf.__all__)
    stubs = stub_names()
    assert public - stubs == set(), "names without a stub"
    helper_types = {n for n in stubs - public if n[0].isupper()}  # TypedDicts and aliases of the stubs
    assert stubs - public - helper_types == set(), "stubs of names the module does not export"
    for name in public - {"__version__"}:
        assert inspect.getdoc(getattr(limsurf, name)), f"{name} has no docstring"
