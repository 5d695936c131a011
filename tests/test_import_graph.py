"""The two layers of the code, read from the source alone (``ast``; nothing is imported): the
library (``strand`` outside ``strand.app``, and ``forms``) never imports the application
(``strand.app``), no module imports itself through others (no import circle, counting the imports
inside functions and under ``TYPE_CHECKING``), and ``strand/__init__.py`` names each name of the
public API once, with the module that defines it.

An import is an edge to the module that defines what it names: ``import a.b.c`` and ``from a.b
import c`` go to the submodule ``a.b.c`` where there is one, else to the package ``a.b``
(its ``__init__``); relative imports are resolved first. A package's ``__init__`` importing its
own submodules is an edge like any other: a submodule importing its package back is a circle.
"""

from __future__ import annotations

import ast
from collections.abc import Iterable, Mapping
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("strand", "forms")
APP = "strand.app"


def modules(root: Path = ROOT, packages: Iterable[str] = PACKAGES) -> dict[str, Path]:
    """Every module of ``packages`` under ``root``: dotted name → file (``__init__.py`` for a
    package)."""
    found = {}
    for package in packages:
        for path in sorted((root / package).rglob("*.py")):
            parts = list(path.relative_to(root).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts.pop()
            found[".".join(parts)] = path
    return found


def _is_package(name: str, known: Mapping[str, Path]) -> bool:
    return known[name].name == "__init__.py"


def _defining(target: str, known: Mapping[str, Path]) -> str | None:
    """The module that defines ``target`` (dotted): itself if it is a module, else the longest
    known prefix; None outside the known modules."""
    parts = target.split(".")
    while parts:
        name = ".".join(parts)
        if name in known:
            return name
        parts.pop()
    return None


def imports_of(name: str, tree: ast.AST, known: Mapping[str, Path]) -> set[str]:
    """The known modules that module ``name`` imports, anywhere in ``tree`` (module level,
    functions, ``TYPE_CHECKING`` blocks)."""
    package = name if _is_package(name, known) else name.rpartition(".")[0]
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                if node.level > 1:
                    base = base[: len(base) - node.level + 1]
                assert base and base[0], f"{name}: relative import beyond the top package"
                base = ".".join(base + ([node.module] if node.module else []))
            else:
                base = node.module
            targets = [
                f"{base}.{alias.name}" if f"{base}.{alias.name}" in known else base
                for alias in node.names
            ]
        else:
            continue
        for target in targets:
            module = _defining(target, known)
            if module is not None and module != name:
                out.add(module)
    return out


def import_graph(root: Path = ROOT, packages: Iterable[str] = PACKAGES) -> dict[str, set[str]]:
    """Module → the modules it imports, over ``packages``."""
    known = modules(root, packages)
    return {
        name: imports_of(name, ast.parse(path.read_text(), str(path)), known)
        for name, path in known.items()
    }


def find_cycle(graph: Mapping[str, Iterable[str]]) -> list[str] | None:
    """One import circle of ``graph`` as [a, b, ..., a], or None if there is none."""
    state: dict[str, int] = {}  # 1: on the current path, 2: done
    path: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        path.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 1:
                return path[path.index(nxt) :] + [nxt]
            if nxt not in state:
                found = visit(nxt)
                if found:
                    return found
        path.pop()
        state[node] = 2
        return None

    for node in sorted(graph):
        if node not in state:
            found = visit(node)
            if found:
                return found
    return None


def _in_app(name: str) -> bool:
    return name == APP or name.startswith(APP + ".")


def layer_violations(graph: Mapping[str, Iterable[str]]) -> list[str]:
    """Each "library module → application module" import: the application imported from
    outside it (its command line runs as ``strand`` or ``python -m strand.app``)."""
    return [
        f"{a} → {b}"
        for a, targets in sorted(graph.items())
        if not _in_app(a)
        for b in sorted(targets)
        if _in_app(b)
    ]


@pytest.fixture(scope="module")
def graph():
    return import_graph()


def test_the_graph_sees_the_modules(graph):
    """The walk finds both layers and the imports between them (a graph without edges would
    pass every test below)."""
    assert {"strand", "strand.app", "strand.app.cli", "forms", "forms.reissner"} <= set(graph)
    assert "strand.app.case" in graph["strand.app.cli"]  # an import inside a function
    assert "forms.rotations" in graph["forms.reissner"]  # a relative import


def test_no_import_circle(graph):
    cycle = find_cycle(graph)
    assert cycle is None, "import circle: " + " → ".join(cycle)


def test_the_library_never_imports_the_application(graph):
    bad = layer_violations(graph)
    assert not bad, "the library imports the application: " + "; ".join(bad)


def test_forms_does_not_import_the_application(graph):
    bad = [v for v in layer_violations(graph) if v.startswith("forms")]
    assert not bad, "; ".join(bad)


def test_the_checks_fail_where_they_should(tmp_path):
    """A circle (through a package ``__init__``, a relative import and an import inside a
    function) and a library module importing the application, in a package made up here."""
    pkg = tmp_path / "strand"
    (pkg / "app").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("def f():\n    from .app import b\n")
    (pkg / "app" / "__init__.py").write_text("from . import b\n")
    (pkg / "app" / "b.py").write_text("from strand import app\nimport strand.a\n")
    g = import_graph(tmp_path, ["strand"])
    assert g["strand.a"] == {"strand.app.b"}
    assert g["strand.app.b"] == {"strand.app", "strand.a"}
    cycle = find_cycle(g)
    assert cycle is not None and cycle[0] == cycle[-1]
    assert set(cycle) in ({"strand.app", "strand.app.b"}, {"strand.a", "strand.app.b"})
    assert layer_violations(g) == ["strand.a → strand.app.b"]
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": set()}) is None
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]


