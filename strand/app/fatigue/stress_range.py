"""The fatigue report's ``stress_range.png`` (matplotlib): every layer's surface stress range along
the strand, the largest of all marked, beside the layers' S–N curves with each wire's largest range
on its curve. Every layer, not the outer one alone: the worst wires may lie in any layer (the core
at a clamp, a thin inner layer under a saddle), and a line per layer (its envelope over its wires)
stays readable where a line per wire of a 120-wire strand does not. Units: Pa, m in the report;
MPa, mm in the figure.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from ...fatigue.sn import SNCurve
from ...fatigue.zones import ZONES
from .findings import ElementResults, FatigueReport

__all__ = [
    "LargestRange",
    "largest_range",
    "layer_envelope",
    "layer_name",
    "sn_range",
    "stress_range_figure",
]

Array = npt.NDArray[np.float64]


@dataclass(frozen=True)
class LargestRange:
    """The element of largest surface stress range (Pa) of a report: its wire, layer, initial
    height z (m) and zone."""

    range: float
    element: int
    wire: int
    layer: int
    z: float
    clamp: bool

    def where(self) -> str:
        """Where it lies, in words: "wire 82 (layer 5), z = 120.0 mm, clamp zone"."""
        return (
            f"wire {self.wire} ({layer_name(self.layer)}), z = {1e3 * self.z:.1f} mm, "
            f"{ZONES[int(self.clamp)]}"
        )


def layer_name(layer: int) -> str:
    """ "core" for layer 0, else "layer i"."""
    return "core" if layer == 0 else f"layer {layer}"


def largest_range(elements: ElementResults) -> LargestRange:
    """The element of largest surface stress range over every layer."""
    k = int(np.nanargmax(elements.range))
    return LargestRange(
        range=float(elements.range[k]),
        element=k,
        wire=int(elements.wire[k]),
        layer=int(elements.layer[k]),
        z=float(elements.z[k]),
        clamp=bool(elements.clamp[k]),
    )


def layer_envelope(elements: ElementResults, layer: int) -> tuple[Array, Array, npt.NDArray]:
    """The largest surface stress range along z over the wires of ``layer``: z split into as
    many equal bins as a wire of the layer has elements, in each the element of largest range;
    its z (m, increasing), range (Pa) and wire. The layer's largest range is among them."""
    mine = np.flatnonzero(elements.layer == layer)
    per_wire = np.bincount(elements.wire[mine]).max()
    z = elements.z[mine]
    edges = np.linspace(z.min(), z.max(), per_wire + 1)
    bins = np.clip(np.searchsorted(edges, z, side="right") - 1, 0, per_wire - 1)
    order = np.lexsort((-elements.range[mine], bins))  # by bin, largest range first
    first = order[np.r_[True, bins[order][1:] != bins[order][:-1]]]
    chosen = mine[first]
    return elements.z[chosen], elements.range[chosen], elements.wire[chosen]


def sn_range(curve: SNCurve, n) -> Array:
    """The stress range Δσ = 2σ_a (MPa) at which ``curve`` gives ``n`` cycles to failure."""
    n = np.asarray(n, float)
    high = curve.A * n**curve.b
    if not curve.A2:
        return 2 * high
    return 2 * np.where(n <= curve.knee, high, curve.A2 * n**curve.b2)


def _layer_colours(n: int) -> list:
    """A colour per layer, the core black, the layers outwards from tab10."""
    import matplotlib.pyplot as plt

    cycle = plt.get_cmap("tab10").colors
    return ["k", *(cycle[i % len(cycle)] for i in range(n - 1))]


def _clamp_lines(ax, report: FatigueReport) -> None:
    for z in (report.end_zone, report.length - report.end_zone):
        if 0 < z < report.length:
            ax.axvline(1e3 * z, color="k", ls="--", lw=0.6)


