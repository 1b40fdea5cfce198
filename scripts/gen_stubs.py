#!/usr/bin/env python3
"""Writes the type stubs of the Python module `horopter` from the built module.

    PYTHONPATH=build/bindings/python python3 scripts/gen_stubs.py [--check] [-o FILE]

Reads every public name of the module (functions, classes with their methods
and properties, the enum, the exception, the constants) and the signatures
pybind11 puts in their docstrings, and writes bindings/python/horopter-stubs/
__init__.pyi (PEP 561: installed with the module by `pip install`, beside
py.typed). pybind11 says `handle` or `object` where a binding takes or
returns a numpy array it checks itself: the table TYPES below gives those
(numpy.typing's NDArray with the dtype); anything it leaves out becomes Any.
Adding a binding: rebuild, run this script, and add the new name's array
types to TYPES when pybind11 cannot tell them. --check exits 1, writing
nothing, when the stub on disk differs from the one the module gives.
python.test_stubs fails when the stub and the module name different things.
"""
import argparse
import difflib
import os
import re
import sys

import horopter

U8 = "NDArray[np.uint8]"
S16 = "NDArray[np.int16]"
F32 = "NDArray[np.float32]"
F64 = "NDArray[np.float64]"
ANY_ARRAY = "NDArray[Any]"

# Parameter and return types pybind11 cannot state: "function" or
# "Class.method" -> {parameter: type, "return": type}.
TYPES = {
    "StereoMatcher.__init__": {"params": "Optional[StereoParams]",
                               "median": "Optional[MedianParams]", "kwargs": "int | str"},
    "StereoMatcher.compute": {"left": U8, "right": U8, "return": S16},
    "StereoMatcher.compute_mask": {"thresholds": S16, "image": f"Optional[{U8}]",
                                   "return": f"tuple[{U8}, Optional[{U8}]]"},
    "StereoMatcher.timings": {"return": "dict[str, float]"},
    "prefilter_xsobel": {"src": U8, "return": f"tuple[{U8}, {U8}]"},
    "match_blocks": {"left": U8, "right": U8, "texture": f"Optional[{U8}]",
                     "return": f"tuple[{S16}, {S16}]"},
    "left_right_check": {"disparity": S16, "winner_right": S16},
    "filter_speckles": {"disparity": S16},
    "median_filter": {"src": S16, "return": S16},
    "horopter_mask": {"disparity": S16, "thresholds": S16, "image": f"Optional[{U8}]",
                      "return": f"tuple[{U8}, Optional[{U8}]]"},
    "imread": {"return": ANY_ARRAY},
    "imwrite": {"image": ANY_ARRAY},
    "write_disparity16": {"disparity": S16},
    "read_disparity16": {"return": S16},
    "write_pfm": {"image": ANY_ARRAY, "invalid": "Optional[int]"},
    "read_pfm": {"return": F32},
    "find_board_corners": {"image": U8, "inner_corners": "tuple[int, int]",
                           "return": f"Optional[{F32}]"},
    "calibrate": {"lefts": f"Sequence[{U8}]", "rights": f"Sequence[{U8}]",
                  "inner_corners": "tuple[int, int]"},
    "StereoRectifier.image_size": {"return": "tuple[int, int]"},
    "StereoRectifier.rectify": {"left": U8, "right": U8, "return": f"tuple[{U8}, {U8}]"},
    "StereoCalibration.image_size": {"return": "tuple[int, int]"},
    "StereoCalibration.roi1": {"return": "tuple[int, int, int, int]"},
    "StereoCalibration.roi2": {"return": "tuple[int, int, int, int]"},
    "StereoCalibration.views": {"return": "list[dict[str, Any]]"},
    "StereoCalibration.inner_corners": {"return": "Optional[tuple[int, int]]"},
    "StereoCalibration.square_size": {"return": "Optional[float]"},
    "load_calibration": {"image_size": "Optional[tuple[int, int]]"},
    **{f"StereoCalibration.{m}": {"return": F64}
       for m in ("K1", "D1", "K2", "D2", "R", "T", "E", "F", "R1", "R2", "P1", "P2", "Q")},
    "Pipeline.__init__": {"params": "Optional[StereoParams]", "median": "Optional[MedianParams]",
                          "movement_model": "Optional[MovementModel]", "kwargs": "Any"},
    "Pipeline.__iter__": {"self": None, "return": "Pipeline"},
    "Pipeline.__enter__": {"self": None, "return": "Pipeline"},
    "Pipeline.__next__": {"return": "dict[str, Any]"},
    "Pipeline.summary": {"return": "Optional[dict[str, Any]]"},
    "Pipeline.digest": {"return": "Optional[str]"},
    "SyntheticScene.render": {"return": "dict[str, Any]"},
    "backends": {"return": "list[dict[str, Any]]"},
    "devices": {"return": "dict[str, Any]"},
    "stereo_options": {"return": "list[dict[str, Any]]"},
    "tuning_options": {"return": "dict[str, Any]"},
    "zone_extent": {"return": "dict[str, float]"},
    "classify_track": {"samples": "Iterable[dict[str, Any]]", "return": "list[dict[str, Any]]"},
    "read_body_track": {"return": "list[dict[str, Any]]"},
    "write_body_track": {"samples": "Iterable[dict[str, Any]]"},
    "synthetic_sequence": {"return": "dict[str, Any]"},
    "MovementModel.params": {"return": "dict[str, float]"},
}

