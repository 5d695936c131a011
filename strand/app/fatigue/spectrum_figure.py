"""A spectrum's figure, ``spectrum.png`` (matplotlib), beside ``spectrum.txt``: the damage of each
class (amplitude) of the spectrum, nᵢ dᵢ, at the wire-level model's worst place (and the other
zone's worst, where it has one) and on the strand's tension by the T–N curves; and the classes on
the curves, the wire's S–N curve beside DNV-OS-E301's and API RP 2SK's T–N curves, each class's
count nᵢ beside its cycles to failure Nᵢ at the same stress range.

``spectrum_figure_data`` gathers what the figure shows (``SpectrumFigure``) from the spectrum's
report (``strand.app.fatigue.spectrum_findings``) and its members' fatigue reports;
``spectrum_figure`` draws it. Stress ranges: the wire's surface Δσ for S–N, the nominal ΔT/A on
the strand's metallic area for T–N (DNV-OS-E301's own measure; API RP 2SK's ΔT/MBS drawn on the
same scale). Units: SI in the data, MPa and the cycle parameter's unit in the figure.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from ...fatigue.sn import SNCurve
from ...fatigue.tn import API_SPIRAL_STRAND, DNV_SPIRAL_ROPE
from ...fatigue.zones import ZONES
from .findings import FatigueReport
from .spectrum_findings import SpectrumReport
from .stress_range import layer_name, sn_range

__all__ = [
    "SpectrumFigure",
    "WirePlace",
    "spectrum_figure_data",
    "spectrum_figure",
    "dnv_range",
    "api_range",
]

Array = npt.NDArray[np.float64]


@dataclass(frozen=True, kw_only=True)
class WirePlace:
    """An element of the wire-level model and what each class (A,) does there.

    Attributes:
        element, wire, layer: the element, its wire and layer.
        z: its initial height, m.
        clamp: in a clamp zone, not in the free span.
        curve: its layer's S–N curve.
        range: (A,) its surface stress range in each class's member, Pa.
        damage: (A,) each class's damage there in the spectrum's period, nᵢ dᵢ.
    """

    element: int
    wire: int
    layer: int
    z: float
    clamp: bool
    curve: SNCurve
    range: Array
    damage: Array

    def name(self) -> str:
        """ "wire 67 (layer 5), clamp zone, z = 49.6 mm"."""
        return (
            f"wire {self.wire} ({layer_name(self.layer)}), {ZONES[int(self.clamp)]}, "
            f"z = {1e3 * self.z:.1f} mm"
        )


@dataclass(frozen=True, kw_only=True)
class SpectrumFigure:
    """What ``spectrum.png`` shows, per class (A,) of the spectrum.

    Attributes:
        parameter, unit: the cycle parameter and its unit.
        amplitudes, counts: the classes' amplitudes and their cycles nᵢ in the period.
        places: the element of largest D, then the other zone's (where it has an assessed
            element); none where no wire is assessed.
        tension_range: (A,) each member's largest tension range ΔT, N.
        tension_cycles: some member's tension cycles (``findings.TensionCheck.cycle``); else
            the T–N curves see next to no damage and the figure leaves them out.
        area: the strand's metallic area, m².
        dnv: (A,) DNV-OS-E301's nᵢ D_T,i.
        api: (A,) API RP 2SK's nᵢ D_T,i (None: no breaking strength given).
        breaking_strength: API RP 2SK's MBS, N (0: not given).
        mean_tension: the first member's mean tension, N (API RP 2SK's curve depends on it).
        design_factor: the design fatigue factor every damage includes.
        mean_stress: the wire-level mean-stress correction ("none": the ranges as they are).
    """

    parameter: str
    unit: str
    amplitudes: Array
    counts: Array
    places: list[WirePlace]
    tension_range: Array
    tension_cycles: bool
    area: float
    dnv: Array
    api: Array | None
    breaking_strength: float
    mean_tension: float
    design_factor: float = 1.0
    mean_stress: str = "none"


def _place(report: SpectrumReport, members: list[FatigueReport], k: int) -> WirePlace:
    e = report.elements
    return WirePlace(
        element=k,
        wire=int(e.wire[k]),
        layer=int(e.layer[k]),
        z=float(e.z[k]),
        clamp=bool(e.clamp[k]),
        curve=members[0].curves[int(e.layer[k])],
        range=np.array([m.elements.range[k] for m in members]),
        damage=e.damage[k] * e.shares[:, k],
    )


def _worst_places(report: SpectrumReport, members: list[FatigueReport]) -> list[WirePlace]:
    """The element of largest D, then the other zone's largest (where assessed)."""
    damage = report.elements.damage
    if np.all(np.isnan(damage)):
        return []
    k = int(np.nanargmax(damage))
    other = np.where(report.elements.clamp != report.elements.clamp[k], damage, np.nan)
    places = [_place(report, members, k)]
    if not np.all(np.isnan(other)):
        places.append(_place(report, members, int(np.nanargmax(other))))
    return places


