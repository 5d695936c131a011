"""Bending at a fairlead as a set-up kind (``[load] kind = "fairlead"``): the strand under its
tension, bent to the curvature of a fairlead sheave or a bend stiffener and held there while the
tension cycles, or with the tension held while the curvature cycles: a mooring line where it
leaves the floater.

The set-up is ``strand.setups.fairlead.FairleadTest``: the uniform bending test (ends turned by
±κ L/2, a core strut carrying the tension, so that the section moment is uniform) whose tension is
the mean plus a swing. Its own settings, ``[load]``:

- the curvature κ of the strand's axis, in exactly one way: ``bend_curvature`` (1/m),
  ``bend_radius`` (m, the radius R of the axis over the sheave or in the stiffener: κ = 1/R), or
  ``bend_angle`` (deg) over ``bend_length`` (m): the mean curvature of a line that turns through
  that angle over that length;
- ``cycled``: "tension" (default: tension → κ, held → the end force over ``[load] tension`` +
  ``cycle`` × ``tension_swing``) or "curvature" (tension, held → κ × ``cycle``).

It shares the others' settings where they mean the same: ``[load] tension_swing`` (N) of the
``tension_cycle`` kind, ``zone`` (m, the central measuring zone) of the ``bending`` kind, and
their ``[steps]`` ``tension_swing``, ``tension_swing_max`` (N), ``curvature``, ``curvature_max``
(1/m). Its reference: the wire stresses of the bent strand in full stick and in full slip
(``analytical.bent_wire_stresses``, docs/theory.md §5.7) beside the model's in the zone at the
held curvature; with the tension cycled, the wires' stress change at the largest swing beside the
fibre model's; with the curvature cycled, the uniform bending report (M–κ beside the stick–slip
law) and its figure. Units: m, N, Pa, 1/m; angles in degrees in the settings.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import partial
from pathlib import Path
from typing import ClassVar

import numpy as np
import numpy.typing as npt

from ...analytical import BentWireStresses, bent_wire_stresses
from ...cable.description import Cable
from ...model.post import fibre_model, harmonic_fit
from ...model.programme import LoadProgramme, Stage, cycle_stages
from ..errors import CaseError
from ..settings import Case
from .base import SetupKind, tension_stage, tension_then_cycle
from .bending import BendingReport, bending_figure, bending_lines, uniform_bending_report

__all__ = [
    "Fairlead",
    "FairleadLoad",
    "FairleadReport",
    "LayerStresses",
    "zone_stresses",
    "held_curvature",
    "CURVATURE_INPUTS",
    "CYCLED",
    "CORE_BENDING_SHARE",
]

Array = npt.NDArray[np.float64]

#: the ways to give the curvature (one of them): setting → its unit
CURVATURE_INPUTS = {"bend_curvature": "1/m", "bend_radius": "m", "bend_angle": "deg"}
#: the core's own bending may differ from E κ d/2 at the zone's curvature by this share before the
#: summary warns that the core does not follow the strand's axis (measured: 0.1 % in stick and
#: full slip on a 1+6, a factor 3.9 where the frictionless core snakes)
CORE_BENDING_SHARE = 0.1
#: what the cycle varies → the set-up's load parameter
CYCLED = {"tension": "tension_swing", "curvature": "curvature"}


@dataclass(frozen=True)
class FairleadLoad:
    """``[load]`` settings of the fairlead test.

    Attributes:
        bend_curvature: the curvature κ of the strand's axis at the fairlead, 1/m; 0: given
            otherwise.
        bend_radius: or the radius R of the strand's axis over the sheave or in the bend
            stiffener (the groove's radius plus half the strand's diameter), m: κ = 1/R; 0: given
            otherwise.
        bend_angle: or the angle the line turns through over ``bend_length``, deg: κ = angle /
            length, the mean curvature (a bend stiffener's peak is higher); 0: given otherwise.
        bend_length: the length over which ``bend_angle`` is turned, m.
        cycled: what the cycle varies: "tension" (the end force over [load] tension + cycle ×
            tension_swing, the curvature held) or "curvature" (cycle × κ, the tension held).
    """

    bend_curvature: float = 0.0  # 1/m
    bend_radius: float = 0.0  # m
    bend_angle: float = 0.0  # deg
    bend_length: float = 0.0  # m
    cycled: str = "tension"  # "tension" or "curvature"

    UNITS: ClassVar[dict[str, str]] = {
        "bend_curvature": "1/m",
        "bend_radius": "m",
        "bend_angle": "deg",
        "bend_length": "m",
    }


def held_curvature(load: FairleadLoad) -> float:
    """The curvature κ (1/m) that ``load`` gives (0 when none is given)."""
    if load.bend_curvature > 0:
        return load.bend_curvature
    if load.bend_radius > 0:
        return 1.0 / load.bend_radius
    if load.bend_angle > 0 and load.bend_length > 0:
        return math.radians(load.bend_angle) / load.bend_length
    return 0.0


def _curvature_text(load: FairleadLoad) -> str:
    """How ``load`` gives the curvature ("R = 5 m", "20° over 2 m", or "")."""
    if load.bend_radius > 0:
        return f"R = {load.bend_radius:g} m"
    if load.bend_angle > 0:
        return f"{load.bend_angle:g}° over {load.bend_length:g} m"
    return ""


@dataclass(frozen=True, kw_only=True)
class LayerStresses:
    """The model's wire stresses per layer (0 = core) over the measuring zone's elements at one
    state, Pa: the axial stress N/A fitted against φ as mean + amplitude sin φ (+ b cos φ; the
    core: its mean, no amplitude), the wire's own bending stress |M| r/I (its mean and its
    spread, max − min), and the largest surface stress N/A + |M| r/I."""

    tension_stress: Array
    amplitude: Array
    bending: Array
    bending_spread: Array
    peak: Array


def zone_stresses(
    cable: Cable, cells, zone: tuple[float, float], direction: npt.ArrayLike
) -> LayerStresses:
    """``LayerStresses`` of the ``cells`` (``post.CellResults``) whose initial midpoint lies in
    ``zone`` = (z_min, z_max) (m); ``direction``: the set-up's bending direction (the core's
    section frame, ``fatigue.stress.section_frames``)."""
    from ...fatigue.stress import section_components, section_frames

    inside = (cells.z >= zone[0]) & (cells.z <= zone[1])
    e1, e2 = section_frames(cells.tangent, cells.radial, fallback=direction)
    m = section_components(cells.moment, cells.tangent, e1, e2)
    n = len(cable.layers)
    out = {k: np.full(n, np.nan) for k in ("mean", "amp", "bend", "spread", "peak")}
    for i, lay in enumerate(cable.layers):
        mine = inside & (cells.layer == i)
        if not np.any(mine):
            continue
        d = lay.wire.diameter
        axial = cells.axial[mine] / lay.wire.area
        bending = np.hypot(m[mine, 0], m[mine, 1]) * (d / 2) / (np.pi * d**4 / 64)
        if i == 0:
            out["mean"][i], out["amp"][i] = axial.mean(), 0.0
        else:
            out["mean"][i], out["amp"][i], _ = harmonic_fit(cells.phi[mine], axial)
        out["bend"][i], out["spread"][i] = bending.mean(), np.ptp(bending)
        out["peak"][i] = np.max(axial + bending)
    return LayerStresses(
        tension_stress=out["mean"],
        amplitude=out["amp"],
        bending=out["bend"],
        bending_spread=out["spread"],
        peak=out["peak"],
    )


@dataclass(frozen=True, kw_only=True)
class FairleadReport:
    """The fairlead run beside its closed forms.

    Attributes:
        step: the step of the held state (the end of the curvature ramp with the tension cycled,
            the largest curvature with the curvature cycled).
        tension: the strand's tension there, N.
        nominal, curvature: the nominal (end rotations) and the zone's measured curvature, 1/m.
        model: the model's wire stresses in the zone there (``LayerStresses``).
        stick, slip: the closed forms at the zone's curvature and that tension
            (``analytical.BentWireStresses``).
        swing: with the tension cycled, the largest swing reached, N (0 otherwise).
        swing_change: per layer, the zone's mean axial stress change from the held state to
            the largest swing, Pa (empty without).
        swing_fibre: the fibre model's E cos²α ΔT/EA for that swing, Pa.
        bending: with the curvature cycled, the uniform bending report (M–κ beside the
            stick–slip law; None otherwise).
    """

    step: int
    tension: float
    nominal: float
    curvature: float
    model: LayerStresses
    stick: BentWireStresses
    slip: BentWireStresses
    swing: float = 0.0
    swing_change: Array = field(default_factory=lambda: np.zeros(0))
    swing_fibre: Array = field(default_factory=lambda: np.zeros(0))
    bending: BendingReport | None = None


class Fairlead(SetupKind):
    """Bending at a fairlead: tension, the curvature held while the tension cycles, or the
    curvature cycled under the tension (``cycled``)."""

    name = "fairlead"
    unit = "N"
    load_settings = FairleadLoad
    signed = frozenset({*CURVATURE_INPUTS, "bend_length"})  # checked here: ≥ 0
    clamp = False  # Poffenberger–Swart's clamp is not a fairlead's

    def __init__(self, cycled: str = "tension"):
        self.cycled = cycled
        self.parameter = CYCLED.get(cycled, "tension_swing")
        if self.parameter == "curvature":
            self.unit, self.progress_unit, self.symbol, self.measure = (
                "1/m",
                ("1/m", 1.0),
                "κ",
                "curvature",
            )
        else:
            self.unit, self.progress_unit, self.symbol = "N", ("kN", 1e3), "ΔT"
            self.measure = "end_displacement"

    def load_text(self, value: float) -> str:
        if self.parameter == "curvature":
            return f"κ = {value:.3g} 1/m"
        return super().load_text(value)

    # -- settings ----------------------------------------------------------------------------------
    def check_settings(self, load: FairleadLoad, steps) -> None:
        """Its own settings alone, in a case of any kind: no negative curvature input, a known
        ``cycled`` (the shared steps are checked by their own kinds)."""
        for key in (*CURVATURE_INPUTS, "bend_length"):
            value = getattr(load, key)
            if value < 0:
                unit = FairleadLoad.UNITS[key]
                raise CaseError(
                    f"[load] {key} = {value:g} {unit}: expected a positive value (the bending "
                    "direction is [load] direction), or 0 for none"
                )
        if load.cycled not in CYCLED:
            raise CaseError(
                f'[load] cycled = {load.cycled!r}: expected "tension" (the end force cycled, '
                'the curvature held) or "curvature" (the curvature cycled, the tension held)'
            )

    def check_case(self, case: Case) -> None:
        """Exactly one curvature input; the zone shorter than the strand; a tension cycle that
        keeps the strand in tension."""
        own, load = self.load(case), case.load
        if (own.bend_angle > 0) != (own.bend_length > 0):
            raise CaseError(
                f"[load] bend_angle = {own.bend_angle:g} deg and bend_length = "
                f"{own.bend_length:g} m go together: the line turns through bend_angle over "
                "bend_length (κ = angle/length)"
            )
        given = [key for key in CURVATURE_INPUTS if getattr(own, key) > 0]
        if not given:
            raise CaseError(
                '[load] kind = "fairlead" needs the curvature: bend_curvature (1/m), '
                "bend_radius (m, κ = 1/R) or bend_angle (deg) with bend_length (m)"
            )
        if len(given) > 1:
            both = " and ".join(
                f"{key} = {getattr(own, key):g} {CURVATURE_INPUTS[key]}" for key in given
            )
            raise CaseError(f"[load] {both} are both given: give the curvature one way")
        zone, length = load.zone, case.mesh.length
        if zone >= length:
            raise CaseError(
                f"[load] zone = {zone} m must be shorter than [mesh] length = {length} m"
            )
        if own.cycled == "tension":
            lowest = load.tension + load.tension_swing * min(0.0, *load.cycle)
            if lowest <= 0:
                raise CaseError(
                    f"[load] tension_swing = {load.tension_swing:g} N takes the end force down "
                    f"to {lowest:g} N with [load] cycle = {list(load.cycle)}: it must stay "
                    f"above 0 ([load] tension = {load.tension:g} N)"
                )

    def for_case(self, case: Case) -> SetupKind:
        """The kind that cycles what ``[load] cycled`` says."""
        cycled = self.load(case).cycled
        return self if cycled == self.cycled else Fairlead(cycled)

    def amplitude_settings(self, case: Case) -> tuple[str, ...]:
        """The swing when the tension is cycled; none when the curvature is (``check_case``
        requires one of its inputs)."""
        return ("tension_swing",) if self.parameter == "tension_swing" else ()

    # -- the run -----------------------------------------------------------------------------------
    def setup(self, case: Case):
        from ...setups.fairlead import FairleadTest

        return partial(
            FairleadTest,
            zone=case.load.zone,
            direction=case.load.direction,
            cycle_parameter=self.parameter,
        )

    def amplitude(self, case: Case) -> float:
        if self.parameter == "curvature":
            return held_curvature(self.load(case))
        return case.load.tension_swing

    def with_amplitude(self, case: Case, amplitude: float) -> Case:
        if self.parameter != "curvature":
            return super().with_amplitude(case, amplitude)
        values = {
            **dict.fromkeys((*CURVATURE_INPUTS, "bend_length"), 0.0),
            "bend_curvature": amplitude,
        }
        return replace(case, load=case.load.with_values(**values))

    def step_sizes(self, steps) -> tuple[float, float]:
        """First and largest increment of the cycle's legs, from the shared ``[steps]``
        (``steps``: the case's ``StepSettings``)."""
        return getattr(steps, self.parameter), getattr(steps, f"{self.parameter}_max")

    def programme(self, case: Case) -> LoadProgramme:
        """The tension, then the curvature's cycle; or the tension, the curvature held, then the
        swing's cycle."""
        steps = case.steps
        first, largest = self.step_sizes(steps)
        if self.parameter == "curvature":
            return tension_then_cycle(case, "curvature", self.amplitude(case), first, largest)
        bend = Stage(
            "curvature",
            "curvature",
            held_curvature(self.load(case)),
            steps.curvature,
            steps.curvature / 2**steps.cuts,
            steps.curvature_max,
            steps.growth,
            extrapolate=steps.predictor,
        )
        legs = cycle_stages(
            self.parameter,
            self.amplitude(case),
            case.load.cycle,
            first,
            largest,
            cuts=steps.cuts,
            growth=steps.growth,
            predictor=steps.predictor,
        )
        return LoadProgramme((tension_stage(case), bend, *legs), self.parameter)

    # -- results -----------------------------------------------------------------------------------
    def reference(self, case: Case, result) -> FairleadReport | None:
        """The held state's wire stresses in the zone beside the closed forms in full stick
        and full slip at the zone's curvature; the swing's stress change beside the fibre
        model, or the uniform bending report."""
        if self.parameter == "curvature":
            held, cells = result.peak_step, result.peak
        else:
            bent = [s for s in result.steps if s.parameter == "curvature"]
            held, cells = (bent[-1] if bent else None), result.tensioned
        if held is None or cells is None or held.state.curvature == 0:
            return None
        L, zone = case.mesh.length, case.load.zone
        span = (L / 2 - zone / 2, L / 2 + zone / 2)
        tension, kappa = held.state.end_force, held.state.curvature
        closed = {
            state: bent_wire_stresses(
                case.cable, tension, kappa, state, friction=case.contact.friction
            )
            for state in ("stick", "slip")
        }
        report = FairleadReport(
            step=held.number,
            tension=tension,
            nominal=held.state.curvature_nominal,
            curvature=kappa,
            model=zone_stresses(case.cable, cells, span, case.load.direction),
            **closed,
        )
        if self.parameter == "curvature":
            bending = uniform_bending_report(
                case.cable, case.load.tension, result.bending, result.slip
            )
            return replace(report, bending=bending)
        peak = result.peak_step
        if peak is None or result.peak is None or peak.state.tension_swing == 0:
            return report
        base, top = (
            zone_stresses(case.cable, c, span, case.load.direction).tension_stress
            for c in (cells, result.peak)
        )
        swing = peak.state.tension_swing
        ea = fibre_model(case.cable, 1.0)["EA"]
        fibre = np.array(
            [lay.wire.E * np.cos(lay.alpha) ** 2 * swing / ea for lay in case.cable.layers]
        )
        return replace(report, swing=swing, swing_change=top - base, swing_fibre=fibre)

    def summary_lines(self, case: Case, result) -> list[str]:
        r = result.reference
        if r is None:
            return []
        own = self.load(case)
        given = _curvature_text(own)
        if self.parameter == "curvature":
            cycle = f"curvature cycled × {list(case.load.cycle)}, tension held"
        else:
            cycle = (
                f"tension cycled {case.load.tension / 1e3:g} kN + {list(case.load.cycle)} × "
                f"{case.load.tension_swing / 1e3:g} kN, curvature held"
            )
        friction = "with the cable's friction" if case.contact.friction else "frictionless"
        lines = [
            f"fairlead: κ = {held_curvature(own):.4g} 1/m{f' ({given})' if given else ''}; {cycle}",
            f"  at step {r.step} (tension {r.tension / 1e3:.4g} kN): curvature nominal "
            f"{r.nominal:.4g} 1/m, zone {r.curvature:.4g} 1/m "
            f"({100 * (r.curvature / r.nominal - 1):+.1f} %)",
            "  wire stresses in the zone (MPa), model / full stick / full slip "
            f"({friction}; docs/theory.md §5.7) at the zone's curvature:",
            "    layer     σ_T (mean axial)          axial sin φ amplitude     own bending "
            "(mean)        largest surface",
        ]
        m, k, s = r.model, r.stick, r.slip
        for i in range(len(case.cable.layers)):
            name = "core" if i == 0 else f"layer {i}"
            columns = [
                (m.tension_stress[i], k.tension_stress[i], s.tension_stress[i]),
                (m.amplitude[i], k.sine_amplitude[i], s.sine_amplitude[i]),
                (m.bending[i], k.bending[i], s.bending[i]),
                (m.peak[i], k.largest[i], s.largest[i]),
            ]
            text = "  ".join(
                f"{a / 1e6:7.1f} /{b / 1e6:7.1f} /{c / 1e6:7.1f}" for a, b, c in columns
            )
            lines.append(f"    {name:8s}  {text}")
        spread = ", ".join(
            f"{'core' if i == 0 else f'layer {i}'} {100 * d / b:.0f} %"
            for i, (d, b) in enumerate(zip(m.bending_spread, m.bending, strict=True))
        )
        lines.append(
            f"  own bending's spread over the zone (max − min over mean): {spread} (the wires "
            "spin on their neighbours, which the closed forms leave out)"
        )
        core = m.bending[0] / k.bending[0]
        if not abs(core - 1) <= CORE_BENDING_SHARE:
            lines.append(
                f"  warning: the core's own bending in the zone is {core:.2f} × E κ d/2 at the "
                "zone's curvature: the core does not follow the strand's axis (frictionless with "
                '[contact] same_layer = "off", the frozen normals let it snake inside its layer: '
                "docs/mooring.md), and the wire stresses are not the strand's"
            )
        if len(r.swing_change):
            parts = ", ".join(
                f"{'core' if i == 0 else f'layer {i}'} {a / 1e6:+.2f} / {b / 1e6:+.2f}"
                for i, (a, b) in enumerate(zip(r.swing_change, r.swing_fibre, strict=True))
            )
            lines.append(
                f"  at the largest swing {r.swing / 1e3:+.4g} kN, the zone's mean axial stress "
                f"change (MPa), model / fibre model E cos²α ΔT/EA: {parts}"
            )
        if r.bending is not None:
            lines += bending_lines(case.load.zone, r.bending)
        return lines

    def figures(self, case: Case, result, note: str = "") -> list[Path]:
        """With the curvature cycled, the uniform bending test's M–κ figure."""
        if self.parameter != "curvature" or not result.bending:
            return []
        return [bending_figure(case, result, note)]