# Module constants: name -> type.
CONSTANTS = {"__version__": "str", "MOVEMENTS": "list[str]",
             "STEREO_BM_PREFILTER_NORMALIZED_RESPONSE": "int",
             "STEREO_BM_PREFILTER_XSOBEL": "int"}

HEADER = '''"""Type stubs of the module `horopter` (written by scripts/gen_stubs.py: edit the
script's TYPES table, not this file, then run it against the built module)."""
from typing import Any, ClassVar, Iterable, Optional, Sequence, overload

import numpy as np
from numpy.typing import NDArray
'''


def translate(pybind_type):
    """A pybind11 signature's type as a stub's."""
    t = pybind_type.strip()
    t = re.sub(r"numpy\.ndarray\[numpy\.(\w+)(\[[^\]]*\])?\]", r"NDArray[np.\1]", t)
    t = t.replace("numpy.ndarray", ANY_ARRAY)
    t = re.sub(r"\bhoropter(\.|::)", "", t)
    t = re.sub(r"\bList\[", "list[", t)
    t = re.sub(r"\bDict\[", "dict[", t)
    t = re.sub(r"\bTuple\[", "tuple[", t)
    bare = {"handle": "Any", "object": "Any", "sequence": "Sequence[Any]",
            "Iterable": "Iterable[Any]", "list": "list[Any]", "dict": "dict[str, Any]",
            "tuple": "tuple[Any, ...]", "Iterator": "Any"}
    return bare.get(t, t)


def split_top(text, sep=","):
    """Splits at `sep` outside brackets, parentheses and quotes."""
    parts, depth, quote, start = [], 0, None, 0
    for i, ch in enumerate(text):
        if quote:
            quote = None if ch == quote else quote
        elif ch in "'\"":
            quote = ch
        elif ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        elif ch == sep and depth == 0:
            parts.append(text[start:i])
            start = i + 1
    parts.append(text[start:])
    return [p.strip() for p in parts if p.strip()]


def signatures(doc, name):
    """(parameters, return type, description) for each overload in a pybind11 docstring."""
    lines = (doc or "").splitlines()
    found = []
    pattern = re.compile(rf"^(?:\d+\. )?{re.escape(name)}\((.*)\) -> (.+)$")
    i = 0
    while i < len(lines):
        match = pattern.match(lines[i].strip())
        i += 1
        if not match:
            continue
        text = []
        while i < len(lines) and not pattern.match(lines[i].strip()):
            if re.match(r"^\d+\. ", lines[i]) and pattern.match(lines[i].split(" ", 1)[1].strip()):
                break
            text.append(lines[i])
            i += 1
        found.append((split_top(match.group(1)), match.group(2), "\n".join(text).strip()))
    return found


def parameter(text, table, first):
    """One parameter of a signature, written for a stub."""
    if text in ("*", "/"):
        return text
    stars = re.match(r"^\*{1,2}", text)
    stars = stars.group(0) if stars else ""
    body = text[len(stars):]
    name, _, rest = body.partition(":")
    name = name.strip()
    type_text, _, default = rest.partition("=")
    if first and name in ("self", "arg0"):
        return "self"
    kind = table.get(name, translate(type_text) if type_text else None)
    out = f"{stars}{name}"
    if kind:
        out += f": {kind}"
    if default.strip():
        out += " = ..."
    return out


def docstring(text, indent):
    if not text:
        return ""
    text = text.replace("\\", "\\\\").replace('"""', "'''")
    return f'{indent}"""{text}"""\n'


