"""Case files (TOML): which cable, how it is meshed (and, later, loads and solver settings).

A case file may hold::

    cable = "cardinal"            # built-in name, or a path to a cable TOML (relative to the case)
    # or an inline [cable] table with name, [cable.core] and [[cable.layer]]

    [mesh]
    length = 1.0                  # m, free length of the strand
    h_max = 4e-3                  # m, largest element (arc length)

Unknown keys are errors, reported with the file and the key before any computing starts.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from pathlib import Path

from .cable import Cable, CableError, cable_from_dict, cardinal, load_cable

__all__ = ["Case", "MeshSettings", "load_case", "CaseError"]

BUILTIN_CABLES = {"cardinal": cardinal}


class CaseError(ValueError):
    """A case file that cannot be used; the message names the file and the setting."""


@dataclass(frozen=True)
class MeshSettings:
    length: float = 1.0  # m
    h_max: float = 4e-3  # m


@dataclass(frozen=True)
class Case:
    cable: Cable
    mesh: MeshSettings
    source: str = "built-in default"


def _positive(table: dict, key: str, where: str, default: float) -> float:
    v = table.get(key, default)
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not v > 0:
        raise CaseError(f"{where}.{key} = {v!r}: expected a positive number")
    return float(v)


def case_from_dict(data: dict, base: Path | None = None, source: str = "case") -> Case:
    unknown = sorted(set(data) - {"cable", "mesh"})
    if unknown:
        raise CaseError(f"{source}: unknown setting(s) {unknown}; allowed: ['cable', 'mesh']")
    spec = data.get("cable", "cardinal")
    try:
        if isinstance(spec, str):
            if spec.lower() in BUILTIN_CABLES:
                cable = BUILTIN_CABLES[spec.lower()]()
            else:
                cable = load_cable((base or Path.cwd()) / spec)
        elif isinstance(spec, dict):
            cable = cable_from_dict(spec)
        else:
            raise CaseError(f"{source}: 'cable' must be a name, a file or a table")
    except CableError as e:
        raise CaseError(f"{source}: cable: {e}") from None
    mesh = data.get("mesh", {})
    if not isinstance(mesh, dict):
        raise CaseError(f"{source}: [mesh] must be a table")
    unknown = sorted(set(mesh) - {"length", "h_max"})
    if unknown:
        raise CaseError(
            f"{source}: unknown setting(s) in [mesh]: {unknown}; allowed: ['h_max', 'length']"
        )
    settings = MeshSettings(
        _positive(mesh, "length", "mesh", MeshSettings.length),
        _positive(mesh, "h_max", "mesh", MeshSettings.h_max),
    )
    return Case(cable, settings, source)


def load_case(path: str | Path | None = None) -> Case:
    """Read a case file; ``None`` gives the default case (Cardinal, 1 m, h_max = 4 mm)."""
    if path is None:
        return case_from_dict({})
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text())
    except FileNotFoundError:
        raise CaseError(f"{path}: no such case file") from None
    except tomllib.TOMLDecodeError as e:
        raise CaseError(f"{path}: not valid TOML ({e})") from None
    if "core" in data and "layer" in data:  # a bare cable description is a case too
        data = {"cable": data}
    return case_from_dict(data, path.parent, str(path))
