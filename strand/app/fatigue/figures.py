"""The fatigue report's figures (matplotlib): the fretting map of every interface
(``fretting_map.png``) and every layer's surface stress ranges against their S–N curves
(``stress_range.png``, ``strand.app.fatigue.stress_range``), from what the report found
(``strand.app.fatigue.findings``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .findings import FatigueReport
from .stress_range import stress_range_figure

__all__ = ["fatigue_figures", "stress_range_figure"]


def fatigue_figures(folder: str | Path, report: FatigueReport) -> list[Path]:
    """The fatigue report's figures in ``folder``: a fretting map per interface (initial z against
    the angle about the axis; pairs that slid coloured by Ruiz's F₂ of the worst cycle, grey where
    F₂ is zero, pairs stuck throughout in blue; dashed lines bound the clamp zones) and the
    surface stress range along every layer, the largest marked, against the S–N curves
    (``stress_range_figure``)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm

    from ..plots import save_figure

    folder = Path(folder)
    crossings = report.crossings
    interfaces = np.unique(crossings.interface)
    fig, axes = plt.subplots(
        1,
        len(interfaces),
        figsize=(max(4 * len(interfaces), 6.5), 5),
        sharey=True,
        squeeze=False,
        layout="constrained",
    )
    f2, stuck = 1e-6 * crossings.ruiz_f2, crossings.stuck
    positive = f2[(f2 > 0) & ~stuck]
    norm = LogNorm(positive.max() * 1e-4, positive.max()) if len(positive) else None
    slid_points = None
    angle, z_mm = crossings.angle, 1e3 * crossings.z
    for ax, i in zip(axes[0], interfaces, strict=True):
        on = crossings.interface == i
        held, flat, slid = on & stuck, on & ~stuck & (f2 <= 0), on & ~stuck & (f2 > 0)
        ax.scatter(angle[held], z_mm[held], s=3, c="tab:blue", lw=0, label="stuck throughout")
        ax.scatter(angle[flat], z_mm[flat], s=3, c="0.75", lw=0)
        slid_points = ax.scatter(
            angle[slid], z_mm[slid], c=f2[slid], s=5, cmap="inferno", norm=norm, lw=0
        )
        for z in (report.end_zone, report.length - report.end_zone):
            if 0 < z < report.length:
                ax.axhline(1e3 * z, color="k", ls="--", lw=0.6)
        ax.set(title=f"interface {i}|{i + 1}", xlabel="angle about the axis (°)", xlim=(-180, 180))
    axes[0, 0].set_ylabel("z (mm)")
    if stuck.any():
        axes[0, 0].legend(loc="upper right", fontsize=7, markerscale=3)
    if norm is not None:
        fig.colorbar(slid_points, ax=axes[0], label="Ruiz F₂ = σ_T τ δ (MPa J/m²), worst cycle")
    fig.suptitle(
        "fretting map: pairs that slid, coloured by F₂\n(blue: stuck throughout; "
        "dashed: clamp zones)",
        fontsize=10,
    )
    paths = [save_figure(fig, folder / "fretting_map.png", None, False)]
    paths.append(stress_range_figure(folder / "stress_range.png", report))
    return paths
