"""The seed paper's test as a set-up kind (``[load] kind = "saddle"``): the strand under end
tension, cycled by a saddle load at midspan (``strand.setups.saddle.SaddleTest``), under force or
displacement control.

Its own settings: ``[load] control`` ("force" by default, or "displacement"), ``lateral`` (N, the
saddle load amplitude under force control), ``deflection`` and ``yb`` (m, the amplitude under
displacement control) and ``saddle_length`` (m); ``[steps] lateral``, ``lateral_max`` (N),
``deflection``, ``deflection_max``, ``yb`` and ``yb_max`` (m).

Under displacement control the cycle prescribes the core's displacement along the load
direction, and each step finds the saddle load that gives it, to ``CONTROL_TOLERANCE`` of the
first increment (``strand.solver.displacement_control``: the secant method on solves of the
force-controlled test, so that the load keeps the saddle's distribution). Exactly one amplitude
is given; it names the displacement (a sweep's amplitudes are then of it):

- ``deflection``: at midspan; the cycle's targets are ``[load] cycle`` × deflection;
- ``yb``: the conductor practice's bending amplitude Y_b, the peak-to-peak displacement of the
  conductor relative to the clamp at 89 mm (3.5 in) from the last point of contact between them
  (IEEE Committee Report, Standardization of conductor vibration measurements, IEEE Trans. PAS-85,
  1966, after Poffenberger and Swart 1965; the definition CIGRE and the EPRI Orange Book, 2006,
  ch. 3, use), here at ``[fatigue] clamp_distance`` (0.089 m) from the clamp z = 0. The parameter
  yb prescribes half its value there, so that the cycle [1, 0, −1, 0] × yb moves the point
  between ±yb/2: a Y_b of yb.

The kind then runs as ``SaddleDisplacement`` (``for_case``), whose cycle parameter is
``deflection`` or ``yb`` (m) and whose sweep measure is the saddle load. Its reference: the
clamped–clamped tensioned beam with the stick–slip law (``analytical.TensionedBeam``) at the
model's loads; its figures: the load–deflection loop and the midspan moment–curvature (both
``strand.app.kinds.saddle_report``). Units: m, N, N m.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import partial
from pathlib import Path

import numpy as np
import numpy.typing as npt

from ...beam.setting import setting
from ..errors import CaseError
from ..layer_report import layer_pressure_figure, layer_pressure_lines
from ..settings import Case
from .base import SetupKind
from .saddle_report import (
    load_deflection_figure,
    midspan_bending_figure,
    saddle_beam_lines,
    saddle_beam_reference,
)

__all__ = ["Saddle", "SaddleDisplacement", "SaddleLoad", "SaddleSteps", "CONTROL_TOLERANCE"]

Array = npt.NDArray[np.float64]

#: under displacement control, the largest distance between the measured and the prescribed
#: displacement, as a fraction of the first increment of the cycle's legs ([steps] deflection,
#: or yb/2)
CONTROL_TOLERANCE = 1e-3
#: the amplitudes of displacement control
DISPLACEMENTS = ("deflection", "yb")


@dataclass(frozen=True)
class SaddleLoad:
    """``[load]`` settings of the saddle test."""

    lateral: float = setting(4.3e3, "Saddle load amplitude.", unit="N", sign="any")
    saddle_length: float = setting(0.02, "Axial length of the saddle at midspan.", unit="m")
    control: str = setting(
        "force",
        "force: the amplitude is the saddle load lateral; displacement: the saddle load that "
        "gives deflection (m, midspan) or yb (m, Y_b at [fatigue] clamp_distance).",
        choices=("force", "displacement"),
    )
    deflection: float = setting(
        0.0,
        "Displacement control: the midspan deflection amplitude; 0: none.",
        unit="m",
        sign="any",
    )
    yb: float = setting(
        0.0,
        "Displacement control: Y_b, peak-to-peak at [fatigue] clamp_distance from the clamp; "
        "0: none.",
        unit="m",
        sign="any",
    )


@dataclass(frozen=True)
class SaddleSteps:
    """``[steps]`` settings of the saddle test."""

    lateral: float = setting(125.0, "First lateral increment of each leg of the cycle.", unit="N")
    lateral_max: float = setting(
        200.0, "Largest lateral increment (sets the load-step error: docs/benchmarks).", unit="N"
    )
    deflection: float = setting(
        5e-4, "Displacement control: first deflection increment of a leg.", unit="m"
    )
    deflection_max: float = setting(2e-3, "Largest deflection increment.", unit="m")
    yb: float = setting(5e-5, "Displacement control: first yb increment of a leg.", unit="m")
    yb_max: float = setting(2e-4, "Largest yb increment.", unit="m")


class Saddle(SetupKind):
    """The midspan saddle test: tension, then the lateral load's cycle."""

    name = "saddle"
    parameter = "lateral"
    unit = "N"
    progress_unit = ("kN", 1e3)
    symbol = "P"
    measure = "deflection"
    load_settings = SaddleLoad
    step_settings = SaddleSteps
    clamp = True

    def check_settings(self, load, steps) -> None:
        super().check_settings(load, steps)
        for name in DISPLACEMENTS:
            if getattr(steps, name) > getattr(steps, f"{name}_max"):
                raise CaseError(
                    f"[steps] {name} = {getattr(steps, name)} m exceeds {name}_max "
                    f"= {getattr(steps, f'{name}_max')} m"
                )
            if getattr(load, name) < 0:
                raise CaseError(
                    f"[load] {name} = {getattr(load, name)} m: expected a positive "
                    "amplitude (the cycle gives the signs), or 0 for none"
                )

    def check_case(self, case: Case) -> None:
        length, h_max = case.mesh.length, case.mesh.h_max
        own = self.load(case)
        if not h_max <= own.saddle_length < length:
            raise CaseError(
                f"[load] saddle_length = {own.saddle_length} m must be shorter than the span "
                f"([mesh] length = {length} m) and at least [mesh] h_max = {h_max} m (so that "
                "every outer wire has a node under the saddle)"
            )
        given = [name for name in DISPLACEMENTS if getattr(own, name) > 0]
        if own.control == "force":
            if given:
                raise CaseError(
                    f"[load] {given[0]} = {getattr(own, given[0])} m is a displacement amplitude:"
                    ' give it with [load] control = "displacement" (under "force" the amplitude'
                    " is lateral)"
                )
            return
        if not given:
            raise CaseError(
                '[load] control = "displacement" needs its amplitude: [load] deflection (m, at '
                "midspan) or yb (m, Y_b peak-to-peak at [fatigue] clamp_distance from the "
                "clamp); with a sweep, the one given names the displacement swept"
            )
        if len(given) > 1:
            raise CaseError(
                f"[load] deflection = {own.deflection} m and yb = {own.yb} m are both given: "
                "give one amplitude (deflection at midspan, or Y_b near the clamp)"
            )
        if own.lateral != SaddleLoad.lateral:
            raise CaseError(
                f"[load] lateral = {own.lateral:g} N is a force amplitude; under control = "
                f'"displacement" the amplitude is [load] {given[0]}: leave lateral out'
            )
        distance = case.fatigue.clamp_distance
        if given == ["yb"] and not distance < length / 2:
            raise CaseError(
                f"[fatigue] clamp_distance = {distance} m, where yb is measured, is not short of "
                f"midspan ([mesh] length = {length} m): Y_b needs a span longer than twice that"
            )

    def for_case(self, case: Case) -> SetupKind:
        """Under displacement control, ``SaddleDisplacement`` of the amplitude given."""
        own = self.load(case)
        if own.control != "displacement":
            return self
        return SaddleDisplacement("yb" if own.yb > 0 else "deflection")

    def setup(self, case: Case):
        from ...setups.saddle import SaddleTest

        return partial(
            SaddleTest, saddle_length=self.load(case).saddle_length, direction=case.load.direction
        )

    def reference(self, case: Case, result) -> dict[str, Array] | None:
        """The tensioned beam's deflections (m) at every cycle step, per friction rule."""
        if not result.cycle_steps:
            return None
        loads = [s.state.lateral for s in result.cycle_steps]
        return saddle_beam_reference(case.cable, case.mesh.length, case.load.tension, loads)

    def summary_lines(self, case: Case, result) -> list[str]:
        peak = result.peak_step
        if peak is None:
            return []
        lines = [
            f"largest lateral load {peak.load / 1e3:.2f} kN: midspan deflection "
            f"{1e3 * peak.state.deflection:.2f} mm, end displacement "
            f"{1e3 * peak.state.end_displacement:.3f} mm"
        ]
        zero = result.unloaded_steps
        if zero:
            lines.append(
                "back at P = 0: deflection "
                + ", ".join(f"{1e3 * s.state.deflection:+.2f} mm" for s in zero)
            )
        return (
            lines
            + saddle_beam_lines(result)
            + layer_pressure_lines(result, self.load_text(peak.load))
        )

    def figures(self, case: Case, result, note: str = "") -> list[Path]:
        if not result.cycle_steps:
            return []
        title = f"{case.cable.name}, T = {case.load.tension / 1e3:g} kN"
        peak = result.peak_step
        layers = layer_pressure_figure(result, title, self.load_text(peak.load), note)
        return [
            load_deflection_figure(case, result, note),
            midspan_bending_figure(case, result, note),
        ] + ([layers] if layers else [])


