"""The saddle test's results beside its references: the midspan deflections of the clamped–clamped
tensioned beam with the stick–slip law (``analytical.TensionedBeam``, both friction rules) at the
model's loads (``saddle_beam_reference``) and the summary's lines comparing them
(``saddle_beam_lines``); its figures, the load–deflection loop and the midspan moment–curvature
against the EI bounds. The kind itself: ``strand.app.kinds.saddle``. Units: m, N, N m.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import numpy.typing as npt

from ...cable.description import Cable
from ..settings import Case

__all__ = [
    "saddle_beam_reference",
    "saddle_beam_lines",
    "load_deflection_figure",
    "midspan_bending_figure",
]

Array = npt.NDArray[np.float64]


def saddle_beam_reference(cable: Cable, length: float, tension: float, loads) -> dict[str, Array]:
    """Midspan deflections (m) of the clamped–clamped tensioned beam (``analytical.TensionedBeam``)
    along the lateral ``loads`` (N, a history that starts from the unloaded beam before its first
    value), with the stick–slip law of each friction rule (Masing cycles): the analytical
    prediction the saddle test sits beside."""
    from ...analytical import StickSlipLaw, TensionedBeam

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
    lines = [
        "tensioned beam with the stick–slip law (clamped–clamped, Masing), deflection (mm):",
        "  P (kN)   model   law: cumulative  own tension",
    ]
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
    ax.plot(d, P, "o-", ms=3, color="tab:blue", label="model", zorder=2)
    # the two friction rules often nearly coincide: a wide pale band under a thin dashed line
    # keeps both in sight where they do
    for rule, style in (
        (
            "cumulative",
            {"color": "tab:orange", "lw": 5, "alpha": 0.45, "zorder": 1, "solid_capstyle": "round"},
        ),
        ("own_tension", {"color": "k", "lw": 1.2, "ls": (0, (4, 2)), "zorder": 3}),
    ):
        ax.plot(
            1e3 * np.r_[0.0, result.reference[rule]],
            P,
            **style,
            label=f"beam, stick–slip law ({rule.replace('_', ' ')}, Masing)",
        )
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

    from ...analytical.fibre import bending_stiffness_bounds
    from ..plots import save_figure

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
