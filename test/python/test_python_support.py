"""The project's Python runs on 3.9 to 3.13 (docs/platforms.md): scripts/requirements.in is
pinned for each of them by scripts/constraints/py3.X.txt (3.8: all but the IFC part), Python
3.11's pins are the ones Debian 12 has always had, setup.sh knows the same versions, and every
project .py file is free of syntax and run-time typing that needs a Python newer than 3.9.
No network: what the registry holds was checked when the files were written."""
import ast
import glob
import os
import re
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
SUPPORTED = ["3.9", "3.10", "3.11", "3.12", "3.13"]
PARTIAL = ["3.8"]       # Ubuntu 20.04 (ROS Noetic): no IfcOpenShell, see requirements.in
# Python 3.11 (Debian 12): the pins of scripts/requirements.txt before the per-Python files.
# Debian 12's results are measured with these; a change here is a deliberate upgrade.
PINS_3_11 = {
    "ifcopenshell": "0.8.4.post1", "isodate": "0.7.2", "lark": "1.3.1", "numpy": "2.4.6",
    "shapely": "2.2.0", "typing-extensions": "4.16.0", "evo": "1.38.1", "apsw": "3.54.1.0",
    "backports-zstd": "1.8.0", "colorama": "0.4.6", "contourpy": "1.3.3", "cycler": "0.12.1",
    "fonttools": "4.68.0", "kiwisolver": "1.5.1", "lz4": "4.4.5", "matplotlib": "3.11.2",
    "natsort": "8.4.0", "numexpr": "2.14.2", "pandas": "3.1.1", "pillow": "13.0.0",
    "python-dateutil": "4.0.0", "rosbags": "0.11.9", "ruamel-yaml": "0.19.1", "scipy": "1.17.1",
    "seaborn": "0.13.2", "tzdata": "2026.6", "xmlschema": "4.3.2", "elementpath": "5.1.4",
    "bcf-client": "0.9.0", "xsdata": "26.10", "requests": "2.34.2",
    "certifi": "2026.10.19.post1", "charset-normalizer": "3.5.3", "idna": "3.20",
    "urllib3": "2.8.0",
}
NAME = re.compile(r"^([A-Za-z0-9][A-Za-z0-9._-]*)")
MARKER = re.compile(r'^python_version\s*(>=|<|==)\s*"(\d+)\.(\d+)"$')


def canonical(name):
    return re.sub(r"[-_.]+", "-", name).lower()


def lines(path):
    with open(os.path.join(REPO, path), encoding="utf-8") as f:
        return [line.split("#", 1)[0].strip() for line in f if line.split("#", 1)[0].strip()]


def requirements(python):
    """requirements.in's packages that apply to `python` ("3.X"). Markers: python_version only."""
    wanted = []
    for line in lines("scripts/requirements.in"):
        spec, _, marker = line.partition(";")
        if marker.strip():
            m = MARKER.match(marker.strip())
            assert m, f"requirements.in: {marker.strip()!r}: only python_version OP \"3.X\""
            have = tuple(int(x) for x in python.split("."))
            bound = (int(m.group(2)), int(m.group(3)))
            if not {">=": have >= bound, "<": have < bound, "==": have == bound}[m.group(1)]:
                continue
        wanted.append(canonical(NAME.match(spec.strip()).group(1)))
    return wanted


def pins(python):
    """The constraints file of `python` as {canonical name: version}; every line name==version."""
    path = f"scripts/constraints/py{python}.txt"
    assert os.path.isfile(os.path.join(REPO, path)), f"{path} is missing"
    pinned = {}
    for line in lines(path):
        m = re.match(r"^([A-Za-z0-9][A-Za-z0-9._-]*)==([A-Za-z0-9.+!-]+)$", line)
        assert m, f"{path}: {line!r} is not an exact pin (name==version)"
        name = canonical(m.group(1))
        assert name not in pinned, f"{path}: {name} pinned twice"
        pinned[name] = m.group(2)
    return pinned