def spectrum_figure_data(
    report: SpectrumReport, members: list[FatigueReport], breaking_strength: float = 0.0
) -> SpectrumFigure:
    """What ``spectrum.png`` shows of ``report``, from its ``members``' fatigue reports (in the
    order of its amplitudes); ``breaking_strength`` (N) for API RP 2SK's curve."""
    checks = [m.tension_check for m in members]
    api = None
    if breaking_strength > 0 and all(c.api is not None for c in checks):
        api = report.counts * np.array([c.api for c in checks])
    return SpectrumFigure(
        parameter=report.parameter,
        unit=report.unit,
        amplitudes=np.asarray(report.amplitudes, float),
        counts=np.asarray(report.counts, float),
        places=_worst_places(report, members),
        tension_range=np.asarray(report.tension.range, float),
        tension_cycles=bool(np.any(report.tension.cycle)),
        area=checks[0].area,
        dnv=report.counts * np.array([c.dnv for c in checks]),
        api=api,
        breaking_strength=breaking_strength,
        mean_tension=float(report.tension.mean[0]),
        design_factor=report.design_factor,
        mean_stress=report.mean_stress,
    )


def dnv_range(n) -> Array:
    """DNV-OS-E301's spiral rope curve: the nominal stress range s (MPa) of ``n`` cycles."""
    a_d, m = DNV_SPIRAL_ROPE
    return (a_d / np.asarray(n, float)) ** (1 / m)


def api_range(n, breaking_strength: float, mean_tension: float, area: float) -> Array:
    """API RP 2SK's spiral strand curve at ``mean_tension`` (N): the nominal stress range
    ΔT/A (MPa) of ``n`` cycles, ΔT = MBS (K/N)^(1/M)."""
    M, log_k0, slope = API_SPIRAL_STRAND
    K = 10.0 ** (log_k0 + slope * mean_tension / breaking_strength)
    return breaking_strength * (K / np.asarray(n, float)) ** (1 / M) / area / 1e6


#: the colours of the wire places (worst first) and of the T–N curves
WIRE_COLOURS = ("tab:red", "tab:orange")
DNV_COLOUR, API_COLOUR = "tab:blue", "tab:green"


def _series(data: SpectrumFigure) -> list[tuple[str, Array, str]]:
    """Per bar series: its legend label (with its D), its nᵢ dᵢ per class, its colour."""
    series = [
        (f"{place.name()}: D = {place.damage.sum():.3g}", place.damage, colour)
        for place, colour in zip(data.places, WIRE_COLOURS, strict=False)
    ]
    if not data.tension_cycles:
        return series
    series.append((f"DNV-OS-E301, T–N: D = {data.dnv.sum():.3g}", data.dnv, DNV_COLOUR))
    if data.api is not None:
        series.append((f"API RP 2SK, T–N: D = {data.api.sum():.3g}", data.api, API_COLOUR))
    return series


def _share(share: float) -> str:
    """A share of a damage in per cent, "<1 %" under one."""
    return "<1 %" if 0 < share < 0.005 else f"{100 * share:.0f} %"


