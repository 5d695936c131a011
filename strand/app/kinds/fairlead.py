"""Bending at a fairlead as a set-up kind (``[load] kind = "fairlead"``): the strand under its
tension, bent to the curvature of a fairlead sheave or a bend stiffener and held there while the
tension cycles about its mean, or while the curvature cycles about the held one: a mooring line
where it leaves the floater.

The set-up is ``strand.setups.fairlead.FairleadTest``: the uniform bending test (ends turned by
±κ L/2, a core strut carrying the tension, so that the section moment is uniform) whose tension is
a mean plus a swing, and whose curvature is a held one plus a swing. Its own settings, ``[load]``:

- the held curvature κ of the strand's axis, in exactly one way: ``bend_curvature`` (1/m),
  ``bend_radius`` (m, the radius R of the axis over the sheave or in the stiffener: κ = 1/R), or
  ``bend_angle`` (deg) over ``bend_length`` (m): the mean curvature of a line that turns through
  that angle over that length;
- ``cycled``: "tension" (default: the end force over ``[load] tension`` + ``cycle`` ×
  ``tension_swing``, κ held) or "curvature" (the curvature over κ + ``cycle`` ×
  ``curvature_swing``, the tension held);
- ``curvature_swing`` (1/m): the curvature's amplitude about κ when it is cycled.

The programme: the tension, then κ (held), then the swing's legs; the fatigue histories start at
the bent state, so that a steady repetition of the cycle counts the swings about it, not the
bending from straight. The kind shares the others' settings where they mean the same: ``[load]
tension_swing`` (N) of the ``tension_cycle`` kind, ``zone`` (m, the central measuring zone) of the
``bending`` kind, and their ``[steps]`` ``tension_swing``, ``tension_swing_max`` (N) and
``curvature``, ``curvature_max`` (1/m: the ramp to κ and the curvature's legs). Its reference:
the wire stresses of the bent strand in full stick and in full slip
(``analytical.bent_wire_stresses``, docs/theory.md §5.7) beside the model's in the zone at the
held state and at the largest swing; with the tension cycled, the wires' stress change over the
swing beside the fibre model's; with the curvature cycled, the zone's M–κ figure. Units: m, N,
Pa, 1/m; angles in degrees in the settings.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import partial
from pathlib import Path

import numpy as np
import numpy.typing as npt

from ...analytical.fibre import fibre_model
from ...beam.setting import declared, setting
from ...model.programme import LoadProgramme, Stage, cycle_stages
from ..errors import CaseError
from ..settings import Case
from .base import SetupKind, tension_stage
from .bending import bending_figure
from .fairlead_report import (
    FairleadReport,
    bent_state,
    state_lines,
)

__all__ = ["Fairlead", "FairleadLoad", "held_curvature", "CURVATURE_INPUTS", "CYCLED"]

Array = npt.NDArray[np.float64]

#: the ways to give the curvature (one of them): setting → its unit
CURVATURE_INPUTS = {"bend_curvature": "1/m", "bend_radius": "m", "bend_angle": "deg"}
#: what the cycle varies → the set-up's load parameter
CYCLED = {"tension": "tension_swing", "curvature": "curvature_swing"}


@dataclass(frozen=True, kw_only=True)
class FairleadLoad:
    """``[load]`` settings of the fairlead test (each ≥ 0, checked by ``Fairlead``)."""

    bend_curvature: float = setting(
        0.0,
        "The curvature κ of the strand's axis at the fairlead; 0: given otherwise.",
        unit="1/m",
        sign="any",
    )
    bend_radius: float = setting(
        0.0,
        "Or the radius R of the strand's axis over the sheave or in the bend stiffener (the "
        "groove's radius plus half the strand's diameter): κ = 1/R; 0: given otherwise.",
        unit="m",
        sign="any",
    )
    bend_angle: float = setting(
        0.0,
        "Or the angle the line turns through over ``bend_length``: κ = angle / length, the "
        "mean curvature (a bend stiffener's peak is higher); 0: given otherwise.",
        unit="deg",
        sign="any",
    )
    bend_length: float = setting(
        0.0, "The length over which ``bend_angle`` is turned.", unit="m", sign="any"
    )
    cycled: str = setting(
        "tension",
        'What the cycle varies: "tension" (the end force over [load] tension + cycle × '
        'tension_swing, the curvature held) or "curvature" (κ + cycle × curvature_swing, the '
        "tension held).",
        choices=tuple(CYCLED),
    )
    curvature_swing: float = setting(
        0.0,
        "The curvature's amplitude about κ when it is cycled (a line whose angle at the "
        "fairlead swings: its curvature there swings with it).",
        unit="1/m",
        sign="any",
    )


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


class Fairlead(SetupKind):
    """Bending at a fairlead: tension, then the curvature κ held while the tension cycles about
    its mean, or while the curvature cycles about κ (``cycled``)."""

    name = "fairlead"
    load_settings = FairleadLoad
    clamp = False  # Poffenberger–Swart's clamp is not a fairlead's
    example = ("load.bend_radius=5.0",)  # the curvature has no default

    def __init__(self, cycled: str = "tension"):
        self.cycled = cycled
        self.parameter = CYCLED.get(cycled, "tension_swing")
        if self.parameter == "curvature_swing":
            self.unit, self.progress_unit, self.symbol = "1/m", ("1/m", 1.0), "Δκ"
            self.measure = "curvature"
        else:
            self.unit, self.progress_unit, self.symbol = "N", ("kN", 1e3), "ΔT"
            self.measure = "end_displacement"

    def load_text(self, value: float) -> str:
        if self.parameter == "curvature_swing":
            return f"Δκ = {value:.3g} 1/m"
        return super().load_text(value)

    # -- settings ----------------------------------------------------------------------------------
    def check_settings(self, load: FairleadLoad, steps) -> None:
        """Its own settings alone, in a case of any kind: no negative curvature input (the
        shared steps are checked by their own kinds; ``cycled`` by its declaration)."""
        for key in (*CURVATURE_INPUTS, "bend_length", "curvature_swing"):
            value = getattr(load, key)
            if value < 0:
                setting = declared(FairleadLoad.__dataclass_fields__[key])
                unit = setting.unit if setting is not None else ""
                raise CaseError(
                    f"[load] {key} = {value:g} {unit}: expected a positive value (the bending "
                    "direction is [load] direction, the cycle gives the swing's signs), or 0 "
                    "for none"
                )

    def check_case(self, case: Case) -> None:
        """Exactly one curvature input; the zone shorter than the strand; a tension cycle that
        keeps the strand in tension, or a curvature swing to cycle."""
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
        if own.cycled == "curvature" and not own.curvature_swing > 0:
            raise CaseError(
                '[load] cycled = "curvature" needs [load] curvature_swing (1/m), the '
                "curvature's amplitude about the held one"
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
        """The swing the cycle's targets multiply: ``tension_swing`` (N) or
        ``curvature_swing`` (1/m)."""
        return getattr(case.load, self.parameter)

    def step_sizes(self, steps) -> tuple[float, float]:
        """First and largest increment of the cycle's legs, from the shared ``[steps]``
        (``steps``: the case's ``StepSettings``): ``tension_swing``, ``tension_swing_max`` (N),
        or ``curvature``, ``curvature_max`` (1/m)."""
        name = "tension_swing" if self.parameter == "tension_swing" else "curvature"
        return getattr(steps, name), getattr(steps, f"{name}_max")

    def programme(self, case: Case) -> LoadProgramme:
        """The tension, the curvature κ (held), then the legs of the swing."""
        steps = case.steps
        first, largest = self.step_sizes(steps)
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
        """The held state's and the largest swing's wire stresses in the zone beside the closed
        forms in full stick and full slip at the zone's curvature; with the tension cycled, the
        swing's stress change beside the fibre model."""
        bent = [s for s in result.steps if s.parameter == "curvature"]
        if not bent or result.tensioned is None or bent[-1].state.curvature == 0:
            return None
        held = bent_state(case, bent[-1], result.tensioned)
        top = result.peak_step
        if top is None or result.peak is None or top.load == 0:
            return FairleadReport(held=held)
        peak = bent_state(case, top, result.peak)
        if self.parameter != "tension_swing":
            return FairleadReport(held=held, peak=peak)
        ea = fibre_model(case.cable, 1.0)["EA"]
        return FairleadReport(
            held=held,
            peak=peak,
            swing_change=peak.model.tension_stress - held.model.tension_stress,
            swing_fibre=np.array(
                [lay.wire.E * np.cos(lay.alpha) ** 2 * top.load / ea for lay in case.cable.layers]
            ),
        )

    def summary_lines(self, case: Case, result) -> list[str]:
        r = result.reference
        if r is None:
            return []
        own = self.load(case)
        given = _curvature_text(own)
        cycle = list(case.load.cycle)
        if self.parameter == "curvature_swing":
            what = f"curvature cycled κ + {cycle} × {own.curvature_swing:g} 1/m, tension held"
        else:
            what = (
                f"tension cycled {case.load.tension / 1e3:g} kN + {cycle} × "
                f"{case.load.tension_swing / 1e3:g} kN, curvature held"
            )
        friction = case.contact.friction
        lines = [
            f"fairlead: κ = {held_curvature(own):.4g} 1/m{f' ({given})' if given else ''}; {what}",
            *state_lines("held", r.held, friction),
        ]
        if r.peak is not None:
            label = self.load_text(result.peak_step.load)
            lines += state_lines(f"at the largest swing {label}", r.peak, friction)
        if len(r.swing_change):
            parts = ", ".join(
                f"{'core' if i == 0 else f'layer {i}'} {a / 1e6:+.2f} / {b / 1e6:+.2f}"
                for i, (a, b) in enumerate(zip(r.swing_change, r.swing_fibre, strict=True))
            )
            lines.append(
                "  the zone's mean axial stress change from the held state to the largest swing "
                f"(MPa), model / fibre model E cos²α ΔT/EA: {parts}"
            )
        return lines

    def figures(self, case: Case, result, note: str = "") -> list[Path]:
        """With the curvature cycled, the zone's M–κ loop (the uniform bending test's figure)."""
        if self.parameter != "curvature_swing" or not result.bending:
            return []
        return [bending_figure(case, result, note)]
