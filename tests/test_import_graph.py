"""The two layers of the code and the order of its packages, read from the source alone (``ast``;
nothing is imported): the library (``strand`` outside ``strand.app``, and ``forms``) never imports
the application (``strand.app``), each package imports only from packages at its level of
``ORDER`` or below, no module imports itself through others (no import circle, counting the
imports inside functions and under ``TYPE_CHECKING``), and ``strand/__init__.py`` names each name
of the public API once, with the module that defines it.

An import is an edge to the module that defines what it names: ``import a.b.c`` and ``from a.b
import c`` go to the submodule ``a.b.c`` where there is one, else to the package ``a.b``
(its ``__init__``); relative imports are resolved first. It is also an edge to the ``__init__`` of
every package on the way (``a``, ``a.b``), as Python runs them first, except the importer's own
packages, which Python has started before the importer. A package's ``__init__`` importing its
own submodules is an edge like any other: a submodule importing its package back is a circle.

An import inside a function counts as one at the top: it runs when the function is called, and
which ``__init__`` it runs then depends on what the process happened to import before, an order
nothing checks; moving an import into a function hides a circle from Python, not from the design.
"""

from __future__ import annotations

import ast
from collections.abc import Iterable, Mapping
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("strand", "forms")
APP = "strand.app"

#: the packages from the bottom up: a package imports only from its own level and those below.
#: ``strand`` is the package's ``__init__`` alone, the public API, which names the library's
#: modules; ``forms`` is the top-level package of the beam forms; every other name is a package
#: of ``strand``
ORDER = (
    ("forms", "contact", "solver"),  # the beam forms, contact between beams, the solver
    ("beam",),  # what any beam run needs: MPI helpers, distribution, field output, records
    ("cable",),  # cables, their geometry and meshes
    ("analytical",),  # the analytical references
    ("fatigue",),  # fatigue physics on arrays
    ("model",),  # the strand model: beams + strand contact
    ("setups",),  # the test set-ups on a model
    ("strand",),  # the public API
    ("app",),  # the application
)


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
                out |= _packages_run_first(module, name, known)
    return out


def _packages_run_first(module: str, importer: str, known: Mapping[str, Path]) -> set[str]:
    """The packages whose ``__init__`` Python runs before ``module`` when ``importer`` imports
    it: every package on ``module``'s path but those ``importer`` sits in (started already)."""
    started = {".".join(importer.split(".")[:i]) for i in range(1, importer.count(".") + 2)}
    parts = module.split(".")
    prefixes = (".".join(parts[:i]) for i in range(1, len(parts)))
    return {p for p in prefixes if p in known and _is_package(p, known) and p not in started}


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


def package_of(module: str) -> str:
    """The package of ``ORDER`` that ``module`` belongs to: ``strand.cable.mesh`` → ``cable``,
    ``strand`` → ``strand`` (its ``__init__``), ``forms.reissner`` → ``forms``."""
    parts = module.split(".")
    return parts[1] if parts[0] == "strand" and len(parts) > 1 else parts[0]


def package_graph(graph: Mapping[str, Iterable[str]]) -> dict[str, set[str]]:
    """Package → the other packages its modules import."""
    out: dict[str, set[str]] = {}
    for a, targets in graph.items():
        here = package_of(a)
        out.setdefault(here, set()).update(package_of(b) for b in targets if package_of(b) != here)
    return out


def order_violations(
    graph: Mapping[str, Iterable[str]], order: Iterable[Iterable[str]] = ORDER
) -> list[str]:
    """Each import of a module from a package above the importer's in ``order``, and each
    package without a place in it."""
    level = {package: i for i, packages in enumerate(order) for package in packages}
    unplaced = sorted({package_of(m) for m in graph} - set(level))
    return [f"{p}: not in the package order" for p in unplaced] + [
        f"{a} → {b} ({package_of(a)} below {package_of(b)})"
        for a, targets in sorted(graph.items())
        for b in sorted(targets)
        if package_of(a) in level
        and package_of(b) in level
        and level[package_of(b)] > level[package_of(a)]
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
    # ``from ..contact.hertz import``: Python runs strand/contact/__init__.py first
    assert {"strand.contact", "strand.contact.hertz"} <= graph["strand.model.compliances"]


def test_no_import_circle(graph):
    cycle = find_cycle(graph)
    assert cycle is None, "import circle: " + " → ".join(cycle)


def test_the_packages_import_in_order(graph):
    bad = order_violations(graph)
    assert not bad, "imports against the package order:\n" + "\n".join(bad)


def test_no_circle_between_packages(graph):
    """Packages of one level may import each other's modules, but not both ways."""
    cycle = find_cycle(package_graph(graph))
    assert cycle is None, "packages that import each other: " + " → ".join(cycle)


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
    assert g["strand.a"] == {"strand.app", "strand.app.b"}  # the package's __init__ runs first
    assert g["strand.app.b"] == {"strand.app", "strand.a"}
    cycle = find_cycle(g)
    assert cycle is not None and cycle[0] == cycle[-1]
    assert set(cycle) in (
        {"strand.app", "strand.app.b"},
        {"strand.a", "strand.app.b"},
        {"strand.a", "strand.app", "strand.app.b"},
    )
    assert layer_violations(g) == ["strand.a → strand.app", "strand.a → strand.app.b"]
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": set()}) is None
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]


