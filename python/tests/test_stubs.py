"""antcd.pyi (installed as antcd/__init__.pyi) describes the module: the same public names, the
same public members per class, the same parameter names per function and method."""
import ast
import inspect
import re
from pathlib import Path

import antcd

STUB = Path(antcd.__file__).with_name("__init__.pyi")


def _stub():
    tree = ast.parse(STUB.read_text())
    names, classes, functions = set(), {}, {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            names.add(node.name)
            members = {}
            for item in node.body:
                if isinstance(item, ast.FunctionDef):
                    members[item.name] = item
                elif isinstance(item, ast.AnnAssign):
                    members[item.target.id] = None
            classes[node.name] = members
        elif isinstance(node, ast.FunctionDef):
            names.add(node.name)
            functions[node.name] = node
        elif isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
        elif isinstance(node, ast.Assign):
            names.update(t.id for t in node.targets)
    return {n for n in names if not n.startswith("_") or n == "__version__"}, classes, functions


def _params(node):
    a = node.args
    return [p.arg for p in a.posonlyargs + a.args + a.kwonlyargs if p.arg != "self"]


def _runtime_params(obj):
    try:
        return [p for p in inspect.signature(obj).parameters if p != "self"]
    except (TypeError, ValueError):  # pybind11 function: the signature is the docstring's first line
        first = obj.__doc__.splitlines()[0]
        inside = first[first.index("(") + 1:first.rindex(")")]
        return [m.group(1) for m in re.finditer(r"(?:^|, )(\w+):", inside) if m.group(1) != "self"]


def _public(name):
    return not name.startswith("_") or name in ("__bool__", "__len__", "__contains__", "__init__")


def test_stub_names_equal_module_names():
    stub_names, _, _ = _stub()
    module_names = {n for n in dir(antcd) if not n.startswith("_") and not inspect.ismodule(getattr(antcd, n))}
    module_names.add("__version__")
    assert stub_names == module_names
    assert set(antcd.__all__) == module_names


def test_stub_classes_list_every_public_member():
    _, classes, _ = _stub()
    for name, members in classes.items():
        cls = getattr(antcd, name)
        runtime = {m for m in vars(cls) if _public(m)} | {"__init__"}
        if name in ("ContactData", "DistanceData"):
            runtime |= {"names"}  # an instance attribute (slot)
        assert set(members) | {"__init__"} == runtime, name


def test_stub_parameters_equal_runtime_parameters():
    _, classes, functions = _stub()
    for name, node in functions.items():
        assert _params(node) == _runtime_params(getattr(antcd, name)), name
    for cls_name, members in classes.items():
        cls = getattr(antcd, cls_name)
        for member, node in members.items():
            attr = inspect.getattr_static(cls, member)
            if node is None or isinstance(attr, property) or type(attr).__name__ == "property":
                continue
            if any(isinstance(d, ast.Name) and d.id == "property" for d in node.decorator_list):
                continue
            func = getattr(cls, member)
            if member == "__init__" and "pybind11" in type(cls).__name__ + str(type(func)):
                pass
            assert _params(node) == _runtime_params(func), f"{cls_name}.{member}"