def function(name, doc, key, indent, method=False, static=False):
    """The stub of a function or method (an @overload per overload)."""
    table = TYPES.get(key, {})
    overloads = signatures(doc, name)
    if not overloads:
        return f"{indent}def {name}(*args: Any, **kwargs: Any) -> Any: ...\n"
    out = []
    for params, ret, text in overloads:
        written = [parameter(p, table, method and not static and i == 0)
                   for i, p in enumerate(params)]
        if method and not static and (not written or written[0] != "self"):
            written.insert(0, "self")
        returned = table.get("return", translate(ret))
        head = f"{indent}@overload\n" if len(overloads) > 1 else ""
        if static:
            head += f"{indent}@staticmethod\n"
        body = docstring(text, indent + "    ")
        line = f"{head}{indent}def {name}({', '.join(written)}) -> {returned}:"
        out.append(f"{line}\n{body}{indent}    ...\n" if body else f"{line} ...\n")
    return "".join(out)


def prop(cls, name, p):
    doc = (p.fget.__doc__ or "") if p.fget else ""
    match = re.search(r"\) -> (.+)$", doc.splitlines()[0]) if doc else None
    kind = TYPES.get(f"{cls.__name__}.{name}", {}).get(
        "return", translate(match.group(1)) if match else "Any")
    described = p.__doc__ or ""
    if re.match(rf"^{re.escape(name)}\(.*\) -> ", described):  # a signature, not a text
        described = ""
    text = docstring(described.strip(), "        ")
    out = f"    @property\n    def {name}(self) -> {kind}:"
    out += f"\n{text}        ...\n" if text else " ...\n"
    if p.fset is not None:
        out += f"    @{name}.setter\n    def {name}(self, value: {kind}) -> None: ...\n"
    return out


METHODS = ("__init__", "__iter__", "__next__", "__enter__", "__exit__", "__repr__", "__eq__",
           "__getstate__", "__setstate__", "__int__", "__index__", "__hash__", "__ne__")


def class_stub(cls):
    out = [f"class {cls.__name__}:\n", docstring(cls.__doc__ or "", "    ")]
    members = getattr(cls, "__members__", None)
    if members:
        out += [f"    {m}: ClassVar[{cls.__name__}]\n" for m in members]
    for name, value in cls.__dict__.items():
        if name.startswith("_") and name not in METHODS:
            continue
        if members and name in members:
            continue
        key = f"{cls.__name__}.{name}"
        if isinstance(value, property):
            out.append(prop(cls, name, value))
        elif isinstance(value, staticmethod):
            out.append(function(name, value.__func__.__doc__, key, "    ", static=True))
        elif callable(value) and type(value).__name__ == "instancemethod":
            out.append(function(name, value.__doc__, key, "    ", method=True))
    return "".join(out) + "\n"


def public_names(module):
    return sorted(n for n in dir(module) if not n.startswith("_") or n in CONSTANTS)


def stub_text(module):
    out = [HEADER, "\n"]
    for name, kind in CONSTANTS.items():
        out.append(f"{name}: {kind}\n")
    out.append("\n")
    error_doc = docstring(module.Error.__doc__ or "", "    ")
    out.append("class Error(ValueError):\n" + (error_doc or "    ...\n") + "\n")
    names = public_names(module)
    for name in names:
        value = getattr(module, name)
        if name in CONSTANTS or name == "Error":
            continue
        if isinstance(value, type):
            out.append(class_stub(value))
    for name in names:
        value = getattr(module, name)
        if name in CONSTANTS or isinstance(value, type):
            continue
        if callable(value):
            out.append(function(name, value.__doc__, name, ""))
        else:
            raise SystemExit(f"gen_stubs.py: no type for the constant horopter.{name}: add it "
                             "to CONSTANTS")
    return "".join(out)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    default = os.path.join(here, "..", "bindings", "python", "horopter-stubs", "__init__.pyi")
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-o", "--out", default=os.path.normpath(default))
    parser.add_argument("--check", action="store_true",
                        help="compare with the file instead of writing it")
    args = parser.parse_args()
    text = stub_text(horopter)
    if args.check:
        with open(args.out) as f:
            old = f.read()
        if old != text:
            sys.stdout.writelines(difflib.unified_diff(old.splitlines(True), text.splitlines(True),
                                                       args.out, "the module"))
            return 1
        print(f"{args.out}: up to date")
        return 0
    with open(args.out, "w") as f:
        f.write(text)
    print(f"wrote {args.out} ({len(public_names(horopter))} names)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
