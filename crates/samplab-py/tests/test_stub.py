"""The type stub `_samplab.pyi` against the native module it describes: the same names,
and for each function and method the same parameters in the same order, with a default
exactly where the module has one. A function added to the binding without its stub, or a
parameter renamed on one side only, fails here."""

import ast
import inspect
from pathlib import Path

import pytest

import samplab._samplab as native

STUB = Path(native.__file__).with_name("_samplab.pyi")


def stub_definitions():
    """name -> list of (parameter, has default) for each function, and for each class
    name -> {method -> parameters}, read from the stub."""
    tree = ast.parse(STUB.read_text())

    def params(f):
        a = f.args
        names = [p.arg for p in a.posonlyargs + a.args]
        defaults = [False] * (len(names) - len(a.defaults)) + [True] * len(a.defaults)
        out = list(zip(names, defaults))
        out += [(p.arg, d is not None) for p, d in zip(a.kwonlyargs, a.kw_defaults)]
        return [p for p in out if p[0] != "self"]

    functions, classes = {}, {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            functions[node.name] = params(node)
        elif isinstance(node, ast.ClassDef):
            classes[node.name] = {
                m.name: params(m)
                for m in node.body
                if isinstance(m, ast.FunctionDef) and not any(
                    isinstance(d, ast.Name) and d.id == "property" for d in m.decorator_list
                )
            }
    return functions, classes


def runtime_params(obj):
    return [(p.name, p.default is not inspect.Parameter.empty) for p in inspect.signature(obj).parameters.values()]


def test_the_stub_names_what_the_module_exports():
    functions, classes = stub_definitions()
    exported = {n for n in dir(native) if not n.startswith("__")}
    assert exported == set(functions) | set(classes), (
        f"in the module only: {sorted(exported - set(functions) - set(classes))}; "
        f"in the stub only: {sorted((set(functions) | set(classes)) - exported)}"
    )


def test_each_function_has_the_stubs_parameters():
    functions, _ = stub_definitions()
    wrong = {n: (p, runtime_params(getattr(native, n))) for n, p in functions.items() if p != runtime_params(getattr(native, n))}
    assert not wrong, f"stub vs module: {wrong}"


def test_each_class_has_the_stubs_constructor():
    _, classes = stub_definitions()
    for name, methods in classes.items():
        if "__init__" in methods:
            assert methods["__init__"] == runtime_params(getattr(native, name)), name


def test_the_check_fails_on_a_renamed_parameter(tmp_path, monkeypatch):
    """The comparison can fail: a stub whose `warp` names its first parameter otherwise."""
    text = STUB.read_text()
    assert "def warp(name: str" in text
    renamed = tmp_path / "_samplab.pyi"
    renamed.write_text(text.replace("def warp(name: str", "def warp(warp_name: str"))
    monkeypatch.setattr(__import__(__name__), "STUB", renamed)
    with pytest.raises(AssertionError, match="warp"):
        test_each_function_has_the_stubs_parameters()
