"""Pages generated at build time into ``docs/_generated/``: the settings reference, read from the
settings dataclasses, and the demos as tutorials, converted by jupytext without running them.

Nothing here is hand-copied: a setting added to a settings class, or a demo added to ``demos/``,
appears in the next build. The tutorials show what each demo printed and drew as recorded in
``_static/tutorials/`` (``scripts/record_figures.py``): the build runs no demo.
"""

from __future__ import annotations

import inspect
import json
import re
from dataclasses import fields
from pathlib import Path

from sphinx.util import logging

ROOT = Path(__file__).parents[2]
GENERATED = "_generated"
logger = logging.getLogger(__name__)


# --- settings reference ---------------------------------------------------------------------


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def settings_reference() -> str:
    """The settings reference page (MyST), from ``strand.app.settings_reference``: the sections'
    settings (the registered set-up kinds' own too) and the cable's fields."""
    from strand.app.settings_reference import default_toml, field_comments, sections
    from strand.cable import description as cable

    out = [
        "# Settings reference",
        "",
        "Every setting of a case file, with its default, unit and meaning, generated when the",
        "docs are built from the one declaration of each setting (`strand.beam.setting`), as",
        "`strand run --help` lists them and `strand run --template` writes them as a commented",
        "case file. SI units. A case file lists only what it changes; `strand run case.toml --set",
        "section.key=value` changes one from the command line. Unknown keys and bad values stop",
        "the run before anything is computed, naming the file and the key. Editors that check",
        "TOML against a JSON Schema (taplo, Even Better TOML) can use the one shipped with strand,",
        "`strand/app/case.schema.json`: a first line `#:schema <path to it>` in a case file.",
        "",
        "## `cable`",
        "",
        '`cable = "cardinal"` (the built-in Cardinal ACSR 54/7, the default), a cable file (TOML,',
        "relative to the case file), or a `[cable]` table with `name`, a `[cable.core]` table and",
        "one `[[cable.layer]]` table per layer of helical wires, innermost first:",
        "",
        "| key | in | meaning |",
        "|---|---|---|",
    ]
    comments = {**field_comments(cable.Wire), **field_comments(cable.Layer)}
    names = {
        "diameter": "wire diameter",
        "E": "Young's modulus",
        "nu": "Poisson's ratio",
        "wires": "number of wires",
        "lay_angle": "lay angle",
        "lay": "lay hand",
    }
    keys = [f.name for f in fields(cable.Wire)] + [f.name for f in fields(cable.Layer)]
    for key in [k for k in keys if k in cable.CORE_KEYS | cable.LAYER_KEYS]:
        where = ", ".join(
            name
            for name, keys in (("core", cable.CORE_KEYS), ("layer", cable.LAYER_KEYS))
            if key in keys
        )
        text = ", ".join(t for t in (names.get(key), comments.get(key)) if t and t != "-")
        out.append(f"| `{key}` | {where} | {_cell(text)} |")
    optional = [f.name for f in fields(cable.Wire) if default_toml(f) != "required"]
    out += ["", f"Every key is required but {', '.join(f'`{k}`' for k in optional)}."]
    for section, (doc, settings) in sections().items():
        out += ["", f"## `[{section}]`", ""]
        if doc:
            out += [doc, ""]
        out += ["| setting | default | unit | meaning |", "|---|---|---|---|"]
        for s in settings:
            text = f'*`kind = "{s.kind}"` only.* {s.meaning}' if s.kind else s.meaning
            unit = s.unit or "–"
            out.append(f"| `{s.name}` | `{_cell(s.default)}` | {unit} | {_cell(text)} |")
    return "\n".join(out) + "\n"


# --- the columns of the set-up kinds' tables ---------------------------------------------------


def _record_rows(record_type) -> list[str]:
    from strand.beam.records import columns

    rows = []
    for name, f in zip(columns(record_type), fields(record_type), strict=True):
        unit = f.metadata.get("unit", "").replace("_per_", "/").replace("Nm", "N m")
        doc = f.metadata.get("doc", "") or f.name.replace("_", " ")
        rows.append(f"| `{name}` | {unit or '–'} | {_cell(doc)} |")
    return rows


def kind_columns() -> str:
    """Per registered set-up kind, the columns its state and bending records give to
    ``steps.csv`` and ``moment_curvature.csv`` (from the records' field metadata)."""
    from strand.app import kinds
    from strand.app.case import load_case

    out = []
    for kind in kinds.registered():
        case = load_case(settings=[f'load.kind="{kind.name}"', *kind.example])
        setup = kind.setup(case).func
        out += [
            f'**`kind = "{kind.name}"`** (`{setup.__module__}.{setup.__name__}`):',
            "",
            "| `steps.csv` column | unit | meaning |",
            "|---|---|---|",
            *_record_rows(setup.state_type),
            "",
            f"`moment_curvature.csv`, at every step of the cycle: "
            f"{_cell(inspect.getdoc(setup.bending_type) or '')}",
            "",
            "| `moment_curvature.csv` column | unit | meaning |",
            "|---|---|---|",
            "| `step` | – | the step's number (as in `steps.csv`) |",
            *_record_rows(setup.bending_type),
            "",
        ]
    return "\n".join(out)