class SaddleDisplacement(Saddle):
    """The midspan saddle test under displacement control: tension, then the cycle of the
    displacement ``parameter`` ("deflection" or "yb", m), the saddle load found at every step."""

    unit = "m"
    progress_unit = ("mm", 1e-3)
    symbol = ""  # the parameter's name: deflection or yb
    measure = "lateral"

    def __init__(self, parameter: str):
        self.parameter = parameter

    def control(self, case: Case):
        """The displacement the cycle prescribes (``setups.saddle.ControlledDisplacement``)."""
        from ...setups.saddle import ControlledDisplacement

        yb = self.parameter == "yb"
        per_unit = 0.5 if yb else 1.0
        tolerance = CONTROL_TOLERANCE * per_unit * getattr(self.steps(case), self.parameter)
        height = case.fatigue.clamp_distance if yb else None
        return ControlledDisplacement(self.parameter, height, per_unit, tolerance)

    def setup(self, case: Case):
        from ...setups.saddle import SaddleTest

        return partial(
            SaddleTest,
            saddle_length=self.load(case).saddle_length,
            direction=case.load.direction,
            control=self.control(case),
        )

    def summary_lines(self, case: Case, result) -> list[str]:
        peak, cycle = result.peak_step, result.cycle_steps
        if peak is None:
            return []
        control = self.control(case)
        where = (
            "midspan" if control.height is None else f"{1e3 * control.height:g} mm from the clamp"
        )
        error = max(abs(s.state.measured - s.state.prescribed) for s in cycle)
        solves = np.mean([s.state.solves for s in cycle])
        lines = [
            f"displacement control of {self.parameter} at {where}: measured within "
            f"{1e6 * error:.3f} µm of the prescribed displacement (tolerance "
            f"{1e6 * control.tolerance:.3f} µm), {solves:.1f} solves per step"
        ]
        if self.parameter == "yb":
            reached = np.ptp([s.state.measured for s in cycle])
            lines.append(f"Y_b reached {1e3 * reached:.3f} mm peak-to-peak at {where}")
        state = peak.state
        lines.append(
            f"at the largest {self.parameter} {1e3 * peak.load:+.3f} mm: saddle load "
            f"{state.lateral / 1e3:+.3f} kN, midspan deflection {1e3 * state.deflection:+.3f} "
            f"mm, end displacement {1e3 * state.end_displacement:.3f} mm"
        )
        zero = result.unloaded_steps
        if zero:
            lines.append(
                f"back at {self.parameter} = 0: saddle load "
                + ", ".join(f"{s.state.lateral / 1e3:+.3f} kN" for s in zero)
            )
        return lines + saddle_beam_lines(result)