def _poffenberger_swart(ax, report: FatigueReport) -> None:
    check = report.poffenberger_swart
    if check is not None and check.holds:
        ax.plot(
            [0],
            [2e-6 * check.sigma_a],
            "kP",
            ms=9,
            label=f"Poffenberger–Swart 2σ_a at the clamp, outer layer "
            f"({2e-6 * check.sigma_a:.1f} MPa)",
        )


def _mark_largest(ax, largest: LargestRange) -> None:
    """A star on the largest range, with its value and place."""
    x, y = 1e3 * largest.z, 1e-6 * largest.range
    ax.plot([x], [y], "*", ms=15, mfc="gold", mec="k", zorder=5, gid="largest")
    left = x > np.mean(ax.get_xlim())
    ax.annotate(
        f"largest: {y:.1f} MPa\n{largest.where().replace(', z', chr(10) + 'z')}",
        (x, y),
        xytext=(-14 if left else 14, 0),
        textcoords="offset points",
        ha="right" if left else "left",
        va="center",
        fontsize=8,
        bbox={"boxstyle": "round", "fc": "w", "ec": "0.5", "alpha": 0.9},
        zorder=6,
        gid="largest",
    )


def _along_panel(ax, report: FatigueReport, colours: dict, largest: LargestRange) -> None:
    """Per layer its envelope along z, the clamp zones, Poffenberger–Swart, the largest."""
    for i, colour in colours.items():
        z, ranges, wires = layer_envelope(report.elements, i)
        k = int(np.argmax(ranges))
        ax.plot(
            1e3 * z,
            1e-6 * ranges,
            lw=1.2,
            color=colour,
            gid=f"envelope {i}",
            label=f"{layer_name(i)}: up to {1e-6 * ranges[k]:.0f} MPa (wire {wires[k]})",
        )
    _clamp_lines(ax, report)
    _poffenberger_swart(ax, report)
    ax.set(
        xlabel="z (mm)",
        ylabel="largest surface stress range Δσ (MPa)",
        title="along the strand: per layer the largest over its wires\n(dashed: clamp zones)",
    )
    ax.margins(x=0.02, y=0.12)
    _mark_largest(ax, largest)
    ax.grid(alpha=0.3)
    ax.legend(
        fontsize=7,
        loc="upper center",
        bbox_to_anchor=(0.5, -0.12),
        ncols=min(len(colours), 3),
        frameon=False,
    )


def _curve_lines(sn, report: FatigueReport, n: Array) -> dict[int, SNCurve]:
    """Each distinct S–N curve of the layers once, named with its layers; the assessed layers'
    curves."""
    assessed = {i: c for i, c in enumerate(report.curves) if c is not None}
    styles = iter(["-", "--", "-.", ":"] * 3)
    for curve in {id(c): c for c in assessed.values()}.values():
        mine = [i for i, c in assessed.items() if c is curve]
        names = (
            "every layer" if len(mine) == len(report.curves) else ", ".join(map(layer_name, mine))
        )
        sn.loglog(
            n,
            sn_range(curve, n),
            "k",
            ls=next(styles),
            lw=1.5,
            zorder=2,
            gid=f"curve {mine[0]}",
            label=_wrap(f"{curve.name} ({names})", 50),
        )
    return assessed


def _wire_points(sn, report: FatigueReport, assessed: dict, colours: dict) -> list[float]:
    """Each assessed wire's largest range per zone (○ free span, × clamp zone) at its life on
    its layer's curve, coloured by layer; the ranges drawn (MPa)."""
    wires, drawn = report.wires, []
    for i, curve in assessed.items():
        for zone, marker in ((wires.free_span, "o"), (wires.clamp_zone, "x")):
            ranges = zone.range[(wires.layer == i) & (zone.range > 0)]
            if len(ranges):
                sn.plot(
                    curve.life(ranges / 2),
                    1e-6 * ranges,
                    marker,
                    ms=5,
                    color=colours[i],
                    mfc="none",
                    zorder=3,
                    gid=f"{i} {ZONES[int(marker == 'x')]}",
                )
                drawn += (1e-6 * ranges).tolist()
    for marker, name in (("o", ZONES[0]), ("x", ZONES[1])):
        sn.plot([], [], marker, color="0.3", mfc="none", label=f"each wire's largest, {name}")
    return drawn