def _api_table() -> tuple[dict[str, str], list[str], dict[str, str]]:
    """From ``strand/__init__.py``: its name → module table ``_API``, ``__all__``, and the
    names its ``TYPE_CHECKING`` block imports, with their modules."""
    tree = ast.parse((ROOT / "strand" / "__init__.py").read_text())
    table, names, typed = {}, [], {}
    for node in tree.body:
        if isinstance(node, ast.Assign) and isinstance(node.targets[0], ast.Name):
            if node.targets[0].id == "_API":
                table = ast.literal_eval(node.value)
            if node.targets[0].id == "__all__":  # ["__version__", *_API]
                names = eval(
                    compile(ast.Expression(node.value), "__all__", "eval"), {"_API": table}
                )
        if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING":
            for imp in node.body:
                assert isinstance(imp, ast.ImportFrom) and imp.level == 1, ast.unparse(imp)
                assert all(a.asname == a.name for a in imp.names), f"{ast.unparse(imp)}: X as X"
                typed |= {alias.name: f"strand.{imp.module}" for alias in imp.names}
    return table, names, typed


def _defines(path: Path, name: str) -> bool:
    """``name`` is a class, function, assignment or import at the top of the module ``path``."""
    for node in ast.parse(path.read_text()).body:
        if isinstance(node, ast.ClassDef | ast.FunctionDef) and node.name == name:
            return True
        if isinstance(node, ast.Assign | ast.AnnAssign):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            if any(isinstance(t, ast.Name) and t.id == name for t in targets):
                return True
        if isinstance(node, ast.ImportFrom) and any(
            (a.asname or a.name) == name for a in node.names
        ):
            return True
    return False


def test_the_public_api_is_named_once():
    """``__all__`` is the table's names; the ``TYPE_CHECKING`` imports (what type checkers and
    editors read) are the same names from the same modules; each module defines its names (or
    imports them: a package's own re-exports) and belongs to the library."""
    table, names, typed = _api_table()
    known = modules()
    assert table, "strand/__init__.py has no _API table"
    assert names == ["__version__", *table]
    assert typed == table
    for name, module in table.items():
        assert module in known and not _in_app(module), f"{name}: {module}"
        assert _defines(known[module], name), f"{module} does not define {name}"