def _damage_panel(ax, data: SpectrumFigure) -> None:
    """Grouped bars: per class, each series' nᵢ dᵢ (log scale), its share of D above it."""
    series = _series(data)
    width = 0.8 / len(series)
    x = np.arange(len(data.amplitudes))
    for j, (label, damage, colour) in enumerate(series):
        shown = np.where(damage > 0, damage, np.nan)
        bars = ax.bar(
            x + (j - (len(series) - 1) / 2) * width,
            shown,
            width,
            color=colour,
            label=label,
            gid=f"bars {j}",
        )
        total = np.nansum(damage)
        if len(x) <= 6 and total > 0:
            ax.bar_label(bars, [_share(d / total) for d in damage], fontsize=6)
    ax.set_yscale("log")
    ax.set_xticks(
        x,
        [
            f"{a:g} {data.unit}\nn = {n:.3g}"
            for a, n in zip(data.amplitudes, data.counts, strict=True)
        ],
    )
    ax.set(
        xlabel=f"class: amplitude of {data.parameter}, cycles n in the period",
        ylabel="damage in the period, nᵢ dᵢ",
        title="damage by class (bars: share of each D)",
    )
    ax.margins(y=0.15)
    ax.grid(alpha=0.3, axis="y", which="both")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2), frameon=False)


def _classes_on(
    ax, data: SpectrumFigure, lives: Array, ranges: Array, colour: str, gid: str, named=True
) -> None:
    """Each class at its stress range (MPa): its count nᵢ (dot; ``named``: the class's amplitude
    beside it, away from its life) joined to its life Nᵢ on the curve (circle)."""
    for life, n, s, a in zip(lives, data.counts, ranges, data.amplitudes, strict=True):
        ax.plot([n, life], [s, s], ":", color=colour, lw=0.8)
        if not named:
            continue
        before = life >= n
        ax.annotate(
            f"{a:g} {data.unit}",
            (n, s),
            xytext=(-5 if before else 5, 0),
            textcoords="offset points",
            ha="right" if before else "left",
            va="center",
            fontsize=6.5,
            color=colour,
        )
    ax.plot(data.counts, ranges, ".", color=colour, ms=7, gid=f"count {gid}")
    ax.plot(lives, ranges, "o", color=colour, mfc="none", ms=7, mew=1.5, gid=f"life {gid}")


def _wire_classes(ax, data: SpectrumFigure, n: Array) -> tuple[list, list]:
    """The places' S–N curves (each once) and their classes; the lives and ranges drawn."""
    for curve in {id(p.curve): p.curve for p in data.places}.values():
        ax.loglog(
            n,
            sn_range(curve, n),
            "k-",
            lw=1.5,
            gid="curve wire",
            label=f"wire S–N, surface Δσ: {curve.name.split(' (')[0]}",
        )
    lives, ranges = [], []
    for j, (place, colour) in enumerate(zip(data.places, WIRE_COLOURS, strict=False)):
        lives.append(place.curve.life(place.range / 2))
        ranges.append(1e-6 * place.range)
        _classes_on(ax, data, lives[-1], ranges[-1], colour, f"wire {j}")
    return lives, ranges


def _tension_classes(ax, data: SpectrumFigure, n: Array) -> tuple[list, list]:
    """The T–N curves on the nominal ΔT/A and the classes on them (API RP 2SK's first, DNV's
    count dots over them); the lives and ranges drawn."""
    from ...fatigue.tn import api_spiral_strand_life, dnv_spiral_rope_life

    nominal, lives = 1e-6 * data.tension_range / data.area, []
    if data.api is not None:
        mbs, mean = data.breaking_strength, data.mean_tension
        ax.loglog(
            n,
            api_range(n, mbs, mean, data.area),
            "--",
            color=API_COLOUR,
            lw=1.5,
            gid="curve api",
            label=f"API RP 2SK spiral strand at T_mean/MBS = {mean / mbs:.2f}, as ΔT/A",
        )
        lives.append(api_spiral_strand_life(data.tension_range, mbs, mean))
        _classes_on(ax, data, lives[-1], nominal, API_COLOUR, "api", named=False)
    ax.loglog(
        n,
        dnv_range(n),
        "-",
        color=DNV_COLOUR,
        lw=1.5,
        gid="curve dnv",
        label="DNV-OS-E301 spiral rope, nominal ΔT/A",
    )
    lives.append(dnv_spiral_rope_life(data.tension_range, data.area))
    _classes_on(ax, data, lives[-1], nominal, DNV_COLOUR, "dnv")
    return lives, [nominal]


