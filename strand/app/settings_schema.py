"""Every setting of a case file, from its one declaration (``strand.beam.setting.setting`` on
the fields of the settings classes, ``strand.app.settings``, and of the registered set-up
kinds' own, ``strand.app.kinds``): the entries of each section (``entries``), the commented case
template (``template``, ``strand run --template``) and the JSON Schema of a case file
(``json_schema``; shipped as ``case.schema.json`` for editors that check TOML against a schema,
taplo and Even Better TOML). The case reader (``strand.app.case``), ``strand run --help`` and the
settings reference (``strand.app.settings_reference``) read the same entries.

The set-up kinds join in here, when a case is read or a text is made: the settings classes
import nothing of them.
"""

from __future__ import annotations

import json
import re
import textwrap
from dataclasses import dataclass, fields, replace
from pathlib import Path
from typing import Any

from ..beam.setting import Declared, declared, default_of
from ..cable.description import CORE_KEYS, LAYER_KEYS
from .settings import KIND_SECTIONS, SECTIONS

__all__ = [
    "Entry",
    "entries",
    "kind_settings",
    "toml_default",
    "template",
    "json_schema",
    "schema_text",
    "write_schema",
    "SCHEMA_FILE",
    "CABLE",
]

#: the JSON Schema of a case file, as shipped with the package (``json_schema``)
SCHEMA_FILE = Path(__file__).with_name("case.schema.json")

#: ``cable``'s meaning (it is no settings class's field)
CABLE = (
    "built-in (cardinal, judge120), a cable TOML file (relative to the case file), or a "
    "[cable] table with a [cable.core] table and one [[cable.layer]] table per layer"
)


@dataclass(frozen=True)
class Entry:
    """One setting of a section: its key, default, declaration and the set-up kind it belongs
    to ("" for the settings every kind shares)."""

    name: str
    default: Any
    meta: Declared
    kind: str = ""


def _registered() -> tuple:
    """The registered set-up kinds (the built-in ones registered by importing them)."""
    from . import kinds

    return kinds.registered()


def kind_settings(section: str) -> dict[str, Any]:
    """Every registered kind's own settings of ``section`` at their defaults, by kind name
    (``WithKinds.by_kind``); {} for a section without kinds' settings."""
    if section not in KIND_SECTIONS:
        return {}
    return {kind.name: getattr(kind, KIND_SECTIONS[section])() for kind in _registered()}


def entries(section: str) -> list[Entry]:
    """The settings of ``section``: those every set-up kind shares, then each registered
    kind's own; ``[load] kind`` chooses among the registered kinds."""
    classes = [(SECTIONS[section], "")]
    if section in KIND_SECTIONS:
        classes += [(getattr(k, KIND_SECTIONS[section]), k.name) for k in _registered()]
    out = []
    for cls, kind in classes:
        for f in fields(cls):
            meta = declared(f)
            if meta is None:
                continue  # by_kind
            if (section, f.name) == ("load", "kind"):
                meta = replace(meta, choices=tuple(k.name for k in _registered()))
            out.append(Entry(f.name, default_of(f), meta, kind))
    return out


def toml_default(value: Any) -> str:
    """A default as a case file writes it: floats in at most 6 significant digits."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, tuple):
        return "[" + ", ".join(repr(v) for v in value) + "]"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, float):
        return re.sub(r"e([+-])0*(\d)", lambda m: "e" + m[1].strip("+") + m[2], f"{value:.6g}")
    return repr(value)


def _comment(entry: Entry) -> str:
    """A setting's comment in the template: its unit, kind and summary."""
    head = ", ".join(
        t for t in (entry.meta.unit, f'kind = "{entry.kind}"' if entry.kind else "") if t
    )
    summary = entry.meta.summary.replace("``", "")
    return f"{head}: {summary}" if head else summary