def _zoom(sn, assessed: dict, drawn: list[float]) -> None:
    """Stress ranges from 1/1.5 of the smallest drawn to 1.5 times the largest, cycles over
    what the curves give for them (within 10²–10¹²)."""
    low, high = min(drawn) / 1.5, max(drawn) * 1.5
    lives = [c.life(5e5 * np.array([high, low])) for c in assessed.values()]
    first = max(min(n[0] for n in lives), 1e2)
    last = min(max(n[1] for n in lives), 1e12)
    sn.set(xlim=(first, last), ylim=(low, high))
    if high / low < 10:  # within a decade: every minor tick's range in MPa
        from matplotlib.ticker import FuncFormatter

        sn.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
        sn.yaxis.set_minor_formatter(FuncFormatter(lambda v, _: f"{v:g}"))


def _sn_panel(sn, report: FatigueReport, colours: dict, largest: LargestRange) -> None:
    """The layers' S–N curves, each wire's largest range per zone at its life, the largest."""
    assessed = _curve_lines(sn, report, np.logspace(2, 12, 300))
    if not assessed:
        sn.text(
            0.5,
            0.5,
            "not assessed\n(no S–N curve for any layer)",
            ha="center",
            va="center",
            transform=sn.transAxes,
        )
        sn.set_axis_off()
        return
    drawn = _wire_points(sn, report, assessed, colours)
    if largest.layer in assessed:
        life = assessed[largest.layer].life(largest.range / 2)
        sn.plot(
            [life], [1e-6 * largest.range], "*", ms=15, mfc="gold", mec="k", zorder=5, gid="largest"
        )
    skipped = [layer_name(i) for i in colours if i not in assessed]
    sn.set(
        xlabel="cycles to failure N",
        ylabel="stress range Δσ = 2σ_a (MPa)",
        title="S–N curves; the wires coloured by layer"
        + (f"\n(not assessed: {', '.join(skipped)})" if skipped else ""),
    )
    _zoom(sn, assessed, drawn or [1e-6 * largest.range])
    sn.grid(alpha=0.3, which="both")
    sn.legend(fontsize=7, loc="upper right")


def stress_range_figure(path: Path, report: FatigueReport) -> Path:
    """``stress_range.png``: per layer its largest surface stress range along z
    (``layer_envelope``; the clamp zones dashed; Poffenberger–Swart's 2σ_a at the clamp where
    it holds), the largest of all starred with its value, wire, layer and z
    (``largest_range``), beside the layers' S–N curves, Δσ = 2σ_a against the cycles to
    failure N, with each wire's largest range in the free span (○) and the clamp zone (×) on
    its layer's curve at its life."""
    import matplotlib.pyplot as plt

    from ..plots import save_figure

    layers = np.unique(report.elements.layer).tolist()
    colours = dict(zip(layers, _layer_colours(len(layers)), strict=True))
    largest = largest_range(report.elements)
    fig, (ax, sn) = plt.subplots(
        1, 2, figsize=(13, 5.6), width_ratios=(1.5, 1), layout="constrained"
    )
    _along_panel(ax, report, colours, largest)
    _sn_panel(sn, report, colours, largest)
    note = (
        ""
        if report.mean_stress == "none"
        else (
            f"; the damage takes the {report.mean_stress} mean-stress correction, the curve the "
            "ranges as they are"
        )
    )
    fig.suptitle(
        f"surface stress range over the history, every layer: the largest "
        f"{1e-6 * largest.range:.1f} MPa, {largest.where()}{note}",
        fontsize=10,
    )
    return save_figure(fig, path, None, False)


def _wrap(text: str, width: int) -> str:
    import textwrap

    return "\n".join(textwrap.wrap(text, width))
