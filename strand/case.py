"""Case files (TOML): the cable, its mesh, contact, loads, load steps, solver and outputs.

Every setting has a default; a case file only lists what it changes. The default case is the seed
paper's test (docs/theory.md §4): Cardinal, 1 m, 40 kN, then the saddle cycle 0 → +4.3 → 0 → −4.3 → 0 kN::

    cable = "cardinal"        # built-in name, a cable TOML (relative to the case), or a [cable] table

    [mesh]
    length = 1.0              # m, free length between the end sections
    h_max = 4e-3              # m, largest element (arc length)

    [contact]
    normal = "auto"           # auto (director with friction, frozen without) | neighbour | director | frozen
    compliance = "hertz"      # hertz (Hertz normal, Mindlin stick: from the wires) | penalty (seed paper)
    k_point = 5e7             # N/m, penalty only: stiffness per crossing
    k_line = 5e9              # N/m², penalty only: core | layer-1 stiffness per metre of wire
    g_lim = 5e-6              # m, penalty only: elastic slip at which friction reaches μP
    friction = true           # Coulomb coefficients of the cable; false: frictionless
    model = "small"           # small sliding (pairs fixed at t = 0) | large (re-projected: the baseline)
    reach = 1e-3              # m, large sliding: sliding room reserved either side of each pair

    [load]
    kind = "saddle"           # saddle: midspan saddle load (the seed paper's test)
                              # bending: uniform bending by end rotations (the section's M–κ)
    tension = 40e3            # N, end force, held during bending
    lateral = 4.3e3           # N, saddle load amplitude
    curvature = 0.5           # 1/m, bending: nominal curvature amplitude
    cycle = [1.0, 0.0, -1.0, 0.0]   # targets after tensioning, in units of lateral or curvature
                                    # ([0.0]: the tension alone)
    saddle_length = 0.02      # m, axial length of the saddle at midspan
    zone = 0.4                # m, bending: central zone where curvature is measured
    direction = [1.0, 0.0, 0.0]     # direction of a positive lateral load / stretched fibre
    sweep = []                # amplitudes of lateral (or curvature) to run, each from the same
                              # tensioned state, into <folder>/<parameter>_<amplitude>/, with
                              # sweep.csv beside them; [] runs lateral (curvature) alone

    [steps]
    tension = 1e3             # N, first tension increment (grows ×growth after easy steps);
                              # the first step closes every contact pair without friction, so
                              # its size sets the wire forces' load-step error (README)
    lateral = 250.0           # N, first lateral increment of each leg of the cycle
    lateral_max = 400.0       # N, largest lateral increment
    curvature = 0.005         # 1/m, bending: first curvature increment of each leg
    curvature_max = 0.05      # 1/m, bending: largest curvature increment
    growth = 1.5
    cuts = 6                  # halvings allowed before a step is declared failed
    max_iterations = 12       # Newton iterations per attempt
    stall = true              # cut an attempt whose residual has not halved in two iterations
                              # (from the 4th on): it would not converge (false: run to the limit)
    line_search = "cp"        # Newton's line search: PETSc's cp (critical point: one secant
                              # step along each Newton direction), or basic (full steps), bt, l2
    tolerance = 1e-2          # N, absolute residual tolerance (2.5e-7 of the tension)
    balance = 1e-4            # or converged when no node is out of balance by more than this
                              # fraction of the mean wire tension T/n (66 mN here), nor by that
                              # force × the largest wire diameter in moment; 0: off

    [output]
    folder = "results/cardinal"    # default for a case file: results/<file name without .toml>
    fields = true             # field time series: XDMF (+ HDF5) for ParaView and meshio
    vtx = true                # with fields: also VTX (ADIOS2 .bp; as large again, ~250 MB here)
    plots = true              # PNG figures at the end
    checkpoint = true         # checkpoint.h5: the last converged state (strand run --restart),
                              # and tensioned.h5: the state before the cycle (3.4 MB each here)

    [fatigue]
    outputs = true            # contact pair and wire section histories, and the fatigue report
    sn_curve = "cigre-sbl-multilayer"   # or "cigre-sbl-single-layer", or "custom" with
    sn_A = 450.0              #   σ_a = sn_A N^sn_b (MPa) up to sn_knee cycles,
    sn_b = -0.2
    sn_knee = 2e7
    sn_A2 = 263.0             #   sn_A2 N^sn_b2 beyond
    sn_b2 = -0.17
    sn_layers = []            # layers (0 = core) the curve applies to; [] = those with E < 100 GPa
    surface_points = 16       # points around each wire's circumference (ranges within 2 %)
    clamp_distance = 0.089    # m, Poffenberger–Swart's distance from the clamp (3.5 in)

Unknown keys and bad values are errors naming the file and the key, raised before any computing.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field, fields, replace
from pathlib import Path

from .cable import Cable, CableError, cable_from_dict, cardinal, load_cable
from .contact_settings import ContactSettings

__all__ = [
    "Case",
    "CaseError",
    "MeshSettings",
    "LoadSettings",
    "StepSettings",
    "OutputSettings",
    "FatigueSettings",
    "load_case",
    "case_from_dict",
    "parse_settings",
]

BUILTIN_CABLES = {"cardinal": cardinal}


class CaseError(ValueError):
    """A case file that cannot be used; the message names the file and the setting."""


@dataclass(frozen=True)
class MeshSettings:
    length: float = 1.0  # m
    h_max: float = 4e-3  # m


LOAD_KINDS = ("saddle", "bending")


@dataclass(frozen=True)
class LoadSettings:
    kind: str = "saddle"
    tension: float = 40e3  # N
    lateral: float = 4.3e3  # N
    curvature: float = 0.5  # 1/m
    cycle: tuple[float, ...] = (1.0, 0.0, -1.0, 0.0)
    saddle_length: float = 0.02  # m
    zone: float = 0.4  # m
    direction: tuple[float, float, float] = (1.0, 0.0, 0.0)
    sweep: tuple[float, ...] = ()  # amplitudes (N or 1/m), each cycled from one tensioned state


@dataclass(frozen=True)
class StepSettings:
    tension: float = 1e3  # N
    lateral: float = 250.0  # N
    lateral_max: float = 400.0  # N
    curvature: float = 0.005  # 1/m
    curvature_max: float = 0.05  # 1/m
    growth: float = 1.5
    cuts: int = 6
    max_iterations: int = 12
    stall: bool = True  # stop stagnating Newton attempts early (NewtonOptions.stall_after)
    line_search: str = "cp"  # NewtonOptions.linesearch (docs/theory.md §6)
    tolerance: float = 1e-2  # N
    balance: float = 1e-4  # fraction of the mean wire tension (NewtonOptions.force_tol)


@dataclass(frozen=True)
class OutputSettings:
    folder: str = "results/cardinal"
    fields: bool = True
    vtx: bool = True
    plots: bool = True
    checkpoint: bool = True  # checkpoint.h5 (last converged state) and tensioned.h5


@dataclass(frozen=True)
class FatigueSettings:
    outputs: bool = True  # contact_pairs.h5, wire_sections.h5 and the fatigue report
    sn_curve: str = "cigre-sbl-multilayer"  # a built-in curve (fatigue.SN_CURVES) or "custom"
    sn_A: float = 450.0  # MPa, custom: σ_a = A N^b up to the knee
    sn_b: float = -0.2
    sn_knee: float = 2e7  # cycles
    sn_A2: float = 263.0  # MPa, custom: σ_a = A2 N^b2 beyond the knee
    sn_b2: float = -0.17
    sn_layers: tuple[float, ...] = ()  # layers the curve applies to; () = those with E < 100 GPa
    surface_points: int = 16  # points around each wire's circumference (ranges within 2 %)
    clamp_distance: float = 0.089  # m, Poffenberger–Swart's measuring distance (3.5 in)

    def curve(self):
        """The S–N curve these settings name (``strand.fatigue.SNCurve``)."""
        from .fatigue.sn import SN_CURVES, SNCurve

        if self.sn_curve == "custom":
            return SNCurve("custom (case file)", self.sn_A, self.sn_b, self.sn_knee, self.sn_A2,
                           self.sn_b2, "the case file")  # fmt: skip
        return SN_CURVES[self.sn_curve]

    def layers(self, cable: Cable) -> list[int]:
        """The layers (0 = core) whose wires the S–N curve applies to."""
        if self.sn_layers:
            return [int(i) for i in self.sn_layers]
        return [i for i, lay in enumerate(cable.layers) if lay.wire.E < 100e9]


@dataclass(frozen=True)
class Case:
    cable: Cable
    mesh: MeshSettings = field(default_factory=MeshSettings)
    contact: ContactSettings = field(default_factory=ContactSettings)
    load: LoadSettings = field(default_factory=LoadSettings)
    steps: StepSettings = field(default_factory=StepSettings)
    output: OutputSettings = field(default_factory=OutputSettings)
    fatigue: FatigueSettings = field(default_factory=FatigueSettings)
    source: str = "built-in default"


SECTIONS = {
    "mesh": MeshSettings,
    "contact": ContactSettings,
    "load": LoadSettings,
    "steps": StepSettings,
    "output": OutputSettings,
    "fatigue": FatigueSettings,
}

#: settings that may be zero or negative (all other numbers must be positive)
_SIGNED = {("load", "lateral"), ("load", "curvature"), ("fatigue", "sn_b"), ("fatigue", "sn_b2")}
#: settings for which 0 means "off" (they must not be negative)
_ZERO_IS_OFF = {("steps", "balance")}
#: PETSc's line searches for Newton (``[steps] line_search``)
LINE_SEARCHES = ("cp", "basic", "bt", "l2")


def _value(section: str, key: str, value, default):
    where = f"[{section}] {key} = {value!r}"
    if isinstance(default, bool):
        if not isinstance(value, bool):
            raise CaseError(f"{where}: expected true or false")
        return value
    if isinstance(default, int | float):
        if (
            isinstance(value, bool)
            or not isinstance(value, int | float)
            or not math.isfinite(value)
        ):
            raise CaseError(f"{where}: expected a number")
        if isinstance(default, int) and not float(value).is_integer():
            raise CaseError(f"{where}: expected a whole number")
        if (section, key) == ("load", "tension") and not value > 0:
            raise CaseError(
                f"{where}: expected a positive tension; a compressed strand is outside the "
                "model (its wires buckle and its contact pairs open)"
            )
        if (section, key) in _ZERO_IS_OFF:
            if value < 0:
                raise CaseError(f"{where}: expected a positive number, or 0 for off")
        elif (section, key) not in _SIGNED and not value > 0:
            raise CaseError(f"{where}: expected a positive number")
        return type(default)(value)
    if isinstance(default, tuple):
        if not isinstance(value, list) or not all(
            isinstance(v, int | float) and not isinstance(v, bool) for v in value
        ):
            raise CaseError(f"{where}: expected a list of numbers")
        if key == "direction" and (len(value) != 3 or value[2] != 0 or value[:2] == [0, 0]):
            raise CaseError(f"{where}: expected [x, y, 0], a direction across the strand axis")
        if key == "cycle" and not value:
            raise CaseError(f"{where}: expected at least one lateral target")
        if key == "sweep" and not all(v > 0 for v in value):
            raise CaseError(f"{where}: expected positive amplitudes (the cycle gives the signs)")
        if key == "sweep" and len(set(value)) != len(value):
            raise CaseError(f"{where}: an amplitude is listed twice")
        return tuple(float(v) for v in value)
    if isinstance(default, str):
        if not isinstance(value, str):
            raise CaseError(f"{where}: expected a string")
        return value
    raise AssertionError(f"no rule for {section}.{key}")


def _section(name: str, table, source: str):
    cls = SECTIONS[name]
    if not isinstance(table, dict):
        raise CaseError(f"{source}: [{name}] must be a table")
    defaults = cls()
    known = [f.name for f in fields(cls)]
    unknown = sorted(set(table) - set(known))
    if unknown:
        raise CaseError(
            f"{source}: unknown setting(s) in [{name}]: {unknown}; allowed: {sorted(known)}"
        )
    values = {}
    for key, value in table.items():
        default = getattr(defaults, key)
        if name == "contact" and key == "normal":
            default = ""
        try:
            values[key] = _value(name, key, value, default)
        except CaseError as e:
            raise CaseError(f"{source}: {e}") from None
    try:
        return replace(defaults, **values) if name != "contact" else cls(**values)
    except CableError as e:
        raise CaseError(f"{source}: [{name}] {e}") from None


def case_from_dict(data: dict, base: Path | None = None, source: str = "case") -> Case:
    allowed = ["cable", *SECTIONS]
    unknown = sorted(set(data) - set(allowed))
    if unknown:
        raise CaseError(f"{source}: unknown setting(s) {unknown}; allowed: {allowed}")
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
    sections = {name: _section(name, data.get(name, {}), source) for name in SECTIONS}
    steps = sections["steps"]
    if steps.line_search not in LINE_SEARCHES:
        raise CaseError(
            f"{source}: [steps] line_search = {steps.line_search!r}: expected one of "
            f"{list(LINE_SEARCHES)}"
        )
    if steps.lateral > steps.lateral_max:
        raise CaseError(f"{source}: [steps] lateral = {steps.lateral} exceeds lateral_max")
    if steps.curvature > steps.curvature_max:
        raise CaseError(f"{source}: [steps] curvature = {steps.curvature} exceeds curvature_max")
    load, mesh = sections["load"], sections["mesh"]
    length = mesh.length
    if mesh.h_max >= length:
        raise CaseError(
            f"{source}: [mesh] h_max = {mesh.h_max} m must be shorter than the span "
            f"[mesh] length = {length} m"
        )
    if load.kind not in LOAD_KINDS:
        raise CaseError(
            f"{source}: [load] kind = {load.kind!r} is unknown; choose {' or '.join(LOAD_KINDS)}"
        )
    if load.kind == "saddle" and not mesh.h_max <= load.saddle_length < length:
        raise CaseError(
            f"{source}: [load] saddle_length = {load.saddle_length} m must be shorter than the "
            f"span ([mesh] length = {length} m) and at least [mesh] h_max = {mesh.h_max} m (so "
            "that every outer wire has a node under the saddle)"
        )
    if load.kind == "bending" and load.zone >= length:
        raise CaseError(
            f"{source}: [load] zone = {load.zone} m must be shorter than [mesh] length = {length} m"
        )
    if load.sweep and not any(load.cycle):
        raise CaseError(
            f"{source}: [load] sweep = {list(load.sweep)} needs a cycle with a target other "
            f"than 0 (cycle = {list(load.cycle)} stays at zero load)"
        )
    fatigue = sections["fatigue"]
    from .fatigue.sn import SN_CURVES

    if fatigue.sn_curve not in (*SN_CURVES, "custom"):
        raise CaseError(
            f"{source}: [fatigue] sn_curve = {fatigue.sn_curve!r} is unknown; choose one of "
            f'{sorted(SN_CURVES)} or "custom" (with sn_A, sn_b, sn_knee, sn_A2, sn_b2)'
        )
    try:
        fatigue.curve()
    except ValueError as e:
        raise CaseError(f"{source}: [fatigue] {e}") from None
    bad = [
        i for i in fatigue.sn_layers if not float(i).is_integer() or not 0 <= i < len(cable.layers)
    ]
    if bad:
        raise CaseError(
            f"{source}: [fatigue] sn_layers = {list(fatigue.sn_layers)}: layers are numbered 0 "
            f"(core) to {len(cable.layers) - 1}"
        )
    return Case(cable, **sections, source=source)


def parse_settings(items: list[str]) -> dict:
    """``["section.key=value", ...]`` (the command line's ``--set``) as a nested dict of case
    settings; values are read as TOML (``2e-3``, ``true``, ``[1.0, 0.0]``), or else as strings."""
    out: dict = {}
    for item in items:
        name, eq, text = item.partition("=")
        section, dot, key = name.strip().rpartition(".")
        if not eq or not key or (dot and not section) or "." in section:
            raise CaseError(f"--set {item!r}: expected section.key=value, e.g. mesh.h_max=2e-3")
        try:
            value = tomllib.loads(f"v = {text.strip()}")["v"]
        except tomllib.TOMLDecodeError:
            value = text.strip()
        if section:
            out.setdefault(section, {})[key] = value
        else:
            out[key] = value
    return out


def _merge(data: dict, overrides: dict) -> dict:
    merged = dict(data)
    for k, v in overrides.items():
        if isinstance(v, dict) and isinstance(merged.get(k), dict):
            merged[k] = {**merged[k], **v}
        else:
            merged[k] = v
    return merged


def load_case(path: str | Path | None = None, settings: list[str] = ()) -> Case:
    """Read a case file; ``None`` gives the default case (the seed paper's Cardinal test).
    ``settings`` (``"section.key=value"``, from ``--set``) override the file's."""
    overrides = parse_settings(list(settings))
    if path is None:
        source = "built-in default" + (" with --set" if settings else "")
        return case_from_dict(overrides, source=source)
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text())
    except FileNotFoundError:
        raise CaseError(f"{path}: no such case file") from None
    except IsADirectoryError:
        raise CaseError(f"{path}: is a folder; give a case file (TOML)") from None
    except UnicodeDecodeError:
        raise CaseError(f"{path}: not a text file; give a case file (TOML)") from None
    except OSError as e:
        raise CaseError(f"{path}: cannot be read ({e.strerror})") from None
    except tomllib.TOMLDecodeError as e:
        raise CaseError(f"{path}: not valid TOML ({e})") from None
    if "core" in data and "layer" in data:  # a bare cable description is a case too
        data = {"cable": data}
    data = _merge(data, overrides)
    output = data.get("output", {})
    if isinstance(output, dict) and "folder" not in output:  # results/<case name> by default
        data = {**data, "output": {**output, "folder": f"results/{path.stem}"}}
    return case_from_dict(data, path.parent, str(path))