# --- tutorials from the demos -----------------------------------------------------------------

#: what each demo printed and drew when last recorded (``scripts/record_figures.py``), per demo
RECORDED = Path(__file__).parents[1] / "_static" / "tutorials"


def recorded(stem: str) -> tuple[list[dict], list[str]]:
    """A demo's recorded cells (``{"code", "output"}``, in order) and figure files."""
    folder = RECORDED / stem
    cells = json.loads((folder / "outputs.json").read_text()) if folder.is_dir() else []
    return cells, sorted(p.name for p in folder.glob("*.png"))


def _printed(text: str) -> str:
    return f"```{{code-block}} text\n:class: demo-output\n\n{text.rstrip()}\n```"


def _figure(stem: str, name: str) -> str:
    return (
        f"```{{figure}} /_static/tutorials/{stem}/{name}\n:alt: {name}, drawn by {stem}\n\n"
        f"`{name}`, drawn by the code above (in `results/{stem}/`)\n```"
    )


def demo_page(path: Path) -> tuple[str, list[str]]:
    """A demo (jupytext py:light) as a MyST page, and what of its record is stale: its markdown
    cells as text, its code cells as code blocks, not executed; under each code cell what it
    printed and the figures it draws, as recorded; a line under its title says how to run it.

    The stale list names each recorded cell no longer in the demo and each figure no code cell
    names (``generate`` warns of them, which fails a ``-W`` build)."""
    import jupytext
    import nbformat

    nb = jupytext.read(path)
    nb.metadata = {}
    cells, figures = recorded(path.stem)
    printed = {c["code"]: c["output"] for c in cells if c["output"].strip()}
    code = {c.source for c in nb.cells if c.cell_type == "code"}
    stale = [
        f"a recorded cell is not in the demo: {c['code'][:60]!r}..."
        for c in cells
        if c["code"] not in code
    ]
    placed = set()
    shown = []
    for cell in nb.cells:
        shown.append(cell)
        if cell.cell_type != "code":
            continue
        after = [_printed(printed[cell.source])] if cell.source in printed else []
        for name in figures:
            if name not in placed and name in cell.source:
                placed.add(name)
                after.append(_figure(path.stem, name))
        if after:
            shown.append(nbformat.v4.new_markdown_cell("\n\n".join(after)))
    stale += [f"no code cell draws the recorded {name}" for name in figures if name not in placed]
    nb.cells = shown
    text = jupytext.writes(nb, fmt="md")
    text = re.sub(r"\A---\n.*?\n---\n+", "", text, flags=re.S)  # jupytext's header
    text = re.sub(r"^<!-- #(end)?region -->\n", "", text, flags=re.M)
    outputs = (
        "shown with what each cell printed and the figures it drew in a serial run (recorded "
        "by `scripts/record_figures.py`)"
        if cells
        else "shown here without its outputs"
    )
    run = (
        f"\n*This tutorial is `demos/{path.name}`, {outputs}. Run it with `.venv/bin/python "
        f"demos/{path.name}`, or on two processes with `.venv/bin/mpirun -n 2 .venv/bin/python "
        f"demos/{path.name}`: it checks itself and leaves its figures in `results/`. The tests "
        "run it both ways (`tests/test_demos.py`).*\n"
    )
    title, _, rest = text.partition("\n")
    return f"{title}\n{run}{rest}", stale


def _write(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` unless it holds it already (keeps Sphinx's incremental build)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


def generate(app) -> None:
    out = Path(app.srcdir) / GENERATED
    _write(out / ".gitignore", "*\n")
    _write(out / "settings.md", settings_reference())
    _write(out / "kind_columns.inc", kind_columns())
    demos = sorted((ROOT / "demos").glob("demo_*.py"))
    for demo in demos:
        page, stale = demo_page(demo)
        _write(out / "tutorials" / f"{demo.stem}.md", page)
        for problem in stale:
            logger.warning(f"{demo.name}: {problem}: run scripts/record_figures.py {demo.stem}")
    for stale in (out / "tutorials").glob("*.md"):
        if not (ROOT / "demos" / f"{stale.stem}.py").exists():
            stale.unlink()


def prose_first_clause(app, what, name, obj, options, lines) -> None:
    """Put back the first clause of an attribute's or constant's docstring that napoleon took
    for its type.

    Napoleon reads "X: Y" on the first line of such a docstring as a type X and a description
    Y, so that a ``#:`` comment such as "``[steps] control``: growth after easy solves, ..."
    rendered as a "Type:" field under the clause that follows. strand writes its docstrings as
    prose, never in that form: the clause goes back in front of its sentence. Connected after
    napoleon (priority 600 > 500)."""
    if what not in ("attribute", "data", "property"):
        return
    typed = [i for i, line in enumerate(lines) if line.startswith(":type: ")]
    if not typed:
        return
    clause = lines.pop(typed[-1])[len(":type: ") :]
    while lines and not lines[-1].strip():
        lines.pop()
    first = next((i for i, line in enumerate(lines) if line.strip()), None)
    if first is None:
        lines.append(clause)
    else:
        lines[first] = f"{clause}: {lines[first]}"


def setup(app):
    app.connect("builder-inited", generate)
    app.connect("autodoc-process-docstring", prose_first_clause, priority=600)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
