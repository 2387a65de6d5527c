"""The typed surface: the stubs match the functions, and results cross from Rust as Python
objects (dicts, NumPy arrays), never JSON text."""

import ast
import inspect
import pathlib

import numpy as np

import tabor

PKG = pathlib.Path(tabor.__file__).parent


def _stub_defs():
    tree = ast.parse((PKG / "__init__.pyi").read_text())
    defs = {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            defs[node.name] = node
    return defs


def test_package_is_marked_typed():
    assert (PKG / "py.typed").exists()


def test_every_public_name_has_a_stub_with_the_same_parameters():
    defs = _stub_defs()
    missing = [n for n in tabor.__all__ if n not in defs]
    assert not missing, f"no stub for {missing}"
    for name in tabor.__all__:
        obj = getattr(tabor, name)
        if inspect.isclass(obj):
            continue
        stub = defs[name].args
        stub_names = [a.arg for a in stub.posonlyargs + stub.args + stub.kwonlyargs]
        if stub.vararg:
            stub_names.append(stub.vararg.arg)
        if stub.kwarg:
            stub_names.append(stub.kwarg.arg)
        real = list(inspect.signature(obj).parameters)
        assert stub_names == real, f"{name}: stub {stub_names} != {real}"


def test_results_are_python_objects_not_json_text():
    s = tabor.Scene.preset("afm-si")
    assert isinstance(s.report, dict) and isinstance(s.report["loads"], list)
    c = tabor.curve(1.0, points=20)
    assert c["A"].dtype == np.float64 and len(c["A"]) == 20
    p = tabor.profile(1.0, load=0.0, points=50)
    assert isinstance(p["models"], list) and isinstance(p["models"][0]["r"], np.ndarray)
    r = tabor.solve(1.0, load=[0.0, 1.0])
    assert isinstance(r.metadata, dict) and r.metadata["backend"] == "cpu"
    inf = tabor.infer_pulloff(1e-7, 1e-6, 1e9)
    assert isinstance(inf, dict)
