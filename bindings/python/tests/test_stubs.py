"""The type stubs (bindings/python/horopter-stubs/__init__.pyi, written by
scripts/gen_stubs.py and installed with the module) name what the built module
has, no more and no less, and every public name of the module is documented."""
import ast
import importlib.util
import os

import pytest

import horopter

# Names allowed to lack a docstring for the time being (none today); each must
# still lack one, so that the list only shrinks.
UNDOCUMENTED_FOR_NOW = set()


def stub_file(source_dir):
    path = os.path.join(source_dir, "bindings", "python", "horopter-stubs", "__init__.pyi")
    if not os.path.exists(path):
        pytest.skip(f"no stub at {path} (an installed module without the sources)")
    return path


def gen_stubs(source_dir):
    path = os.path.join(source_dir, "scripts", "gen_stubs.py")
    spec = importlib.util.spec_from_file_location("gen_stubs", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def stub_names(path):
    """Top-level names of the stub, and each class's member names."""
    with open(path) as f:
        tree = ast.parse(f.read(), path)
    names, members = set(), {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
        if isinstance(node, ast.ClassDef):
            members[node.name] = set()
            for item in node.body:
                if isinstance(item, ast.FunctionDef):
                    members[node.name].add(item.name)
                elif isinstance(item, ast.AnnAssign) and isinstance(item.target, ast.Name):
                    members[node.name].add(item.target.id)
    return names, members


def public(names):
    return {n for n in names if not n.startswith("_")}


def test_stub_names_what_the_module_has(source_dir):
    path = stub_file(source_dir)
    names, members = stub_names(path)
    module_names = public(dir(horopter)) | {"__version__"}
    hint = "run scripts/gen_stubs.py against the built module"
    assert not module_names - names, f"missing from the stub ({hint}): {module_names - names}"
    assert not names - module_names, f"the module has no {names - module_names} ({hint})"
    for name, stubbed in members.items():
        cls = getattr(horopter, name)
        if name == "Error":
            continue
        have = public(cls.__dict__) | public(getattr(cls, "__members__", {}))
        assert not have - public(stubbed), f"{name}: missing from the stub: {have - stubbed}"
        assert not public(stubbed) - have, f"{name}: the class has no {public(stubbed) - have}"


def test_stub_is_valid_python_with_numpy_typing(source_dir):
    with open(stub_file(source_dir)) as f:
        text = f.read()
    tree = ast.parse(text)
    assert "from numpy.typing import NDArray" in text
    matcher = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "StereoMatcher")
    compute = next(n for n in matcher.body if isinstance(n, ast.FunctionDef) and n.name == "compute")
    assert ast.unparse(compute.returns) == "NDArray[np.int16]"
    assert ast.unparse(compute.args.args[1].annotation) == "NDArray[np.uint8]"


def test_py_typed_marker_beside_the_stub(source_dir):
    marker = os.path.join(os.path.dirname(stub_file(source_dir)), "py.typed")
    assert os.path.exists(marker)


def test_every_public_name_has_a_docstring(source_dir):
    signatures = gen_stubs(source_dir).signatures
    undocumented = set()
    for name in public(dir(horopter)):
        value = getattr(horopter, name)
        if isinstance(value, type):
            documented = bool((value.__doc__ or "").strip())
        elif callable(value):
            overloads = signatures(value.__doc__, name)
            documented = bool(overloads) and all(text for _, _, text in overloads)
        else:
            continue  # a constant (MOVEMENTS): its type's docstring is not its own
        if not documented:
            undocumented.add(name)
    assert undocumented - UNDOCUMENTED_FOR_NOW == set(), "no docstring in the binding"
    assert UNDOCUMENTED_FOR_NOW - undocumented == set(), \
        "documented now: remove from UNDOCUMENTED_FOR_NOW"
