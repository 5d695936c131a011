"""Case files (TOML): the cable, its mesh, contact, loads, load steps, solver and outputs.

Every setting has a default; a case file only lists what it changes. The default case is the seed
paper's test (docs/theory.md §4): Cardinal, 1 m, 40 kN, then the saddle cycle 0 → +4.3 → 0 → −4.3 → 0 kN::

    cable = "cardinal"        # built-in (cardinal, judge120), a cable TOML (relative to the case), or a [cable] table

    [mesh]
    length = 1.0              # m, free length between the end sections
    h_max = 4e-3              # m, largest element (arc length), from the thinnest wire's
                              #   diameter / 10 to the shortest lay length / 8

    [contact]
    normal = "auto"           # auto (director with friction, frozen without) | neighbour | director | frozen
    compliance = "hertz"      # hertz (Hertz normal, Mindlin stick: from the wires) | penalty (seed paper)
    k_point = 5e7             # N/m, penalty only: stiffness per crossing
    k_line = 5e9              # N/m², penalty only: core | layer-1 stiffness per metre of wire
    g_lim = 5e-6              # m, penalty only: elastic slip at which friction reaches μP
    friction = true           # Coulomb coefficients of the cable; false: frictionless
    model = "small"           # small sliding (pairs fixed at t = 0) | large (re-projected: the baseline)
    reach = 1e-3              # m, large sliding: sliding room reserved either side of each pair
    same_layer = "auto"       # contact between neighbours of a layer: auto (packed) | packed
                              #   (touching, the spare gap in one place) | nominal (spread
                              #   evenly) | random (split at random from gap_seed) | off
    gap_seed = 0              # the seed of random gaps
    first_layer = "on_core"   # a first layer whose helices overlap (a closed ring): on_core
                              #   (on the core too) | ring (a vault off the core)
    same_layer_stencil = "segment"  # a same-layer pair ties node a to its facing segment, or
                              #   to the neighbour's nearest node (node: a cheaper LU, results
                              #   within 1-20x the mesh error: docs/benchmarks.md), or (facing,
                              #   small sliding) to the node meshed exactly where it faces it
    slip = "surface"          # friction's slip: surface points | centreline (the seed paper's)

    [load]
    kind = "saddle"           # saddle: midspan saddle load (the seed paper's test)
                              # bending: uniform bending by end rotations (the section's M–κ)
                              # tension_cycle: the end force cycled by tension_swing (N), with
                              #   a saddle load fixed_lateral (N) held at midspan
                              # fairlead: bent to bend_curvature (1/m), bend_radius (m) or
                              #   bend_angle (deg) over bend_length (m), held while the tension
                              #   cycles by tension_swing (N), or (cycled = "curvature") the
                              #   curvature cycles about it by curvature_swing (1/m)
    tension = 40e3            # N, end force, held during bending
    lateral = 4.3e3           # N, saddle load amplitude
    curvature = 0.5           # 1/m, bending: nominal curvature amplitude
    cycle = [1.0, 0.0, -1.0, 0.0]   # targets after tensioning, in units of lateral or curvature
                                    # ([0.0]: the tension alone)
    saddle_length = 0.02      # m, axial length of the saddle at midspan
    control = "force"         # saddle: force (lateral) | displacement: the saddle load that
                              #   gives deflection (m, midspan) or yb (m, Y_b at clamp_distance)
    zone = 0.4                # m, bending, fairlead: central zone where curvature is measured
    direction = [1.0, 0.0, 0.0]     # direction of a positive lateral load / stretched fibre
    sweep = []                # amplitudes of lateral (or curvature) to run, each from the same
                              # tensioned state, into <folder>/<parameter>_<amplitude>/, with
                              # sweep.csv beside them; [] runs lateral (curvature) alone

    [steps]
    tension = 1e3             # N, first tension increment (grows ×growth after easy steps);
                              # the first step closes every contact pair without friction, so
                              # its size sets the wire forces' load-step error (benchmarks/window.py)
    lateral = 125.0           # N, first lateral increment of each leg of the cycle
    lateral_max = 200.0       # N, largest lateral increment (sets the load-step error)
    curvature = 0.005         # 1/m, bending: first curvature increment of each leg
    curvature_max = 0.05      # 1/m, bending: largest curvature increment
    growth = 1.5
    control = "growth"        # growth: ×growth after easy solves | error: from the predictor's miss
    error_tolerance = 1e-6    # m, error control: the predictor's miss aimed at by each step
    retry = true              # retry a failed step once with the other predictor, then halve
    predictor = true          # start each Newton solve of a ramp (tension, legs) from the secant
                              # predictor of its last step; false: from the last converged state
    iteration = "newton"      # newton: an LU per iteration | reuse_lu: GMRES on each Jacobian with
                              #   an earlier one's LU | lbfgs: L-BFGS on a solve's first LU;
                              #   either falls back to Newton when it fails (docs/theory.md §6)
    stabilise = 1e4           # N/m per pair: a step whose cuts are exhausted is tried again
                              # with springs on every contact pair's slip (near-mechanisms:
                              # wires rolling round the layer below), released when it
                              # converges; their energy over the strain energy is reported;
                              # 0: off
    cuts = 6                  # halvings allowed before a step is declared failed
    max_iterations = 12       # Newton iterations per attempt
    stall = true              # cut an attempt whose residual has not halved in two iterations
                              # (from the 4th on): it would not converge (false: run to the limit)
    line_search = "cp"        # Newton's line search: PETSc's cp (critical point: one secant
                              # step along each Newton direction), or basic (full steps), bt, l2
    tolerance = 1e-2          # N, absolute residual tolerance (2.5e-7 of the tension)
    balance = 1e-4            # also converged when no node is out of balance by more than this
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
    steel_sn_curve = "en1992-prestressing-steel"  # the other steel wires' (E ≥ 100 GPa) curve,
                              #   or "en1992-steel-duct" (fretting), "user", or "none": not assessed
    user_sn_m1 = 0.0          # a user's own curve (sn_curve or steel_sn_curve = "user"),
                              #   N = a1 Δσ^-m1 (Δσ the range in MPa): its slope to the knee
    user_sn_m2 = 0.0          # its slope beyond the knee, continuous there; 0: m1 throughout
    user_sn_log_a = 0.0       # its intercept log10 a1 (Δσ in MPa); 0: user_sn_range instead
    user_sn_range = 0.0       # Pa, or its intercept as the range at user_sn_cycles
    user_sn_cycles = 2e6      # cycles at which user_sn_range is given
    user_sn_knee = 1e7        # cycles where the slope turns from m1 to m2
    user_sn_given = "characteristic"  # the user curve as given: characteristic | mean
    user_sn_use = "characteristic"    # the user curve assessed with: characteristic | mean
    user_sn_sd = 0.0          # standard deviation of log10 N: the characteristic curve lies two
                              #   of them below the mean (needed where use and given differ)
    user_sn_mean = 0.0        # Pa, the mean stress of the user curve's tests (0: fully reversed)
    mean_stress = "none"      # wire-level mean-stress correction: none | goodman | gerber | swt
                              #   (with the wires' tensile_strength); none: the built-in curves
                              #   come from tensioned tests (docs/fatigue.md)
    design_fatigue_factor = 1.0   # DFF: every damage, wire-level and T–N, is the Miner sum × DFF
                              #   (lives ÷ DFF); 1: none; the standards' values: docs/fatigue.md
    surface_points = 16       # points around each wire's circumference (ranges within 2 %)
    clamp_distance = 0.089    # m, Poffenberger–Swart's distance from the clamp (3.5 in)
    end_zone = 0.0            # m, clamp zone at each end, reported apart from the free span;
                              #   0: half the longest lay length (how far the ends' lock reaches)
    stuck_slip = 1e-9         # m, pairs that slide less than this stayed stuck throughout
    breaking_strength = 0.0   # N, minimum breaking strength for API RP 2SK's T–N; 0: not given
    spectrum = []             # [[amplitude, cycles], ...]: the cycles in a period (a year, the
                              #   design life) at each amplitude of lateral (N), curvature (1/m)
                              #   or tension_swing (N); runs the amplitudes as the sweep and
                              #   writes Miner's sum per wire and pair: spectrum.csv, spectrum.txt;
                              #   or a table [fatigue.spectrum] with classes = [[...], ...], as
                              #   strand spectrum prints it (beside [fatigue], no second one)

Unknown keys and bad values are errors naming the file and the key, raised before any computing:
this module checks each value alone, ``strand.app.checks`` the settings against one another. The
command line's ``--set`` overrides are read by ``strand.app.case_overrides``.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import fields, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..cable.description import (
    Cable,
    CableError,
    cable_from_dict,
    cardinal,
    judge120,
    load_cable,
)
from ..cable.input_file import read_text
from .case_overrides import merge_settings, parse_settings
from .case_toml import cable_table
from .errors import CaseError
from .settings import KIND_SECTIONS, SECTIONS, Case, unit_of

if TYPE_CHECKING:
    from .kinds import SetupKind

#: ``Case`` (``strand.app.settings``) and ``CaseError`` (``strand.app.errors``) are importable
#: from here too
__all__ = ["load_case", "case_from_dict", "check_loads_given"]

BUILTIN_CABLES = {"cardinal": cardinal, "judge120": judge120}


#: settings that may be zero or negative (all other numbers must be positive; a set-up kind
#: names its own: ``SetupKind.signed``)
_SIGNED = {("fatigue", "sn_b"), ("fatigue", "sn_b2")}
#: settings for which 0 means "off" (they must not be negative)
_ZERO_IS_OFF = {
    ("steps", "balance"),
    ("steps", "stabilise"),
    ("fatigue", "end_zone"),
    ("fatigue", "breaking_strength"),
    *(
        ("fatigue", f"user_sn_{key}")
        for key in ("m1", "m2", "log_a", "range", "sd", "mean")  # 0: not given
    ),
}
#: whole numbers from 0 up
_COUNTS = {("contact", "gap_seed")}


def _boolean(where: str, value) -> bool:
    if not isinstance(value, bool):
        raise CaseError(f"{where}: expected true or false")
    return value


def _number(where: str, value, default, signed: bool, zero_is_off: bool):
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise CaseError(f"{where}: expected a number")
    if isinstance(default, int) and not float(value).is_integer():
        raise CaseError(f"{where}: expected a whole number")
    if zero_is_off:
        if value < 0:
            raise CaseError(f"{where}: expected a positive number, or 0 for off")
    elif not signed and not value > 0:
        raise CaseError(f"{where}: expected a positive number")
    return type(default)(value)


def _numbers(where: str, key: str, value) -> tuple[float, ...]:
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


def _spectrum(value) -> tuple[tuple[float, float], ...]:
    """``[fatigue] spectrum``: the list ``[[amplitude, cycles], ...]``, or the table
    ``[fatigue.spectrum]`` with that list as ``classes`` (``strand spectrum``'s block)."""
    from ..fatigue.spectrum import spectrum_classes

    if isinstance(value, dict):
        if set(value) != {"classes"}:
            raise CaseError(
                f"[fatigue.spectrum]: expected the one key classes = [[amplitude, cycles], ...]; "
                f"got {sorted(value)}"
            )
        value = value["classes"]
    try:
        return spectrum_classes(value)
    except ValueError as e:
        raise CaseError(f"[fatigue] spectrum: {e}") from None


def _value(section: str, key: str, value, default, signed: bool = False):
    """``value`` of ``[section] key`` checked against the type of its ``default``."""
    unit = unit_of(section, key) if isinstance(value, int | float) else ""
    where = f"[{section}] {key} = {value!r}" + (f" {unit}" if unit else "")
    if isinstance(default, bool):
        return _boolean(where, value)
    if isinstance(default, int | float):
        tension = (section, key) == ("load", "tension")
        signed = signed or tension or (section, key) in _SIGNED
        if (section, key) in _COUNTS:
            if not (isinstance(value, int) and not isinstance(value, bool) and value >= 0):
                raise CaseError(f"{where}: expected a whole number ≥ 0")
            return value
        number = _number(where, value, default, signed, (section, key) in _ZERO_IS_OFF)
        if tension and not number > 0:
            raise CaseError(
                f"{where}: expected a positive tension; a compressed strand is outside the "
                "model (its wires buckle and its contact pairs open)"
            )
        return number
    if (section, key) == ("fatigue", "spectrum"):
        return _spectrum(value)
    if isinstance(default, tuple):
        return _numbers(where, key, value)
    if isinstance(default, str):
        if not isinstance(value, str):
            raise CaseError(f"{where}: expected a string")
        return value
    raise AssertionError(f"no rule for {section}.{key}")


def _keys(name: str) -> dict[str, tuple[Any, bool]]:
    """The settings of section ``name`` (with those of every registered set-up kind): each
    key's default and whether it may be zero or negative."""
    defaults = SECTIONS[name]()
    keys = {f.name: (getattr(defaults, f.name), False) for f in fields(defaults)}
    if name in KIND_SECTIONS:
        from . import kinds

        del keys["by_kind"]
        for kind in kinds.registered():
            own = getattr(kind, KIND_SECTIONS[name])()
            for f in fields(own):
                keys[f.name] = (getattr(own, f.name), name == "load" and f.name in kind.signed)
    return keys


def _section(name: str, table, source: str):
    if not isinstance(table, dict):
        raise CaseError(f"{source}: [{name}] must be a table")
    keys = _keys(name)
    unknown = sorted(set(table) - set(keys))
    if unknown:
        raise CaseError(
            f"{source}: unknown setting(s) in [{name}]: {unknown}; allowed: {sorted(keys)}"
        )
    values = {}
    for key, value in table.items():
        default, signed = keys[key]
        if name == "contact" and key == "normal":
            default = ""
        try:
            values[key] = _value(name, key, value, default, signed)
        except CaseError as e:
            raise CaseError(f"{source}: {e}") from None
    cls = SECTIONS[name]
    try:
        if name == "contact":  # its defaults depend on what is given (``ContactSettings``)
            return cls(**values)
        return cls().with_values(**values) if name in KIND_SECTIONS else cls(**values)
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
            if spec.lower() in BUILTIN_CABLES:
                return BUILTIN_CABLES[spec.lower()]()
            path = (base or Path.cwd()) / spec
            if not path.exists():
                raise CaseError(
                    f"{source}: cable = {spec!r} is neither a built-in cable nor a file ({path}); "
                    f"built-in cables: {', '.join(BUILTIN_CABLES)}"
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
