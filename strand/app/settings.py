"""The settings of a case: its sections (mesh, load, load steps, outputs, fatigue) and the
``Case`` that holds them with the cable and its contact settings (``strand.app.case`` reads them
from a case file).

Every setting has a default. ``[load]`` and ``[steps]`` hold the settings every set-up kind shares
and, in ``by_kind``, each registered kind's own (``strand.app.kinds``), all read flat as the case
file writes them (``case.load.zone``). The settings read the kinds from their registry
(``strand.app.kind_registry``) and import none: the kinds are built on the settings, and the
built-in ones are registered by importing ``strand.app.kinds``, which reading a case does. ``strand.app.case`` checks a case file's values against
these. Units: SI, in the comments.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, fields, replace
from functools import partial
from typing import Any, ClassVar

from ..cable.description import Cable
from ..model.contact_settings import ContactSettings
from .kind_registry import registered

__all__ = [
    "Case",
    "MeshSettings",
    "LoadSettings",
    "StepSettings",
    "OutputSettings",
    "FatigueSettings",
    "WithKinds",
    "KIND_SECTIONS",
    "unit_of",
]


@dataclass(frozen=True)
class MeshSettings:
    length: float = 1.0  # m
    h_max: float = 4e-3  # m, largest element: thinnest wire diameter / 10 to shortest lay / 8

    #: the SI unit of every number ("" for a ratio or a count): error messages give it
    UNITS: ClassVar[dict[str, str]] = {"length": "m", "h_max": "m"}


#: the sections whose keys include the set-up kinds' own, and each kind's attribute for them
KIND_SECTIONS = {"load": "load_settings", "steps": "step_settings"}


def _kind_defaults(section: str) -> dict[str, Any]:
    """Every registered set-up kind's own settings of ``section`` at their defaults, by kind
    (the built-in kinds are registered once ``strand.app.kinds`` is imported, as reading a case
    does)."""
    return {kind.name: getattr(kind, KIND_SECTIONS[section])() for kind in registered()}


class WithKinds:
    """A section holding the settings every set-up kind shares (its fields) and, in ``by_kind``,
    each registered kind's own (``SetupKind.load_settings``, ``step_settings``); all of them read
    flat, as the case file writes them (``load.zone``)."""

    by_kind: Mapping[str, Any]

    def __getattr__(self, name: str) -> Any:
        for own in self.__dict__.get("by_kind", {}).values():
            if name in own.__dataclass_fields__:
                return getattr(own, name)
        raise AttributeError(f"{type(self).__name__} has no setting {name!r}")

    def items(self) -> list[tuple[str, Any]]:
        """Every setting as (key, value): the common ones, then each kind's own."""
        common = [(f.name, getattr(self, f.name)) for f in fields(self) if f.name != "by_kind"]
        own = [(f.name, getattr(s, f.name)) for s in self.by_kind.values() for f in fields(s)]
        return common + own

    def with_values(self, **values):
        """A copy with ``values`` (common or kinds' settings) changed."""
        by_kind = {}
        for name, own in self.by_kind.items():
            mine = {k: values.pop(k) for k in list(values) if k in own.__dataclass_fields__}
            by_kind[name] = replace(own, **mine)
        return replace(self, **values, by_kind=by_kind)


@dataclass(frozen=True)
class LoadSettings(WithKinds):
    kind: str = "saddle"  # a registered set-up kind (``strand.app.kinds``)
    tension: float = 40e3  # N
    cycle: tuple[float, ...] = (1.0, 0.0, -1.0, 0.0)
    direction: tuple[float, float, float] = (1.0, 0.0, 0.0)
    sweep: tuple[float, ...] = ()  # amplitudes (N or 1/m), each cycled from one tensioned state
    by_kind: Mapping[str, Any] = field(default_factory=partial(_kind_defaults, "load"), hash=False)

    UNITS: ClassVar[dict[str, str]] = {"tension": "N"}


@dataclass(frozen=True, kw_only=True)
class StepSettings(WithKinds):
    tension: float = 1e3  # N
    growth: float = 1.5  # the next increment over this one after a step of at most 6 iterations
    cuts: int = 6
    max_iterations: int = 12
    stall: bool = True  # stop stagnating Newton attempts early (NewtonOptions.stall_after)
    line_search: str = "cp"  # NewtonOptions.linesearch (docs/theory.md §6)
    tolerance: float = 1e-2  # N
    balance: float = 1e-4  # fraction of the mean wire tension (NewtonOptions.force_tol)
    control: str = "growth"  # "growth" after easy solves, or "error": the predictor's miss
    error_tolerance: float = 1e-6  # m, "error" control: the step's miss aimed at (ErrorControl)
    retry: bool = True  # retry a failed step once with the other predictor before halving
    predictor: bool = True  # start each solve from the secant predictor of the ramp's last step
    iteration: str = "newton"  # NewtonOptions.iteration: "newton", "reuse_lu" or "lbfgs"
    stabilise: float = 1e4  # N/m per pair: contact springs for a step that fails (Stabiliser)
    by_kind: Mapping[str, Any] = field(default_factory=partial(_kind_defaults, "steps"), hash=False)

    UNITS: ClassVar[dict[str, str]] = {
        "tension": "N",
        "growth": "",
        "cuts": "",
        "max_iterations": "",
        "tolerance": "N",
        "balance": "",
        "error_tolerance": "m",
        "stabilise": "N/m",
    }


