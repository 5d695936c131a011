"""Every setting of a case file with its default and meaning, from its declaration
(``strand.app.settings_schema.entries``): the one source of the settings reference in the docs
(``docs/_ext/strand_docs.py``) and of the settings in ``strand run --help``. A setting added to a
settings class, or to a set-up kind's own (``strand.app.kinds``), is listed without any list to
keep. ``field_comments`` reads the comments of the cable's fields (``strand.cable.description``),
which are no case settings.
"""

from __future__ import annotations

import inspect
import io
import textwrap
import tokenize
from dataclasses import MISSING, dataclass

from ..beam.setting import default_of

__all__ = ["Setting", "sections", "default_toml", "field_comments", "help_text"]


@dataclass(frozen=True)
class Setting:
    """One setting of a section: its key, default (as TOML), meaning, summary (its first
    sentence), SI unit ("" if none) and the set-up kind it belongs to ("" for the settings every
    kind shares)."""

    name: str
    default: str
    meaning: str
    summary: str
    kind: str = ""
    unit: str = ""


def field_comments(cls) -> dict[str, str]:
    """Each field's comment in ``cls``'s source: the comment on its line and the comment lines
    right under it, indented further."""
    out: dict[str, str] = {}
    current = last = None
    source = textwrap.dedent(inspect.getsource(cls))
    for tok in tokenize.generate_tokens(io.StringIO(source).readline):
        if tok.type == tokenize.NAME and tok.start[1] == 4 and current is None:
            current = tok.string
        elif tok.type == tokenize.COMMENT and current:
            out[current] = tok.string.lstrip("# ")
        elif tok.type == tokenize.NEWLINE:
            last, current = current, None
        elif tok.type == tokenize.COMMENT and tok.start[1] > 4 and last in out:
            out[last] += " " + tok.string.lstrip("# ")
        elif tok.type not in (tokenize.NL, tokenize.COMMENT):
            last = None if tok.type != tokenize.NAME else last
    return out


def default_toml(f) -> str:
    """The default of the dataclass field ``f`` as a case file writes it; "required" if none."""
    from .settings_schema import toml_default

    value = default_of(f)
    return "required" if value is MISSING else toml_default(value)


def sections() -> dict[str, tuple[str, list[Setting]]]:
    """Per section of a case file (``strand.app.settings.SECTIONS``): its class's one-line
    summary and its settings, those every set-up kind shares first, then each registered kind's
    own."""
    from .settings import SECTIONS
    from .settings_schema import entries, toml_default

    out = {}
    for section, cls in SECTIONS.items():
        doc = (inspect.getdoc(cls) or "").split("\n\n")[0]
        settings = [
            Setting(
                e.name,
                toml_default(e.default),
                e.meta.doc,
                e.meta.summary,
                e.kind,
                e.meta.unit,
            )
            for e in entries(section)
        ]
        out[section] = (doc, settings)
    return out


def help_text(width: int = 100) -> str:
    """Every setting of every section, with its default, unit and summary, as ``strand run
    --help`` prints them."""
    from .settings_schema import CABLE

    lines = _entry('cable = "cardinal"', CABLE, width)
    for section, (_, settings) in sections().items():
        lines += ["", f"[{section}]"]
        for s in settings:
            summary = s.summary.replace("``", "")
            if s.unit:
                summary = f"({s.unit}) {summary}"
            if s.kind:
                summary = f'(kind = "{s.kind}") {summary}'
            lines += _entry(f"  {s.name} = {s.default}", summary, width)
    return "\n".join(lines)


def _entry(key: str, text: str, width: int, column: int = 30) -> list[str]:
    """``key``, then ``text`` wrapped from ``column`` on, beside it if it leaves room."""
    pad = " " * column
    lines = textwrap.wrap(text, width, initial_indent=pad, subsequent_indent=pad) or [pad]
    if len(key) < column - 1:
        return [key.ljust(column) + lines[0].lstrip(), *lines[1:]]
    return [key, *lines]