def _positive(arrays: list) -> Array:
    """The finite positive values of ``arrays``, in one array."""
    values = np.concatenate([np.ravel(a) for a in arrays])
    return values[np.isfinite(values) & (values > 0)]


def _decade_labels(axis) -> None:
    """Plain numbers on a log axis: every decade, and 2, 3 and 5 times it."""
    from matplotlib.ticker import FuncFormatter

    def label(v, _):
        mantissa = v / 10 ** np.floor(np.log10(v))
        return f"{v:g}" if round(mantissa) in (1, 2, 3, 5) else ""

    axis.set_major_formatter(FuncFormatter(label))
    axis.set_minor_formatter(FuncFormatter(label))


def _curves_panel(ax, data: SpectrumFigure) -> None:
    """The wire S–N curve(s) beside the T–N curves, the classes on them, framed on the classes
    (counts, lives and ranges)."""
    n = np.logspace(1, 13, 400)
    wire_lives, wire_ranges = _wire_classes(ax, data, n)
    tension_lives, tension_ranges = [], []
    if data.tension_cycles:
        tension_lives, tension_ranges = _tension_classes(ax, data, n)
    ax.plot([], [], "k.", ms=7, label="class: its count nᵢ in the period")
    ax.plot([], [], "ko", mfc="none", label="class: its cycles to failure Nᵢ")
    cycles = _positive([*wire_lives, *tension_lives, data.counts])
    ranges = _positive([*wire_ranges, *tension_ranges])
    if len(ranges):
        ax.set_ylim(ranges.min() / 1.6, ranges.max() * 1.6)
        _decade_labels(ax.yaxis)
    if len(cycles):
        ax.set_xlim(max(cycles.min() / 30, n[0]), min(cycles.max() * 10, n[-1]))
    tn = data.tension_cycles
    ax.set(
        xlabel="cycles",
        ylabel="stress range (MPa): wire Δσ (S–N)" + (", nominal ΔT/A (T–N)" if tn else ""),
        title=f"wire S–N{' beside T–N' if tn else ''}: each class's count and life",
    )
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), frameon=False)


def _note(data: SpectrumFigure) -> str:
    """What the damages include that the curves do not show, and what the figure leaves out."""
    parts = []
    if not data.tension_cycles:
        parts.append("no tension cycle in any class: the T–N curves see next to no damage")
    if data.mean_stress != "none":
        parts.append(f"the wire damage takes the {data.mean_stress} mean-stress correction")
    if data.design_factor != 1:
        parts.append(f"every damage the design fatigue factor {data.design_factor:g}")
    return "; ".join(parts)


def spectrum_figure(path: Path, data: SpectrumFigure) -> Path:
    """``spectrum.png``: the damage of each class at the worst wire places and by the T–N
    curves (``_damage_panel``), and the classes on the wire S–N and the T–N curves."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..plots import save_figure

    fig, (bars, curves) = plt.subplots(1, 2, figsize=(13, 6), layout="constrained")
    _damage_panel(bars, data)
    _curves_panel(curves, data)
    note = _note(data)
    fig.suptitle(
        f"fatigue spectrum of {data.parameter}: Miner's D = Σ nᵢ dᵢ over "
        f"{len(data.amplitudes)} classes, per the counts' period" + (f"\n({note})" if note else ""),
        fontsize=11,
    )
    return save_figure(fig, path, None, False)