@pytest.mark.parametrize("python", SUPPORTED + PARTIAL)
def test_every_requirement_is_pinned_for_each_python(python):
    pinned = pins(python)
    missing = [name for name in requirements(python) if name not in pinned]
    assert not missing, f"constraints/py{python}.txt does not pin {missing} (requirements.in)"


def test_the_ifc_part_is_left_out_on_3_8_only():
    for python in SUPPORTED:
        assert "ifcopenshell" in requirements(python), f"no IfcOpenShell on Python {python}"
    assert "ifcopenshell" not in requirements("3.8")
    assert "ifcopenshell" not in pins("3.8"), "IfcOpenShell has no build for Python 3.8"


def test_python_3_11_keeps_debian_12s_pins():
    assert pins("3.11") == PINS_3_11


def test_no_stray_constraints_files():
    found = {os.path.basename(p)[2:-4]
             for p in glob.glob(os.path.join(REPO, "scripts", "constraints", "py*.txt"))}
    assert found == set(SUPPORTED + PARTIAL), "a constraints file for no supported Python"


def test_setup_picks_the_constraints_of_the_supported_pythons():
    with open(os.path.join(REPO, "scripts", "setup.sh"), encoding="utf-8") as f:
        setup = f.read()
    case = re.search(r"^\s*(3\.\d+(?:\s*\|\s*3\.\d+)*)\)\s*;;", setup, re.M)
    assert case, "setup.sh: no case line listing the supported Pythons"
    assert re.split(r"\s*\|\s*", case.group(1)) == SUPPORTED
    assert re.search(r"^\s*3\.8\)", setup, re.M), "setup.sh: no branch for Python 3.8"
    assert "constraints=scripts/constraints/py${pyver}.txt" in setup
    stamp = re.search(r"^want=\$\((.*)\)$", setup, re.M)
    assert stamp and "scripts/requirements.in" in stamp.group(1) and '"$constraints"' in \
        stamp.group(1), "setup.sh: the venv's stamp must cover requirements.in and the constraints"


def project_sources():
    paths = sorted(set(glob.glob(os.path.join(REPO, "scripts", "**", "*.py"), recursive=True) +
                       glob.glob(os.path.join(REPO, "test", "**", "*.py"), recursive=True)))
    assert len(paths) > 20, "too few .py files found: has the layout changed?"
    return paths


def annotation_nodes(tree):
    """ids of every node inside an annotation (arguments, returns, annotated assignments)."""
    inside = set()
    for node in ast.walk(tree):
        roots = []
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            a = node.args
            arguments = a.posonlyargs + a.args + a.kwonlyargs + [a.vararg, a.kwarg]
            roots = [x.annotation for x in arguments if x is not None] + [node.returns]
        elif isinstance(node, ast.AnnAssign):
            roots = [node.annotation]
        for root in roots:
            if root is not None:
                inside.update(id(n) for n in ast.walk(root))
    return inside


BUILTIN_GENERICS = {"list", "dict", "tuple", "set", "frozenset", "type"}
TYPE_NAMES = BUILTIN_GENERICS | {"int", "float", "str", "bool", "bytes", "object"}


def parenthesized_with(node, source):
    """Whether a `with` statement puts its items in parentheses, `with (a as x, b):` (Python
    3.10 syntax; 3.9's parser takes it, 3.8's does not, and ast's feature_version misses it)."""
    items = node.items
    if len(items) < 2 and items[0].optional_vars is None:
        return False
    text = ast.get_source_segment(source, node) or ""
    i = 4 + len(text[4:]) - len(text[4:].lstrip())
    if not text.startswith("with") or text[i:i + 1] != "(":
        return False
    depth = 0
    for k in range(i, len(text)):
        depth += {"(": 1, ")": -1}.get(text[k], 0)
        if depth == 0:
            break
    line = node.lineno + text.count("\n", 0, k)
    col = k - text.rfind("\n", 0, k) - 1 + (node.col_offset if line == node.lineno else 0)
    last = items[-1].optional_vars or items[-1].context_expr
    return (line, col) >= (last.end_lineno, last.end_col_offset)