def _write(root: Path, files: Mapping[str, str]) -> None:
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)


def test_a_circle_closed_by_a_package_init_is_found(tmp_path):
    """The settings import the kinds' registry inside a function; Python runs the package
    ``kinds/__init__.py`` first, which imports ``kinds.base``, which imports the settings: a
    circle that an edge to the registry module alone would miss."""
    _write(
        tmp_path,
        {
            "strand/__init__.py": "",
            "strand/app/__init__.py": "",
            "strand/app/settings.py": "def f():\n    from .kinds.registry import registered\n",
            "strand/app/kinds/__init__.py": "from .base import Kind\n",
            "strand/app/kinds/base.py": "from ..settings import f\nfrom .registry import add\n",
            "strand/app/kinds/registry.py": "",
        },
    )
    g = import_graph(tmp_path, ["strand"])
    assert g["strand.app.settings"] == {"strand.app.kinds", "strand.app.kinds.registry"}
    # a module's own packages have started before it: no edge back to them
    assert g["strand.app.kinds.base"] == {"strand.app.settings", "strand.app.kinds.registry"}
    assert find_cycle(g) == [
        "strand.app.kinds",
        "strand.app.kinds.base",
        "strand.app.settings",
        "strand.app.kinds",
    ]
    # without the package's __init__ importing base there is no circle
    (tmp_path / "strand/app/kinds/__init__.py").write_text("")
    assert find_cycle(import_graph(tmp_path, ["strand"])) is None


def test_the_order_check_fails_where_it_should(tmp_path):
    """A package importing one above it (at the top of a module, inside a function, from a
    package ``__init__``, or through a package's ``__init__``) and a package without a place."""
    _write(
        tmp_path,
        {
            "strand/__init__.py": "",
            "strand/cable/__init__.py": "from ..model import partition\n",
            "strand/cable/mesh.py": "def m():\n    from strand.model.partition import p\n",
            "strand/cable/geometry.py": "from ..setups.base import q\n",
            "strand/model/__init__.py": "",
            "strand/model/partition.py": "from ..cable import mesh\n",
            "strand/setups/__init__.py": "from .saddle import S\n",
            "strand/setups/base.py": "",
            "strand/setups/saddle.py": "from ..model import partition\n",
            "strand/extra/__init__.py": "",
        },
    )
    g = import_graph(tmp_path, ["strand"])
    order = (("cable",), ("model",), ("setups",), ("strand",))
    assert order_violations(g, order) == [
        "extra: not in the package order",
        "strand.cable → strand.model (cable below model)",
        "strand.cable → strand.model.partition (cable below model)",
        "strand.cable.geometry → strand.setups (cable below setups)",
        "strand.cable.geometry → strand.setups.base (cable below setups)",
        "strand.cable.mesh → strand.model (cable below model)",
        "strand.cable.mesh → strand.model.partition (cable below model)",
    ]
    assert order_violations(g, (("cable", "model"), ("setups",), ("extra", "strand"))) == [
        "strand.cable.geometry → strand.setups (cable below setups)",
        "strand.cable.geometry → strand.setups.base (cable below setups)",
    ]
    assert find_cycle(package_graph(g)) == ["cable", "model", "cable"]
    assert order_violations(g, (("strand", "extra"), ("setups",), ("model",), ("cable",))) == [
        "strand.model.partition → strand.cable (model below cable)",
        "strand.model.partition → strand.cable.mesh (model below cable)",
        "strand.setups.saddle → strand.model (setups below model)",
        "strand.setups.saddle → strand.model.partition (setups below model)",
    ]


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