#: PETSc's line searches for Newton (``[steps] line_search``)
LINE_SEARCHES = ("cp", "basic", "bt", "l2")
#: ``[steps] control``: growth after easy solves, or the predictor-miss controller (``ErrorControl``)
STEP_CONTROLS = ("growth", "error")


@dataclass(frozen=True)
class OutputSettings:
    folder: str = "results/cardinal"
    fields: bool = True
    vtx: bool = True
    plots: bool = True
    checkpoint: bool = True  # checkpoint.h5 (last converged state) and tensioned.h5


@dataclass(frozen=True, kw_only=True)
class FatigueSettings:
    outputs: bool = True  # contact_pairs.h5, wire_sections.h5 and the fatigue report
    sn_curve: str = "cigre-sbl-multilayer"  # a built-in curve (fatigue.SN_CURVES), "custom", "user"
    sn_A: float = 450.0  # MPa, custom: σ_a = A N^b up to the knee
    sn_b: float = -0.2  # custom: the exponent b up to the knee
    sn_knee: float = 2e7  # cycles
    sn_A2: float = 263.0  # MPa, custom: σ_a = A2 N^b2 beyond the knee
    sn_b2: float = -0.17  # custom: the exponent b2 beyond the knee
    sn_layers: tuple[float, ...] = ()  # layers the curve applies to; () = those with E < 100 GPa
    steel_sn_curve: str = "en1992-prestressing-steel"  # steel wires' curve, "user" or "none"
    # a user's own curve (sn_curve or steel_sn_curve "user"): N = a1 Δσ^-m1, Δσ the range in MPa
    user_sn_m1: float = 0.0  # its slope up to the knee (required)
    user_sn_m2: float = 0.0  # its slope beyond the knee; 0: m1 throughout
    user_sn_log_a: float = 0.0  # log10 a1 (Δσ in MPa); 0: the intercept is user_sn_range instead
    user_sn_range: float = 0.0  # Pa, the range Δσ0 at user_sn_cycles (instead of user_sn_log_a)
    user_sn_cycles: float = 2e6  # cycles at which user_sn_range is given
    user_sn_knee: float = 1e7  # cycles where the slope turns from m1 to m2
    user_sn_given: str = "characteristic"  # the curve as given: "characteristic" or "mean"
    user_sn_use: str = "characteristic"  # the one assessed with: "characteristic" or "mean"
    user_sn_sd: float = 0.0  # std. deviation of log10 N (characteristic: 2 below the mean)
    user_sn_mean: float = 0.0  # Pa, the mean stress of the curve's tests (0: fully reversed)
    mean_stress: str = "none"  # wire cycles' mean-stress correction: none, goodman, gerber, swt
    design_fatigue_factor: float = 1.0  # DFF: every damage (wire and T–N) × DFF; 1: none
    surface_points: int = 16  # points around each wire's circumference (ranges within 2 %)
    clamp_distance: float = 0.089  # m, Poffenberger–Swart's measuring distance (3.5 in)
    end_zone: float = 0.0  # m, clamp zone at each end; 0: half the longest lay length
    stuck_slip: float = 1e-9  # m, a pair whose Coulomb slide stays below this stuck throughout
    breaking_strength: float = 0.0  # N, the strand's MBS for API RP 2SK's T–N; 0: not given
    spectrum: tuple[tuple[float, float], ...] = ()  # [[amplitude, cycles], ...]: run as the sweep

    UNITS: ClassVar[dict[str, str]] = {
        "sn_A": "MPa",
        "sn_b": "",
        "sn_knee": "cycles",
        "sn_A2": "MPa",
        "sn_b2": "",
        "user_sn_m1": "",
        "user_sn_m2": "",
        "user_sn_log_a": "",
        "user_sn_range": "Pa",
        "user_sn_cycles": "cycles",
        "user_sn_knee": "cycles",
        "user_sn_sd": "",
        "user_sn_mean": "Pa",
        "design_fatigue_factor": "",
        "surface_points": "",
        "clamp_distance": "m",
        "end_zone": "m",
        "stuck_slip": "m",
        "breaking_strength": "N",
    }

    def user_curve(self):
        """The user's own S–N curve (``user_sn_*``; ``strand.fatigue.sn.user_curve``): the one
        ``user_sn_use`` names, moved from the one given by ``CHARACTERISTIC_SDS`` standard
        deviations ``user_sn_sd`` of log10 N where the two differ."""
        from ..fatigue.sn import CHARACTERISTIC_SDS, user_curve

        sign = {"mean": 1, "characteristic": 0}
        shift = (sign[self.user_sn_use] - sign[self.user_sn_given]) * CHARACTERISTIC_SDS
        point = (self.user_sn_range, self.user_sn_cycles) if self.user_sn_range else None
        intercept = (
            f"Δσ = {1e-6 * self.user_sn_range:g} MPa at {self.user_sn_cycles:.3g} cycles"
            if point
            else f"log10 a1 = {self.user_sn_log_a:g} (Δσ in MPa)"
        )
        beyond = f", m2 = {self.user_sn_m2:g} beyond" if self.user_sn_m2 else ""
        moved = (
            f", moved from the {self.user_sn_given} one given by {abs(shift):g} × "
            f"{self.user_sn_sd:g} in log10 N"
            if shift
            else ""
        )
        name = (
            f"user curve ({self.user_sn_use}): N = a1 Δσ^-{self.user_sn_m1:g}, {intercept}, "
            f"knee {self.user_sn_knee:.3g} cycles{beyond}{moved}"
        )
        return user_curve(
            self.user_sn_m1,
            self.user_sn_knee,
            log_a=self.user_sn_log_a,
            point=point,
            m2=self.user_sn_m2,
            shift=shift * self.user_sn_sd,
            name=name,
        )

    def curve(self):
        """The S–N curve these settings name (``strand.fatigue.SNCurve``)."""
        from ..fatigue.sn import SN_CURVES, SNCurve

        if self.sn_curve == "user":
            return self.user_curve()
        if self.sn_curve == "custom":
            return SNCurve(
                "custom (case file)",
                self.sn_A,
                self.sn_b,
                self.sn_knee,
                self.sn_A2,
                self.sn_b2,
                "the case file",
            )
        return SN_CURVES[self.sn_curve]

    def layers(self, cable: Cable) -> list[int]:
        """The layers (0 = core) whose wires the S–N curve applies to."""
        if self.sn_layers:
            return [int(i) for i in self.sn_layers]
        return [i for i, lay in enumerate(cable.layers) if lay.wire.E < 100e9]

    def curves(self, cable: Cable) -> list:
        """Per layer (0 = core), its wires' S–N curve, or None (not assessed): ``sn_curve`` on
        ``layers``, ``steel_sn_curve`` on the other steel layers (E ≥ 100 GPa)."""
        from ..fatigue.sn import SN_CURVES, wire_material

        mine = self.layers(cable)
        steel = (
            self.user_curve()
            if self.steel_sn_curve == "user"
            else SN_CURVES.get(self.steel_sn_curve)
        )
        return [
            self.curve() if i in mine else steel if wire_material(lay.wire.E) == "steel" else None
            for i, lay in enumerate(cable.layers)
        ]

    def uses_user_curve(self) -> bool:
        """Whether ``sn_curve`` or ``steel_sn_curve`` names the user's own curve."""
        return "user" in (self.sn_curve, self.steel_sn_curve)

    def unknown_strength(self, cable: Cable) -> list[int]:
        """The assessed layers (with a curve) whose wires give no tensile strength."""
        return [
            i
            for i, (lay, curve) in enumerate(zip(cable.layers, self.curves(cable), strict=True))
            if curve is not None and lay.wire.tensile_strength is None
        ]

    def mean_stress_corrections(self, cable: Cable) -> list:
        """Per layer (0 = core), its wires' mean-stress correction
        (``strand.fatigue.meanstress.MeanStress``), or None: no ``mean_stress``, or no curve.
        The user's curve is taken at its tests' mean ``user_sn_mean``, the others at zero."""
        from ..fatigue.meanstress import MeanStress

        curves = self.curves(cable)
        if self.mean_stress == "none":
            return [None] * len(curves)
        user = self.user_curve() if self.uses_user_curve() else None
        return [
            None
            if curve is None
            else MeanStress(
                self.mean_stress,
                lay.wire.tensile_strength,
                self.user_sn_mean if curve == user else 0.0,
            )
            for lay, curve in zip(cable.layers, curves, strict=True)
        ]

    def end_zone_length(self, cable: Cable) -> float:
        """The clamp zone's length at each end (m): ``end_zone``, or how far the end sections'
        lock on the wires reaches, half the longest lay length (``strand.fatigue.zones``)."""
        from ..fatigue.zones import lock_reach

        return self.end_zone if self.end_zone > 0 else lock_reach(cable)


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
    #: the ``[load]`` settings a run needs that the case leaves at their defaults (Cardinal's)
    #: although its cable is not a built-in one (``check_loads_given``)
    unset_loads: tuple[str, ...] = ()


#: the sections of a case file after ``cable``, and their settings classes
SECTIONS = {
    "mesh": MeshSettings,
    "contact": ContactSettings,
    "load": LoadSettings,
    "steps": StepSettings,
    "output": OutputSettings,
    "fatigue": FatigueSettings,
}


def unit_of(section: str, key: str) -> str:
    """The SI unit of the number ``[section] key`` (its settings class's ``UNITS``, or a set-up
    kind's own); "" for a ratio, a count or a setting that is not a number."""
    classes = [SECTIONS[section]]
    if section in KIND_SECTIONS:
        classes += [getattr(kind, KIND_SECTIONS[section]) for kind in registered()]
    for cls in classes:
        units = getattr(cls, "UNITS", {})
        if key in units:
            return units[key]
    return ""