def typing_problems(tree, future_annotations, source=""):
    """What Python 3.9 (and, for builtin generics at run time, 3.8) cannot run: `X | Y` of types
    outside annotations or in annotations evaluated at definition (no `from __future__ import
    annotations`), `list[int]` and the like outside annotations (3.8), parenthesized `with`
    items, and the 3.10+ keyword arguments dataclass(slots=, kw_only=) and zip(strict=)."""
    inside = annotation_nodes(tree)
    found = []
    for node in ast.walk(tree):
        in_annotation = id(node) in inside
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.BitOr) and \
                (not in_annotation or not future_annotations):
            sides = (node.left, node.right)
            if any(isinstance(s, ast.Constant) and s.value is None for s in sides) or \
                    any(isinstance(s, ast.Name) and s.id in TYPE_NAMES for s in sides) or \
                    (in_annotation and not future_annotations):
                found.append((node.lineno, "X | Y of types (Python 3.10)"))
        if isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name) and \
                node.value.id in BUILTIN_GENERICS and not in_annotation:
            found.append((node.lineno, f"{node.value.id}[...] evaluated at run time (fails on 3.8: "
                                       "use typing's)"))
        if isinstance(node, ast.With) and parenthesized_with(node, source):
            found.append((node.lineno, "with (...) around its items (Python 3.10)"))
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
            words = {k.arg for k in node.keywords}
            if node.func.id == "dataclass" and words & {"slots", "kw_only", "match_args"}:
                found.append((node.lineno, "dataclass(slots/kw_only/match_args) (Python 3.10)"))
            if node.func.id == "zip" and "strict" in words:
                found.append((node.lineno, "zip(strict=) (Python 3.10)"))
    return found


def test_every_python_file_parses_as_python_3_9():
    bad = []
    for path in project_sources():
        with open(path, encoding="utf-8") as f:
            source = f.read()
        try:
            ast.parse(source, path, feature_version=(3, 9))
        except SyntaxError as e:
            bad.append(f"{os.path.relpath(path, REPO)}:{e.lineno}: {e.msg}")
    assert not bad, "syntax newer than Python 3.9:\n" + "\n".join(bad)


def test_no_typing_or_keywords_that_need_python_3_10():
    bad = []
    for path in project_sources():
        with open(path, encoding="utf-8") as f:
            source = f.read()
        tree = ast.parse(source, path)
        future = any(isinstance(n, ast.ImportFrom) and n.module == "__future__" and
                     any(a.name == "annotations" for a in n.names) for n in tree.body)
        bad += [f"{os.path.relpath(path, REPO)}:{line}: {what}"
                for line, what in typing_problems(tree, future, source)]
    assert not bad, "needs a newer Python than 3.9:\n" + "\n".join(bad)


def test_the_typing_check_finds_what_it_looks_for():
    source = ("from dataclasses import dataclass\n"
              "Point = tuple[float, float]\n"
              "def f(a: int | None) -> list[int]:\n"
              "    return isinstance(a, int | str)\n"
              "@dataclass(slots=True)\n"
              "class C:\n"
              "    x: int = 0\n"
              "pairs = list(zip([1], [2], strict=True))\n")
    lines_found = sorted(line for line, _ in typing_problems(ast.parse(source), False))
    assert lines_found == [2, 3, 4, 5, 8]
    # with `from __future__ import annotations` the annotations are strings: only 2, 4, 5, 8
    assert sorted(line for line, _ in typing_problems(ast.parse(source), True)) == [2, 4, 5, 8]
    withs = ("with (open(a) as f, open(b) as g):\n    pass\n"
             "with (open(a) as f):\n    pass\n"
             "with (\n        open(a) as f,\n        open(b)):\n    pass\n"
             "with (open(a)) as f, (open(b)) as g:\n    pass\n"
             "with (a), (b):\n    pass\n"
             "with (a):\n    pass\n")
    if sys.version_info >= (3, 9):      # Python 3.8's parser rejects them outright
        assert sorted(line for line, _ in typing_problems(ast.parse(withs), True, withs)) == \
            [1, 3, 5]
    with pytest.raises(SyntaxError):
        ast.parse("match x:\n    case 1:\n        pass\n", feature_version=(3, 9))
