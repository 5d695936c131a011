"""Every setting of a case file with its default and meaning, read from the settings classes:
the one source of the settings reference in the docs (``docs/_ext/strand_docs.py``) and of the
settings in ``strand run --help``.

A setting's meaning is its class's ``Attributes:`` docstring entry, else the fuller of the comment
on its field and the comment beside its key in the commented case file of ``strand.app.case``'s
docstring (with the comment lines indented under either). A setting added to a settings class, or
to a set-up kind's own (``strand.app.kinds``), is listed without any list to keep.
"""

from __future__ import annotations

import inspect
import io
import re
import textwrap
import tokenize
from dataclasses import MISSING, dataclass, fields

__all__ = ["Setting", "sections", "default_toml", "field_comments", "help_text"]


@dataclass(frozen=True)
class Setting:
    """One setting of a section: its key, default (as TOML), meaning (the fullest text there
    is), summary (a line or two of it, ``_summary``), and the set-up kind it belongs to (""
    for the settings every kind shares)."""

    name: str
    default: str
    meaning: str
    summary: str
    kind: str = ""


def _attributes(cls) -> dict[str, str]:
    """The ``Attributes:`` section of ``cls``'s docstring (Google style), by name."""
    doc = inspect.getdoc(cls) or ""
    if "Attributes:" not in doc:
        return {}
    out: dict[str, str] = {}
    name = None
    for line in doc.split("Attributes:", 1)[1].splitlines():
        if line and not line.startswith(" "):
            break  # the next section
        m = re.match(r"^ {4}(\w+(?:, \w+)*):\s+(.*)$", line)
        if m:
            name = m.group(1)
            out[name] = m.group(2)
        elif name and line.strip():
            out[name] += " " + line.strip()
    for names in [k for k in out if "," in k]:  # "a, b: ..." documents both
        for n in names.split(","):
            out[n.strip()] = out[names]
    return out


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


def _template_comments(doc: str) -> dict[tuple[str, str], str]:
    """The comments of the commented case file in ``strand.app.case``'s docstring, by (section,
    key): the comment on the key's line and the comment lines indented under it."""
    out: dict[tuple[str, str], str] = {}
    section, key = "", None
    for line in doc.splitlines():
        s = line.strip()
        if m := re.match(r"^\[(\w+)\]$", s):
            section, key = m.group(1), None
        elif m := re.match(r"^(\w+)\s*=\s*[^#]*#\s*(.*)$", s):
            key = m.group(1)
            out[(section, key)] = m.group(2)
        elif re.match(r"^\w+\s*=", s):
            key = None
        elif s.startswith("#") and key and line.startswith("    " * 2):
            out[(section, key)] += " " + s.lstrip("# ")
    return out


def default_toml(f) -> str:
    """The default of the dataclass field ``f`` as a case file writes it; "required" if none."""
    if f.default is not MISSING:
        value = f.default
    elif f.default_factory is not MISSING:
        value = f.default_factory()
    else:
        return "required"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, tuple):
        return "[" + ", ".join(repr(v) for v in value) + "]"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, float):
        return re.sub(r"e([+-])0*(\d)", lambda m: "e" + m[1].strip("+") + m[2], f"{value:.6g}")
    return repr(value)


def _longer(template: str, comment: str) -> str:
    """The fuller of a setting's two comments (the case template's and the class's); a template
    comment that runs on into the next key's is left out."""
    if template.endswith((",", " with")):
        template = ""
    return max(template, comment, key=len) or "—"


def _summary(meaning: str, template: str, comment: str, most: int = 160) -> str:
    """The fullest of a setting's texts (its meaning's first sentence, its template and class
    comments) within ``most`` characters, else the shortest of them."""
    texts = [_first_sentence(meaning), _first_sentence(meaning, ".;"), comment]
    if not template.endswith((",", " with")):
        texts.append(template)
    texts = [t for t in texts if t and t != "—"] or ["—"]
    fitting = [t for t in texts if len(t) <= most]
    return max(fitting, key=len) if fitting else min(texts, key=len)


def _settings(section: str, classes, template: dict, skip=("by_kind",)) -> list[Setting]:
    out = []
    for cls, kind in classes:
        attributes, comments = _attributes(cls), field_comments(cls)
        for f in fields(cls):
            if f.name in skip:
                continue
            said = template.get((section, f.name), ""), comments.get(f.name, "")
            text = attributes.get(f.name) or _longer(*said)
            out.append(Setting(f.name, default_toml(f), text, _summary(text, *said), kind))
    return out


def sections() -> dict[str, tuple[str, list[Setting]]]:
    """Per section of a case file (``strand.app.settings.SECTIONS``): its class's one-line
    summary ("" if none) and its settings, those every set-up kind shares first, then each
    registered kind's own."""
    from . import case, kinds
    from .settings import KIND_SECTIONS, SECTIONS

    template = _template_comments(case.__doc__ or "")
    out = {}
    for section, cls in SECTIONS.items():
        doc = (inspect.getdoc(cls) or "").split("\n\n")[0]
        if "Attributes:" in doc or doc.startswith(f"{cls.__name__}("):
            doc = ""  # no summary: the dataclass's generated signature
        classes = [(cls, "")]
        if section in KIND_SECTIONS:
            own = KIND_SECTIONS[section]
            classes += [(getattr(k, own), k.name) for k in kinds.registered()]
        out[section] = (doc, _settings(section, classes, template))
    return out


def _first_sentence(text: str, stops: str = ".") -> str:
    """``text`` up to its first full stop (or other of ``stops``) followed by a space, outside
    brackets."""
    depth = 0
    for i, c in enumerate(text):
        depth += (c in "([") - (c in ")]")
        if c in stops and depth == 0 and text[i + 1 : i + 2] == " ":
            return text[: i + 1].rstrip(";")
    return text


def help_text(width: int = 100) -> str:
    """Every setting of every section, with its default and summary, as ``strand run --help``
    prints them."""
    cable = (
        "built-in (cardinal, judge120), a cable TOML file (relative to the case file), or a "
        "[cable] table with a [cable.core] table and one [[cable.layer]] table per layer"
    )
    lines = _entry('cable = "cardinal"', cable, width)
    for section, (_, settings) in sections().items():
        lines += ["", f"[{section}]"]
        for s in settings:
            summary = s.summary.replace("``", "")
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
