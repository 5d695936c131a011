"""A cycle of the tension as a set-up kind (``[load] kind = "tension_cycle"``): the strand pulled to
its mean tension, optionally pressed by a saddle load held at midspan, then the end force cycled
about the mean: the load of a mooring line, whose tension varies with the waves.

Its own settings: ``[load] tension_swing`` (N, the amplitude of the end force about ``[load]
tension``: the cycle's targets ``[load] cycle`` × ``tension_swing``, so that the default cycle
[1, 0, −1, 0] takes the end force over T ± tension_swing) and ``fixed_lateral`` (N, a saddle
load at midspan applied after the tension and held through the cycle; 0: none; the saddle's
``[load] saddle_length`` and ``[steps] lateral``, ``lateral_max`` apply), ``[steps]
tension_swing`` and ``tension_swing_max`` (N). The set-up is the saddle test's
(``strand.setups.tension_cycle.TensionCycleTest``, a ``strand.setups.saddle.SaddleTest``: z = 0 clamped, z = L a rigid end section pulled by a
force), whose end force is the tension plus the swing. Its reference: the fibre model (ends held
against rotation, ``analytical.fibre_model``): the end displacement per unit end force L/EA and the
wires' axial stress change E cos²α ΔT/EA per layer. The fatigue report's strand-level T–N check
(``strand.fatigue.tn``) then sees the tension cycle. Units: m, N, Pa.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import partial

import numpy as np

from ...analytical.fibre import fibre_model
from ...beam.setting import setting
from ...model.programme import LoadProgramme, Stage, cycle_stages
from ...setups.tension_cycle import TensionCycleState, TensionCycleTest, TensionSection
from ..errors import CaseError
from ..kind_registry import lookup
from ..settings import Case
from .base import SetupKind, tension_stage

__all__ = [
    "TensionCycle",
    "TensionCycleLoad",
    "TensionCycleSteps",
    "TensionCycleTest",
    "TensionCycleState",
    "TensionSection",
    "TensionCycleReference",
]


@dataclass(frozen=True)
class TensionCycleLoad:
    """``[load]`` settings of the tension cycle."""

    tension_swing: float = setting(
        10e3, "Amplitude of the end force about [load] tension.", unit="N"
    )
    fixed_lateral: float = setting(
        0.0, "Saddle load at midspan held through the cycle; 0: none.", unit="N", sign="any"
    )


@dataclass(frozen=True)
class TensionCycleSteps:
    """``[steps]`` settings of the tension cycle."""

    tension_swing: float = setting(1e3, "First increment of each leg of the cycle.", unit="N")
    tension_swing_max: float = setting(4e3, "Largest increment.", unit="N")


@dataclass(frozen=True)
class TensionCycleReference:
    """The fibre model beside the run (ends held against rotation).

    Attributes:
        ea: axial stiffness Σ n E A cos³α, N.
        end_displacement: the end displacement (m) at every cycle step: the tensioned state's
            plus the swing's L/EA.
        stress_per_newton: per layer, the wires' axial stress per newton of end force,
            E cos²α / EA (Pa/N).
        tension_range: the largest end-force range the run's cycle steps reached, N (the
            tensioned state included).
    """

    ea: float
    end_displacement: list[float]
    stress_per_newton: list[float]
    tension_range: float


class TensionCycle(SetupKind):
    """A cycle of the end force about the mean tension, with a saddle load held or none."""

    name = "tension_cycle"
    parameter = "tension_swing"
    unit = "N"
    progress_unit = ("kN", 1e3)
    symbol = "ΔT"
    measure = "end_displacement"
    load_settings = TensionCycleLoad
    step_settings = TensionCycleSteps
    clamp = False  # Poffenberger–Swart relates a bending amplitude to stress, not a tension cycle

    def check_case(self, case: Case) -> None:
        load = case.load
        lowest = load.tension + self.load(case).tension_swing * min(0.0, *load.cycle)
        if lowest <= 0:
            raise CaseError(
                f"[load] tension_swing = {self.load(case).tension_swing:g} N takes the end force "
                f"down to {lowest:g} N with [load] cycle = {list(load.cycle)}: it must stay above "
                f"0 ([load] tension = {load.tension:g} N; a compressed strand is outside the model)"
            )
        if self.load(case).fixed_lateral != 0:
            lookup("saddle").check_case(case)  # its saddle under the mesh

    def setup(self, case: Case):
        return partial(
            TensionCycleTest, saddle_length=case.load.saddle_length, direction=case.load.direction
        )

    def programme(self, case: Case) -> LoadProgramme:
        """The tension, the held saddle load (if any), then the cycle of the swing."""
        steps, load = case.steps, case.load
        stages = [tension_stage(case)]
        lateral = self.load(case).fixed_lateral
        if lateral != 0:
            stages.append(
                Stage(
                    "lateral",
                    "lateral",
                    lateral,
                    steps.lateral,
                    steps.lateral / 2**steps.cuts,
                    steps.lateral_max,
                    steps.growth,
                    extrapolate=steps.predictor,
                )
            )
        first, largest = self.step_sizes(self.steps(case))
        stages += cycle_stages(
            self.parameter,
            self.amplitude(case),
            load.cycle,
            first,
            largest,
            cuts=steps.cuts,
            growth=steps.growth,
            predictor=steps.predictor,
        )
        return LoadProgramme(tuple(stages), self.parameter)

    def reference(self, case: Case, result) -> TensionCycleReference | None:
        """The fibre model's end displacements along the cycle and wire stresses per newton."""
        cycle = result.cycle_steps
        before = [s for s in result.steps if s.parameter != self.parameter]
        if not cycle or not before:
            return None
        ea = fibre_model(case.cable, 1.0)["EA"]
        u0 = before[-1].state.end_displacement
        forces = [before[-1].state.end_force] + [s.state.end_force for s in cycle]
        return TensionCycleReference(
            ea=ea,
            end_displacement=[u0 + s.state.tension_swing * case.mesh.length / ea for s in cycle],
            stress_per_newton=[
                lay.wire.E * np.cos(lay.alpha) ** 2 / ea for lay in case.cable.layers
            ],
            tension_range=float(np.ptp(forces)),
        )

    def summary_lines(self, case: Case, result) -> list[str]:
        from ..summary import layer_stresses

        ref, peak = result.reference, result.peak_step
        if ref is None or peak is None or result.tensioned is None or result.peak is None:
            return []
        i = result.cycle_steps.index(peak)
        u0 = [s for s in result.steps if s.parameter != self.parameter][-1].state.end_displacement
        du, du_ref = peak.state.end_displacement - u0, ref.end_displacement[i] - u0
        swing = peak.state.tension_swing
        L = case.mesh.length
        change = layer_stresses(case.cable, result.peak, L) - layer_stresses(
            case.cable, result.tensioned, L
        )
        lines = [
            f"tension cycle: end force {case.load.tension / 1e3:g} kN ± "
            f"{self.load(case).tension_swing / 1e3:g} kN (cycle {list(case.load.cycle)}), "
            f"range reached {ref.tension_range / 1e3:.4g} kN; saddle load held "
            f"{self.load(case).fixed_lateral:g} N",
            f"  at the largest swing {swing / 1e3:+.4g} kN: end displacement change "
            f"{1e6 * du:+.2f} µm, fibre model (L/EA, EA = {ref.ea / 1e6:.2f} MN) "
            f"{1e6 * du_ref:+.2f} µm ({100 * (du / du_ref - 1):+.1f} %)",
            "  mean wire stress change, middle half (MPa), model / fibre model E cos²α ΔT/EA:",
        ]
        for j, (ds, k) in enumerate(zip(change, ref.stress_per_newton, strict=True)):
            name = "core" if j == 0 else f"layer {j}"
            lines.append(f"    {name:8s} {ds / 1e6:+8.2f} / {k * swing / 1e6:+8.2f}")
        return lines
