"""The seed paper's test as a set-up kind (``[load] kind = "saddle"``): the strand under end
tension, cycled by a saddle load at midspan (``strand.setups.saddle.SaddleTest``).

Its own settings: ``[load] lateral`` (N, the saddle load amplitude) and ``saddle_length`` (m),
``[steps] lateral`` and ``lateral_max`` (N). Its reference: the clamped–clamped tensioned beam with
the stick–slip law (``analytical.TensionedBeam``); its figures: the load–deflection loop and the
midspan moment–curvature. Units: m, N, N m.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import partial
from pathlib import Path

import numpy as np
import numpy.typing as npt

from ..cable import Cable
from ..case import Case, CaseError
from . import SetupKind

__all__ = ["Saddle", "SaddleLoad", "SaddleSteps", "saddle_beam_reference", "saddle_beam_lines"]

Array = npt.NDArray[np.float64]


@dataclass(frozen=True)
class SaddleLoad:
    """``[load]`` settings of the saddle test."""

    lateral: float = 4.3e3  # N, saddle load amplitude
    saddle_length: float = 0.02  # m, axial length of the saddle at midspan


@dataclass(frozen=True)
class SaddleSteps:
    """``[steps]`` settings of the saddle test."""

    lateral: float = 250.0  # N, first lateral increment of each leg of the cycle
    lateral_max: float = 400.0  # N, largest lateral increment


class Saddle(SetupKind):
    """The midspan saddle test: tension, then the lateral load's cycle."""

    name = "saddle"
    parameter = "lateral"
    unit = "N"
    progress_unit = ("kN", 1e3)
    measure = "deflection"
    load_settings = SaddleLoad
    step_settings = SaddleSteps
    signed = frozenset({"lateral"})
    clamp = True

    def check_case(self, case: Case) -> None:
        length, h_max = case.mesh.length, case.mesh.h_max
        saddle_length = self.load(case).saddle_length
        if not h_max <= saddle_length < length:
            raise CaseError(
                f"[load] saddle_length = {saddle_length} m must be shorter than the span ([mesh] "
                f"length = {length} m) and at least [mesh] h_max = {h_max} m (so that every "
                "outer wire has a node under the saddle)"
            )

    def setup(self, case: Case):
        from ..setups.saddle import SaddleTest

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
        return lines + saddle_beam_lines(result)

    def figures(self, case: Case, result, note: str = "") -> list[Path]:
        if not result.cycle_steps:
            return []
        return [load_deflection_figure(case, result, note),
                midspan_bending_figure(case, result, note)]  # fmt: skip


def saddle_beam_reference(cable: Cable, length: float, tension: float, loads) -> dict[str, Array]:
    """Midspan deflections (m) of the clamped–clamped tensioned beam (``analytical.TensionedBeam``)
    along the lateral ``loads`` (N, a history that starts from the unloaded beam before its first
    value), with the stick–slip law of each friction rule (Masing cycles): the analytical
    prediction the saddle test sits beside."""
    from ..analytical import StickSlipLaw, TensionedBeam

    path = np.r_[0.0, np.asarray(loads, dtype=float)]
    return {
        rule: TensionedBeam(length, tension, StickSlipLaw(cable, tension, rule).curvature).cycle(
            path
        )[1:]
        for rule in ("cumulative", "own_tension")
    }


def saddle_beam_lines(result) -> list[str]:
    """The saddle test's deflections beside the tensioned beam with the stick–slip law."""
    steps = result.cycle_steps
    loads = np.array([s.state.lateral for s in steps])
    ref = result.reference
    peak = int(np.argmax(np.abs(loads)))
    lines = ["tensioned beam with the stick–slip law (clamped–clamped, Masing), deflection (mm):",
             "  P (kN)   model   law: cumulative  own tension"]  # fmt: skip
    shown = {peak} | {j for j, s in enumerate(steps) if s in result.unloaded_steps}
    shown |= {int(np.argmin(np.abs(loads[: peak + 1] - f * loads[peak]))) for f in (0.25, 0.5)}
    for j in sorted(shown):
        lines.append(
            f"  {loads[j] / 1e3:6.2f}  {1e3 * steps[j].state.deflection:6.2f}  "
            f"{1e3 * ref['cumulative'][j]:16.2f}  {1e3 * ref['own_tension'][j]:11.2f}"
        )
    return lines


def load_deflection_figure(case: Case, result, note: str = "") -> Path:
    """``load_deflection.png``: the midspan deflection along the cycle, beside the tensioned beam
    with the stick–slip law (both friction rules)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..plots import save_figure

    lateral = result.cycle_steps
    fig, ax = plt.subplots(figsize=(6, 4.5))
    P = [0.0] + [s.state.lateral / 1e3 for s in lateral]
    d = [0.0] + [1e3 * s.state.deflection for s in lateral]
    ax.plot(d, P, "o-", ms=3, label="model")
    for rule, style in (("cumulative", "--"), ("own_tension", ":")):
        ax.plot(1e3 * np.r_[0.0, result.reference[rule]], P, style, color="k",
                label=f"beam, stick–slip law ({rule.replace('_', ' ')}, Masing)")  # fmt: skip
    ax.legend(fontsize=8)
    ax.set_xlabel("midspan deflection (mm)")
    ax.set_ylabel("lateral load P (kN)")
    ax.grid(alpha=0.3)
    ax.set_title(f"load–deflection, T = {case.load.tension / 1e3:g} kN")
    return save_figure(fig, Path(result.folder) / "load_deflection.png", note)


def midspan_bending_figure(case: Case, result, note: str = "") -> Path:
    """``moment_curvature.png``: the midspan section's moment against the core's curvature
    (``result.bending``: ``MidspanBending`` records), with the EI bounds."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..plots import save_figure
    from ..post import bending_stiffness_bounds

    kappa = np.array([row.measures.curvature for row in result.bending])
    moment = np.array([row.measures.moment for row in result.bending])
    ei_min, ei_max = bending_stiffness_bounds(case.cable)
    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.plot(np.r_[0, kappa], np.r_[0, moment], "o-", ms=3, label="model, midspan")
    k = np.linspace(0, np.abs(kappa).max(), 2)
    ax.plot(k, ei_max * k, "--", label=f"EI_max = {ei_max:.0f} N m²")
    ax.plot(k, ei_min * k, ":", label=f"EI_min = {ei_min:.1f} N m²")
    ax.set_ylim(1.2 * min(moment.min(), 0), 1.2 * max(moment.max(), 0) + 1e-9)
    ax.set_xlabel("curvature κ (1/m)")
    ax.set_ylabel("bending moment M (N m)")
    ax.set_title(f"midspan moment–curvature, T = {case.load.tension / 1e3:g} kN")
    ax.legend()
    ax.grid(alpha=0.3)
    return save_figure(fig, Path(result.folder) / "moment_curvature.png", note)