def template(width: int = 100) -> str:
    """A commented case file with every setting at its default (``strand run --template``):
    valid TOML, read as the default case."""
    lines = [
        "# A strand case file: every setting at its default, with its unit and meaning",
        "# (strand run --template). Keep only what you change; the settings reference of the",
        "# docs gives each setting in full. Units: SI.",
        "",
        *_commented('cable = "cardinal"', CABLE, width),
    ]
    for section in SECTIONS:
        lines += ["", f"[{section}]"]
        for e in entries(section):
            lines += _commented(f"{e.name} = {toml_default(e.default)}", _comment(e), width)
    return "\n".join(lines) + "\n"


def _commented(key: str, text: str, width: int, column: int = 26) -> list[str]:
    """``key``, then ``text`` as a comment wrapped from ``column`` on."""
    pad = " " * column
    wrapped = textwrap.wrap(text, width - column - 2) or [""]
    comments = [f"# {line}" for line in wrapped]
    if len(key) < column - 1:
        return [key.ljust(column) + comments[0], *(pad + c for c in comments[1:])]
    return [key, *(pad + c for c in comments)]


# --- the JSON Schema ----------------------------------------------------------------------


def _value_schema(entry: Entry) -> dict[str, Any]:
    """The JSON Schema of one setting's value, with its meaning and default."""
    meta, default = entry.meta, entry.default
    if meta.schema is not None:
        out = dict(meta.schema)
    elif isinstance(default, bool):
        out = {"type": "boolean"}
    elif isinstance(default, int | float):
        whole = isinstance(default, int) or meta.sign == "count"
        out = {"type": "integer" if whole else "number"}
        if meta.sign == "positive":
            out["exclusiveMinimum"] = 0
        elif meta.sign in ("zero_is_off", "count"):
            out["minimum"] = 0
    elif isinstance(default, str):
        out = {"type": "string"}
        if meta.allowed():
            out["enum"] = list(meta.allowed())
    elif isinstance(default, tuple):
        out = {"type": "array", "items": {"type": "number"}}
    else:
        raise TypeError(f"{entry.name}: no JSON Schema for a default {default!r}")
    unit = f" ({meta.unit})" if meta.unit else ""
    kind = f'kind = "{entry.kind}": ' if entry.kind else ""
    out["description"] = f"{kind}{meta.doc}{unit}".replace("``", "`")
    out["default"] = json.loads(json.dumps(default))
    return out


def _cable_schema() -> dict[str, Any]:
    def table(keys) -> dict[str, Any]:
        return {
            "type": "object",
            "properties": {k: {} for k in sorted(keys)},
            "additionalProperties": False,
        }

    return {
        "description": CABLE,
        "anyOf": [
            {"type": "string"},
            {
                "type": "object",
                "properties": {
                    "name": {"type": "string"},
                    "core": table(CORE_KEYS),
                    "layer": {"type": "array", "items": table(LAYER_KEYS)},
                },
                "required": ["core", "layer"],
                "additionalProperties": False,
            },
        ],
    }


def json_schema() -> dict[str, Any]:
    """The JSON Schema (draft 7) of a case file: every section and setting, each with its type,
    sign, choices, meaning and default; an unknown key fails it."""
    properties: dict[str, Any] = {"cable": _cable_schema()}
    for section, cls in SECTIONS.items():
        properties[section] = {
            "type": "object",
            "description": (cls.__doc__ or "").split("\n\n")[0].strip(),
            "properties": {e.name: _value_schema(e) for e in entries(section)},
            "additionalProperties": False,
        }
    return {
        "$schema": "http://json-schema.org/draft-07/schema#",
        "title": "strand case file",
        "description": "A case of strand (strand run): every setting has a default; a case "
        "lists what it changes. Units: SI. Generated by strand.app.settings_schema.",
        "type": "object",
        "properties": properties,
        "additionalProperties": False,
    }


def schema_text() -> str:
    """``json_schema`` as the shipped file ``case.schema.json`` holds it."""
    return json.dumps(json_schema(), indent=2, ensure_ascii=False) + "\n"


def write_schema() -> None:
    """Write ``SCHEMA_FILE`` from the declarations (after a setting is added or changed)."""
    SCHEMA_FILE.write_text(schema_text())
