"""The fatigue report's figures (matplotlib): the fretting map of every interface
(``fretting_map.png``) and the outer wires' surface stress ranges against their S–N curve
(``stress_range.png``), from what the report found (``strand.app.fatigue.findings``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...fatigue.sn import SNCurve
from .findings import FatigueReport

__all__ = ["fatigue_figures", "stress_range_figure"]


def fatigue_figures(folder: str | Path, report: FatigueReport) -> list[Path]:
    """The fatigue report's figures in ``folder``: a fretting map per interface (initial z against
    the angle about the axis; pairs that slid coloured by Ruiz's F₂ of the worst cycle, grey where
    F₂ is zero, pairs stuck throughout in blue; dashed lines bound the clamp zones) and the
    surface stress range along every outer wire (with Poffenberger–Swart's amplitude × 2 at the
    clamp where it holds)."""
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


def stress_range_figure(path: Path, report: FatigueReport) -> Path:
    """``stress_range.png``: the outer wires' largest surface stress range along z (one line per
    wire, the clamp zones dashed; Poffenberger–Swart's 2σ_a at the clamp where it holds) beside
    their layer's S–N curve, Δσ = 2σ_a against the cycles to failure N, with each outer wire's
    largest range in the free span and in the clamp zone placed on it at its life."""
    import matplotlib.pyplot as plt

    from ..plots import save_figure

    elements = report.elements
    layer = int(elements.layer.max())
    outer = elements.layer == layer
    fig, (ax, sn) = plt.subplots(1, 2, figsize=(12, 4.5), width_ratios=(1.6, 1))
    for w in np.unique(elements.wire[outer]):
        mine = elements.wire == w
        ax.plot(1e3 * elements.z[mine], 1e-6 * elements.range[mine], lw=0.6, alpha=0.7)
    for z in (report.end_zone, report.length - report.end_zone):
        if 0 < z < report.length:
            ax.axvline(1e3 * z, color="k", ls="--", lw=0.6)
    check = report.poffenberger_swart
    if check is not None and check.holds:
        ax.plot(
            [0],
            [2e-6 * check.sigma_a],
            "k*",
            ms=10,
            label=f"Poffenberger–Swart 2σ_a at the clamp ({2e-6 * check.sigma_a:.1f} MPa)",
        )
        ax.legend(fontsize=8)
    ax.set(
        xlabel="z (mm)",
        ylabel="largest surface stress range Δσ (MPa)",
        title="along the strand (one line per wire; dashed: clamp zones)",
    )
    ax.grid(alpha=0.3)
    curve = report.curves[layer] if len(report.curves) > layer else None
    if curve is None:
        sn.text(
            0.5,
            0.5,
            f"layer {layer}: not assessed\n(no S–N curve for its wires)",
            ha="center",
            va="center",
            transform=sn.transAxes,
        )
        sn.set_axis_off()
    else:
        wires = report.wires
        n = np.logspace(3, 10, 200)
        sn.loglog(n, _sn_range(curve, n), "k-", lw=1.5, label=_wrap(curve.name, 45), zorder=2)
        lowest = _sn_range(curve, n[-1])
        for zone, marker, name in (
            (wires.free_span, "o", "free span"),
            (wires.clamp_zone, "x", "clamp zone"),
        ):
            ranges = zone.range[(wires.layer == layer) & (zone.range > 0)]
            if len(ranges):
                sn.plot(
                    curve.life(ranges / 2),
                    1e-6 * ranges,
                    marker,
                    ms=6,
                    color="tab:red",
                    zorder=3,
                    mfc="none",
                    label=f"outer wires' largest range, {name}",
                )
                lowest = min(lowest, 1e-6 * ranges.min())
        sn.set(
            xlabel="cycles to failure N",
            ylabel="stress range Δσ = 2σ_a (MPa)",
            title=f"layer {layer}'s S–N curve",
            xlim=(n[0], n[-1]),
            ylim=(lowest / 1.5, None),
        )
        sn.grid(alpha=0.3, which="both")
        sn.legend(fontsize=7, loc="upper right")
    fig.suptitle("outer wires: surface stress range over the history against the S–N curve")
    return save_figure(fig, path, None, True)


def _sn_range(curve: SNCurve, n) -> np.ndarray:
    """The stress range Δσ = 2σ_a (MPa) at which ``curve`` gives ``n`` cycles to failure."""
    n = np.asarray(n, float)
    high = curve.A * n**curve.b
    if not curve.A2:
        return 2 * high
    return 2 * np.where(n <= curve.knee, high, curve.A2 * n**curve.b2)


def _wrap(text: str, width: int) -> str:
    import textwrap

    return "\n".join(textwrap.wrap(text, width))
