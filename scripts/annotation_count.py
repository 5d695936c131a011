"""Count annotated parameters and ``Any`` dataclass fields in strand's library and application.

    .venv/bin/python scripts/annotation_count.py [folder ...]   # default: strand forms

Parameters: every argument of every ``def`` (positional-only, ordinary, ``*args``, keyword-only,
``**kwargs``), ``self`` and ``cls`` of methods left out (nothing to annotate), lambdas left out.
Fields: class-body annotations of classes decorated ``@dataclass`` (with or without arguments)
whose annotation mentions ``Any`` (``Any``, ``dict[str, Any]``, ``list[Any] | None``); a bare
``dict``/``list`` counts as untyped too (``Any`` in disguise). Returns: totals per top folder,
then the whole.
"""

from __future__ import annotations

import argparse
import ast
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BARE = {"dict", "list", "tuple", "set", "Dict", "List", "Tuple", "Set"}


@dataclass
class Count:
    """The counts of one folder."""

    parameters: int = 0
    annotated: int = 0
    returns: int = 0  # functions with a return annotation
    functions: int = 0
    fields: int = 0  # dataclass fields
    any_fields: list[str] = field(default_factory=list)  # "module:Class.field"
    bare_fields: list[str] = field(default_factory=list)

    def add(self, other: Count) -> None:
        self.parameters += other.parameters
        self.annotated += other.annotated
        self.returns += other.returns
        self.functions += other.functions
        self.fields += other.fields
        self.any_fields += other.any_fields
        self.bare_fields += other.bare_fields


def _is_dataclass(node: ast.ClassDef) -> bool:
    for d in node.decorator_list:
        target = d.func if isinstance(d, ast.Call) else d
        name = target.attr if isinstance(target, ast.Attribute) else getattr(target, "id", "")
        if name == "dataclass":
            return True
    return False


def _names(annotation: ast.expr) -> set[str]:
    """The names an annotation mentions (string annotations parsed)."""
    if isinstance(annotation, ast.Constant) and isinstance(annotation.value, str):
        try:
            annotation = ast.parse(annotation.value, mode="eval").body
        except SyntaxError:
            return set()
    out = set()
    for n in ast.walk(annotation):
        if isinstance(n, ast.Name):
            out.add(n.id)
        elif isinstance(n, ast.Attribute):
            out.add(n.attr)
    return out


def _is_bare(annotation: ast.expr) -> bool:
    """``dict``, ``list | None`` and the like: a container without its item types."""
    if isinstance(annotation, ast.Constant) and isinstance(annotation.value, str):
        try:
            annotation = ast.parse(annotation.value, mode="eval").body
        except SyntaxError:
            return False
    if isinstance(annotation, ast.BinOp):
        return _is_bare(annotation.left) or _is_bare(annotation.right)
    return isinstance(annotation, ast.Name) and annotation.id in BARE


def count_file(path: Path) -> Count:
    """The counts of one module."""
    c = Count()
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    module = path.relative_to(ROOT).with_suffix("").as_posix().replace("/", ".")
    methods: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ClassDef):
            for item in node.body:
                if isinstance(item, ast.FunctionDef | ast.AsyncFunctionDef):
                    methods.add(id(item))
            if _is_dataclass(node):
                for item in node.body:
                    if isinstance(item, ast.AnnAssign) and isinstance(item.target, ast.Name):
                        names = _names(item.annotation)
                        if "ClassVar" in names or "KW_ONLY" in names:
                            continue
                        c.fields += 1
                        where = f"{module}:{node.name}.{item.target.id}"
                        if "Any" in names:
                            c.any_fields.append(where)
                        elif _is_bare(item.annotation):
                            c.bare_fields.append(where)
    for node in ast.walk(tree):
        if not isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            continue
        c.functions += 1
        c.returns += node.returns is not None
        a = node.args
        params = [*a.posonlyargs, *a.args, *a.kwonlyargs]
        params += [p for p in (a.vararg, a.kwarg) if p is not None]
        static = any(getattr(d, "id", "") == "staticmethod" for d in node.decorator_list)
        if id(node) in methods and not static and params and params[0].arg in ("self", "cls"):
            params = params[1:]
        c.parameters += len(params)
        c.annotated += sum(p.annotation is not None for p in params)
    return c


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folders", nargs="*", default=["strand", "forms"])
    parser.add_argument("--list", action="store_true", help="list the Any and bare fields")
    args = parser.parse_args(argv)
    total = Count()
    groups: dict[str, Count] = {}
    for folder in args.folders:
        for path in sorted((ROOT / folder).rglob("*.py")):
            rel = path.relative_to(ROOT).parts
            group = "/".join(rel[:2]) if rel[0] == "strand" and len(rel) > 2 else rel[0]
            c = count_file(path)
            groups.setdefault(group, Count()).add(c)
            total.add(c)
    print(
        f"{'':18} {'params':>7} {'annot.':>7} {'unannot.':>8} {'returns':>11} {'Any/bare fields':>16}"
    )
    for name, c in [*sorted(groups.items()), ("all", total)]:
        print(
            f"{name:18} {c.parameters:7d} {c.annotated:7d} {c.parameters - c.annotated:8d} "
            f"{c.returns:5d}/{c.functions:<5d} {len(c.any_fields):7d}/{len(c.bare_fields):<3d} "
            f"of {c.fields}"
        )
    if args.list:
        for where in total.any_fields:
            print("Any  ", where)
        for where in total.bare_fields:
            print("bare ", where)


if __name__ == "__main__":
    main()
