"""Case files (TOML): the cable, its mesh, contact, loads, load steps, solver and outputs.

Every setting has a default; a case file only lists what it changes. The default case is the seed
paper's test (docs/theory.md §4): Cardinal, 1 m, 40 kN, then the saddle cycle 0 → +4.3 → 0 → −4.3
→ 0 kN. Each setting is declared once, on its settings class's field (``strand.app.settings``,
the set-up kinds' own in ``strand.app.kinds``): ``strand run --template`` prints every one at its
default with its unit and meaning, a commented case file to start from.

Unknown keys and bad values are errors naming the file and the key, raised before any computing:
this module checks each value alone against its declaration (one reader for every setting,
``strand.beam.setting.read_value``), ``strand.app.checks`` the settings against one another. The
command line's ``--set`` overrides are read by ``strand.app.case_overrides``.
"""

from __future__ import annotations

import tomllib
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

from ..beam.setting import SettingError, read_value, where_text
from ..cable.description import (
    Cable,
    CableError,
    built_in_cable,
    built_in_cables,
    cable_from_dict,
    load_cable,
)
from ..cable.input_file import read_text
from .case_overrides import merge_settings, parse_settings
from .case_toml import cable_table
from .errors import CaseError
from .settings import KIND_SECTIONS, SECTIONS, Case
from .settings_schema import entries, kind_settings

if TYPE_CHECKING:
    from .kinds import SetupKind

#: ``Case`` (``strand.app.settings``) and ``CaseError`` (``strand.app.errors``) are importable
#: from here too
__all__ = ["load_case", "case_from_dict", "check_loads_given"]


def _section(name: str, table, source: str):
    """The settings of section ``name`` read from its ``table`` (every key checked against its
    declaration), with every registered set-up kind's own where the section has them."""
    if not isinstance(table, dict):
        raise CaseError(f"{source}: [{name}] must be a table")
    known = {e.name: e for e in entries(name)}
    unknown = sorted(set(table) - set(known))
    if unknown:
        raise CaseError(
            f"{source}: unknown setting(s) in [{name}]: {unknown}; allowed: {sorted(known)}"
        )
    values = {}
    for key, value in table.items():
        e = known[key]
        try:
            values[key] = read_value(
                where_text(f"[{name}] ", key, value, e.meta.unit), value, e.default, e.meta
            )
        except SettingError as err:
            raise CaseError(f"{source}: {err}") from None
    cls = SECTIONS[name]
    try:
        if name in KIND_SECTIONS:
            return cls(by_kind=kind_settings(name)).with_values(**values)
        return cls(**values)
    except CableError as e:
        raise CaseError(f"{source}: [{name}] {e}") from None


def _cable(spec, base: Path | None, source: str) -> Cable:
    """The cable ``spec`` names (built-in, file or table), with the ``CableEdits`` of the
    command line when ``spec`` is (named cable, edits)."""
    if isinstance(spec, tuple):
        named, edits = spec
        return _cable(edits.applied(cable_table(_cable(named, base, source))), base, source)
    try:
        if isinstance(spec, str):
            if spec.lower() in built_in_cables():
                return built_in_cable(spec)
            path = (base or Path.cwd()) / spec
            if not path.exists():
                raise CaseError(
                    f"{source}: cable = {spec!r} is neither a built-in cable nor a file ({path}); "
                    f"built-in cables: {', '.join(built_in_cables())}"
                )
            return load_cable(path)
        if isinstance(spec, dict):
            return cable_from_dict(spec)
        raise CaseError(f"{source}: 'cable' must be a name, a file or a table")
    except CableError as e:
        raise CaseError(f"{source}: cable: {e}") from None


def case_from_dict(data: dict, base: Path | None = None, source: str = "case") -> Case:
    """The case of ``data`` (a case file's tables; relative cable files from ``base``), every
    setting checked (``CaseError`` naming ``source`` and the setting)."""
    from . import kinds  # noqa: F401  (here: the set-up kinds register when a case is read)
    from .checks import checked_case

    allowed = ["cable", *SECTIONS]
    unknown = sorted(set(data) - set(allowed))
    if unknown:
        raise CaseError(f"{source}: unknown setting(s) {unknown}; allowed: {allowed}")
    cable = _cable(data.get("cable", "cardinal"), base, source)
    sections = {name: _section(name, data.get(name, {}), source) for name in SECTIONS}
    case, kind = checked_case(Case(cable, **sections, source=source))
    return replace(case, unset_loads=_unset_loads(data, case, kind))


def _unset_loads(data: dict, case: Case, kind: SetupKind) -> tuple[str, ...]:
    """The loads a run of ``case`` needs (the tension, and the cycle's amplitude, ``kind``'s
    parameter, unless the cycle stays at zero or a sweep gives the amplitudes) that ``data``
    leaves out, for a cable other than Cardinal, whose defaults they are."""
    spec = data.get("cable", "cardinal")
    if isinstance(spec, tuple):  # a cable edited on the command line: the loads of the one named
        spec = spec[0]
    if isinstance(spec, str) and spec.lower() == "cardinal":
        return ()
    needed = ["tension"]
    if any(case.load.cycle) and not case.load.sweep:
        needed.append(kind.parameter)
    given = data.get("load", {})
    return tuple(k for k in needed if k not in given)


def check_loads_given(case: Case) -> None:
    """Refuse (``CaseError``, one line) to run ``case`` with Cardinal's default loads on a cable
    of its own: they would load a smaller strand far beyond what it carries."""
    if case.unset_loads:
        defaults = ", ".join(f"{k} = {getattr(case.load, k):g}" for k in case.unset_loads)
        raise CaseError(
            f"{case.source}: give [load] {', '.join(case.unset_loads)} for the cable "
            f"{case.cable.name!r}: the defaults ({defaults}, in SI units) are the built-in "
            "Cardinal's"
        )


def load_case(path: str | Path | None = None, settings: list[str] = ()) -> Case:
    """Read a case file; ``None`` gives the default case (the seed paper's Cardinal test).
    ``settings`` (``"section.key=value"``, from ``--set``) override the file's."""
    overrides = parse_settings(list(settings))
    if path is None:
        source = "built-in default" + (" with --set" if settings else "")
        return case_from_dict(merge_settings({}, overrides), source=source)
    path = Path(path)
    text = read_text(path, "case file (TOML)", CaseError, missing="case file")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise CaseError(f"{path}: not valid TOML ({e})") from None
    if "core" in data and "layer" in data:  # a bare cable description is a case too
        data = {"cable": data}
    data = merge_settings(data, overrides)
    output = data.get("output", {})
    if isinstance(output, dict) and "folder" not in output:  # results/<case name> by default
        data = {**data, "output": {**output, "folder": f"results/{path.stem}"}}
    return case_from_dict(data, path.parent, str(path))
