"""The command line's ``--set`` overrides of a case file: ``section.key=value`` items read as TOML
values (``parse_settings``) and laid over the file's tables (``merge_settings``); edits inside the
cable (``--set cable.core.nu=0.28``, ``--set cable.layer.2.E=60e9``) are ``CableEdits``, applied to
the case's cable when the case is read (``strand.app.case``).
"""

from __future__ import annotations

import re
import tomllib

from ..cable.description import CORE_KEYS, LAYER_KEYS
from .errors import CaseError

__all__ = ["parse_settings", "merge_settings", "CableEdits"]


class CableEdits(list):
    """The command line's edits of the case's cable (``--set cable.core.nu=0.28``,
    ``--set cable.layer.2.E=60e9``, ``--set cable.name=...``), in order: (path, value, item),
    the path ("core", key), ("layer", n, key) with n from 1 (the innermost helical layer), or
    ("name",)."""

    def applied(self, table: dict) -> dict:
        """A copy of the cable's ``table`` (``case_toml.cable_table``'s form) with the edits."""
        out = {**table, "core": dict(table["core"]), "layer": [dict(t) for t in table["layer"]]}
        for path, value, item in self:
            if path[0] == "name":
                out["name"] = value
            elif path[0] == "core":
                out["core"][path[1]] = value
            else:
                n = len(out["layer"])
                if not 1 <= path[1] <= n:
                    raise CaseError(
                        f"--set {item!r}: the cable {out['name']!r} has layers 1 to "
                        f"{n} (layer 1 the innermost helical one)"
                    )
                out["layer"][path[1] - 1][path[2]] = value
        return out


_CABLE_KEYS = "cable.name, cable.core.<key>, cable.layer.<n>.<key>"


def _cable_path(item: str, parts: list[str]) -> tuple:
    """The path in the cable of ``--set cable.<parts>=...`` (``CableEdits``), its keys checked."""
    table, *rest = parts
    if table == "name" and not rest:
        return ("name",)
    if table == "core" and len(rest) == 1:
        if rest[0] not in CORE_KEYS:
            raise CaseError(
                f"--set {item!r}: the cable's core has no key {rest[0]!r}; valid: "
                f"{', '.join(sorted(CORE_KEYS))}"
            )
        return ("core", rest[0])
    if table == "layer" and len(rest) == 2:
        if not rest[0].isdigit() or int(rest[0]) < 1:
            raise CaseError(
                f"--set {item!r}: expected a layer number 1, 2, … after cable.layer "
                "(1: the innermost helical layer)"
            )
        if rest[1] not in LAYER_KEYS:
            raise CaseError(
                f"--set {item!r}: a cable layer has no key {rest[1]!r}; valid: "
                f"{', '.join(sorted(LAYER_KEYS))}"
            )
        return ("layer", int(rest[0]), rest[1])
    raise CaseError(f"--set {item!r}: expected cable=<name or file> or one of {_CABLE_KEYS}")


def parse_settings(items: list[str]) -> dict:
    """``["section.key=value", ...]`` (the command line's ``--set``) as a nested dict of case
    settings; values are read as TOML (``2e-3``, ``true``, ``[1.0, 0.0]``), or else as strings.
    Keys inside the cable (``cable.core.nu``, ``cable.layer.1.E`` or ``cable.layer[1].E``,
    ``cable.name``) are ``CableEdits`` under ``"cable"``."""
    out: dict = {}
    for item in items:
        name, eq, text = item.partition("=")
        parts = re.sub(r"\[(\w+)\]", r".\1", name.strip()).split(".")
        if not eq or not all(parts) or (len(parts) > 2 and parts[0] != "cable"):
            raise CaseError(f"--set {item!r}: expected section.key=value, e.g. mesh.h_max=2e-3")
        try:
            value = tomllib.loads(f"v = {text.strip()}")["v"]
        except tomllib.TOMLDecodeError:
            value = text.strip()
        if parts[0] == "cable" and len(parts) > 1:
            edits = out.setdefault("cable", CableEdits())
            if not isinstance(edits, CableEdits):
                raise CaseError(
                    f"--set {item!r}: give the whole cable (--set cable=...) or edit "
                    "the case's, not both"
                )
            edits.append((_cable_path(item, parts[1:]), value, item))
        elif len(parts) == 2:
            out.setdefault(parts[0], {})[parts[1]] = value
        elif isinstance(out.get(name.strip()), CableEdits):
            raise CaseError(
                f"--set {item!r}: give the whole cable (--set cable=...) or edit the "
                "case's, not both"
            )
        else:
            out[name.strip()] = value
    return out


def merge_settings(data: dict, overrides: dict) -> dict:
    """A case file's tables ``data`` with the ``overrides`` of ``parse_settings``: each
    section's keys over the file's; ``CableEdits`` applied to the file's cable (built-in,
    file or table; Cardinal by default) when the case is read."""
    merged = dict(data)
    for k, v in overrides.items():
        if isinstance(v, CableEdits):
            merged[k] = (merged.get(k, "cardinal"), v)
        elif isinstance(v, dict) and isinstance(merged.get(k), dict):
            merged[k] = {**merged[k], **v}
        else:
            merged[k] = v
    return merged
