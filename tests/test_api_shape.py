"""The shape of strand's public signatures, read from the source (AST, no imports): no public
function, method or class takes more than ``MAX_POSITIONAL`` positional parameters; the options
past them are keyword-only (``*,``) or grouped in a settings object (issue 41)."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1] / "strand"

#: positional parameters a public signature may take (``self`` and ``cls`` not counted)
MAX_POSITIONAL = 7

#: records (dataclasses whose fields are all positional) that take more, made keyword-only one by
#: one: a record may leave this list, never join it (their count here is what they take now)
RECORDS_TO_CUT = {
    "strand/app/kinds/bending.py:BendingReport": 11,
    "strand/app/step_records.py:RunStep": 12,
    "strand/app/step_records.py:StepContext": 9,
    "strand/app/settings.py:Case": 9,
    "strand/cable/geometry.py:ContactPairs": 9,
    "strand/cable/geometry.py:StrandGeometry": 10,
    "strand/contact/pairs.py:NodePairs": 9,
    "strand/fatigue/sn.py:SNCurve": 8,
    "strand/model/checkpoint.py:Checkpoint": 11,
    "strand/model/contact_settings.py:ContactSettings": 11,
    "strand/model/pair_results.py:PairResults": 9,
    "strand/model/cell_results.py:CellResults": 11,
    "strand/model/programme.py:Stage": 9,
    "strand/model/reactions.py:EndReactions": 8,
    "strand/model/same_layer.py:SameLayerPairs": 11,
    "strand/setups/bending.py:ZoneBending": 10,
    "strand/solver/convergence.py:NewtonOptions": 15,
    "strand/solver/stepping.py:StepRecord": 11,
}


def _positional(args: ast.arguments, method: bool) -> int:
    names = [a.arg for a in (*args.posonlyargs, *args.args)]
    if method and names and names[0] in ("self", "cls"):
        names = names[1:]
    return len(names)


def _is_dataclass(node: ast.ClassDef) -> tuple[bool, bool]:
    """Whether ``node`` is a dataclass, and whether its fields are keyword-only."""
    for d in node.decorator_list:
        target = d.func if isinstance(d, ast.Call) else d
        name = target.attr if isinstance(target, ast.Attribute) else getattr(target, "id", "")
        if name == "dataclass":
            kw_only = isinstance(d, ast.Call) and any(
                k.arg == "kw_only" and isinstance(k.value, ast.Constant) and k.value.value
                for k in d.keywords
            )
            return True, kw_only
    return False, False


def _fields(node: ast.ClassDef) -> int:
    """A dataclass's positional fields: annotated names up to a ``KW_ONLY`` marker, not
    ``ClassVar``s."""
    n = 0
    for s in node.body:
        if isinstance(s, ast.AnnAssign) and isinstance(s.target, ast.Name):
            annotation = ast.unparse(s.annotation)
            if "KW_ONLY" in annotation:
                break
            if "ClassVar" not in annotation:
                n += 1
    return n


def long_signatures(source: str, where: str) -> dict[str, int]:
    """The public functions, methods and classes of ``source`` that take more than
    ``MAX_POSITIONAL`` positional parameters (``where:name`` → how many); dataclasses by their
    fields."""
    found: dict[str, int] = {}

    def visit(body, prefix: str, in_class: bool, public: bool) -> None:
        for node in body:
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                mine = public and (not node.name.startswith("_") or node.name == "__init__")
                n = _positional(node.args, in_class)
                if mine and n > MAX_POSITIONAL:
                    found[f"{where}:{prefix}{node.name}"] = n
            elif isinstance(node, ast.ClassDef):
                mine = public and not node.name.startswith("_")
                dataclass, kw_only = _is_dataclass(node)
                if mine and dataclass and not kw_only and _fields(node) > MAX_POSITIONAL:
                    found[f"{where}:{prefix}{node.name}"] = _fields(node)
                visit(node.body, f"{prefix}{node.name}.", True, mine)

    visit(ast.parse(source).body, "", False, True)
    return found


def test_the_check_finds_a_long_signature():
    source = (
        "def f(a, b, c, d, e, f, g, h): pass\n"
        "def ok(a, b, c, d, e, f, g, *, h): pass\n"
        "def _private(a, b, c, d, e, f, g, h): pass\n"
        "class C:\n"
        "    def __init__(self, a, b, c, d, e, f, g, h): pass\n"
        "    def m(self, a, b, c, d, e, f, g): pass\n"
        "@dataclass\n"
        "class R:\n" + "".join(f"    x{i}: int\n" for i in range(8)) + "@dataclass(kw_only=True)\n"
        "class K:\n" + "".join(f"    x{i}: int\n" for i in range(8))
    )
    assert long_signatures(source, "m.py") == {"m.py:f": 8, "m.py:C.__init__": 8, "m.py:R": 8}


def test_no_public_signature_takes_more_than_seven_positional_parameters():
    found: dict[str, int] = {}
    for path in sorted(ROOT.rglob("*.py")):
        where = path.relative_to(ROOT.parent).as_posix()
        found |= long_signatures(path.read_text(), where)
    records = {k: v for k, v in found.items() if k in RECORDS_TO_CUT}
    others = {k: v for k, v in found.items() if k not in RECORDS_TO_CUT}
    assert not others, f"make the trailing parameters keyword-only (*,): {others}"
    grown = {k: v for k, v in records.items() if v > RECORDS_TO_CUT[k]}
    assert not grown, f"these records grew; give new fields kw_only: {grown}"
    gone = sorted(set(RECORDS_TO_CUT) - set(records))
    assert not gone, f"cut already: take them off RECORDS_TO_CUT: {gone}"
