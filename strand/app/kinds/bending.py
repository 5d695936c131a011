"""Uniform bending as a set-up kind (``[load] kind = "bending"``): the strand under tension, bent
by end rotations (``strand.setups.bending.UniformBendingTest``): the section's moment–curvature.

Its own settings: ``[load] curvature`` (1/m, the nominal curvature amplitude) and ``zone`` (m, the
central measuring zone), ``[steps] curvature`` and ``curvature_max`` (1/m). Its reference: the
stick–slip law (``analytical.StickSlipLaw``, virgin curve and Masing loops), and per layer the
wires' axial force, spin and torque in the zone beside the smeared estimate of wires rolling on
stuck ties (``analytical.stick_bending_estimate``); its figure: the zone's M–κ loop with the
section moments' uniformity. Units: m, N, N m, 1/m, rad.
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from functools import partial
from pathlib import Path

import numpy as np
import numpy.typing as npt

from ...analytical import StickEstimate
from ...beam.setting import setting
from ...cable.description import Cable
from ...model.layer_fields import LayerFields
from ...setups.bending import ZoneBending
from ..errors import CaseError
from ..layer_report import layer_pressure_figure, layer_pressure_lines
from ..settings import Case
from ..step_records import SlipFractions, StepBending
from .base import SetupKind

__all__ = [
    "UniformBending",
    "BendingLoad",
    "BendingSteps",
    "BendingReport",
    "StickRolling",
    "uniform_bending_report",
    "stick_rolling",
]


@dataclass(frozen=True)
class BendingLoad:
    """``[load]`` settings of the uniform bending test."""

    curvature: float = setting(0.5, "Nominal curvature amplitude.", unit="1/m", sign="any")
    zone: float = setting(
        0.4, "Central zone where the curvature is measured (bending, fairlead).", unit="m"
    )


@dataclass(frozen=True)
class BendingSteps:
    """``[steps]`` settings of the uniform bending test."""

    curvature: float = setting(0.005, "First curvature increment of each leg.", unit="1/m")
    curvature_max: float = setting(0.05, "Largest curvature increment.", unit="1/m")


class UniformBending(SetupKind):
    """Uniform bending by end rotations: tension, then the nominal curvature's cycle."""

    name = "bending"
    parameter = "curvature"
    unit = "1/m"
    progress_unit = ("1/m", 1.0)
    symbol = "κ"
    measure = "curvature"
    load_settings = BendingLoad
    step_settings = BendingSteps
    clamp = False

    def load_text(self, value: float) -> str:
        """A curvature as figure titles give it ("κ = 0.0125 1/m")."""
        return f"κ = {value:.3g} 1/m"

    def check_case(self, case: Case) -> None:
        zone, length = self.load(case).zone, case.mesh.length
        if zone >= length:
            raise CaseError(
                f"[load] zone = {zone} m must be shorter than [mesh] length = {length} m"
            )

    def setup(self, case: Case):
        from ...setups.bending import UniformBendingTest

        return partial(UniformBendingTest, zone=self.load(case).zone, direction=case.load.direction)

    def reference(self, case: Case, result) -> BendingReport | None:
        """What the run measured beside the stick–slip law (``uniform_bending_report``), with
        the wires' fields per layer (``stick_rolling``)."""
        L, zone = case.mesh.length, self.load(case).zone
        rolling = stick_rolling(
            case.cable, case.load.tension, (L / 2 - zone / 2, L / 2 + zone / 2), result
        )
        return uniform_bending_report(
            case.cable, case.load.tension, result.bending, result.slip, rolling
        )

    def summary_lines(self, case: Case, result) -> list[str]:
        return bending_lines(self.load(case).zone, result.reference) + layer_pressure_lines(
            result, self._peak_text(result)
        )

    def figures(self, case: Case, result, note: str = "") -> list[Path]:
        title = f"{case.cable.name}, T = {case.load.tension / 1e3:g} kN"
        layers = layer_pressure_figure(result, title, self._peak_text(result), note)
        return [bending_figure(case, result, note)] + ([layers] if layers else [])

    def _peak_text(self, result) -> str:
        peak = result.peak_step
        return "" if peak is None else self.load_text(peak.load)


@dataclass(frozen=True)
class StickRolling:
    """The wires' fields per helical layer in the measuring zone (``layer_fields.LayerFields``: axial
    force share of plane sections, spin and torque per unit curvature) at the first cycle step
    (the stick regime) and at the largest curvature, with M/κ there over EI_max, beside the
    smeared estimate of wires rolling on stuck ties (``analytical.stick_bending_estimate``;
    its spins and torques are magnitudes)."""

    first: LayerFields
    largest: LayerFields
    slope_first: float  # M/κ over EI_max at the first cycle step
    slope_largest: float  # M/κ over EI_max at the largest curvature
    estimate: StickEstimate


@dataclass(frozen=True)
class BendingReport:
    """What the uniform bending test measured beside the stick–slip law.

    Attributes:
        ei_min, ei_max: the bending stiffness bounds, N m².
        initial_slope: M/κ at the first cycle step, N m².
        uniformity: the largest spread of the zone's five section moments over a step, as a
            share of the largest abs(M).
        reaction_error: the largest difference of an end reaction from the mid-zone moment, as
            a share of the largest abs(M).
        table: the first loading leg at the report curvatures: (κ 1/m, M N m, the law's M with
            the cumulative rule, with the own-tension rule).
        slip_onset: per layer 1, 2, …: the first curvature (1/m) of the first leg at which 10 %
            of the pairs on the layer's inner interface in the zone slip (NaN: none).
        slip_onset_law: the law's κ_b per layer, by friction rule.
        loop_area: a whole cycle's M–κ loop area, J/m (None without one).
        masing_area: Masing's loop area on the same curvature path, J/m, by friction rule.
        rolling: the wires' fields per layer beside the rolling estimate (None without the
            tensioned state, e.g. a run restarted within the cycle).
    """

    ei_min: float
    ei_max: float
    initial_slope: float
    uniformity: float
    reaction_error: float
    table: list[tuple[float, float, float, float]]
    slip_onset: list[float]
    slip_onset_law: dict[str, npt.NDArray[np.float64]]
    loop_area: float | None = None
    masing_area: dict[str, float] | None = None
    rolling: StickRolling | None = None


#: the curvatures (1/m) the report's table gives the first loading leg at
REPORT_CURVATURES = (0.001, 0.005, 0.01, 0.05, 0.1, 0.25, 0.5)


def uniform_bending_report(
    cable: Cable,
    tension: float,
    bending: list[StepBending],
    slip: list[SlipFractions],
    rolling: StickRolling | None = None,
) -> BendingReport | None:
    """What the uniform bending test measured (its ``ZoneBending`` records at the cycle steps,
    and the slipping shares of every step), beside the stick–slip law (``analytical``), with
    the wires' fields per layer ``rolling``; None before the first cycle step."""
    from ...analytical import StickSlipLaw, loop_area, masing

    if not bending:
        return None
    zb = [row.measures for row in bending]
    kn = np.array([r.curvature_nominal for r in zb])
    k = np.array([r.curvature for r in zb])
    M = np.array([r.moment_zone_middle for r in zb])
    sections = np.array([r.section_moments for r in zb])
    reactions = np.array([[r.moment_end_reaction_0, r.moment_end_reaction_L] for r in zb])
    peak = int(np.argmax(np.abs(kn) >= np.abs(kn).max() - 1e-12))
    leg = slice(0, peak + 1)
    laws = {rule: StickSlipLaw(cable, tension, rule) for rule in ("cumulative", "own_tension")}
    order = np.argsort(k[leg])
    table = [
        (
            kappa,
            float(np.interp(kappa, k[leg][order], M[leg][order])),
            float(laws["cumulative"].moment(kappa)),
            float(laws["own_tension"].moment(kappa)),
        )
        for kappa in REPORT_CURVATURES
        if k[0] <= kappa <= np.abs(k[leg]).max() * (1 + 1e-9)
    ]
    loop = masing_area = None
    # a whole cycle: the loop area against Masing's on the same curvature path
    if len(kn) > peak + 2 and abs(kn[-1]) < 1e-12 and np.min(kn) < -0.9 * np.max(kn):
        path = np.r_[0.0, k]
        loop = loop_area(path, np.r_[0.0, M])
        masing_area = {
            rule: loop_area(path, masing(law.moment, path)) for rule, law in laws.items()
        }
    return BendingReport(
        ei_min=laws["cumulative"].ei_min,
        ei_max=laws["cumulative"].ei_max,
        initial_slope=float(M[0] / k[0]),
        uniformity=float(np.max(np.ptp(sections, axis=1)) / np.abs(M).max()),
        reaction_error=float(np.abs(reactions - M[:, None]).max() / np.abs(M).max()),
        table=table,
        slip_onset=slip_onset(len(cable.layers), bending[: peak + 1], k[leg], slip),
        slip_onset_law={r: law.slip_onset for r, law in laws.items()},
        loop_area=loop,
        masing_area=masing_area,
        rolling=rolling,
    )


def stick_rolling(
    cable: Cable, tension: float, zone: tuple[float, float], result
) -> StickRolling | None:
    """The wires' fields per layer in ``zone`` = (z_min, z_max) (m) at the first cycle step and
    at the largest curvature of ``result`` (its ``CellResults`` kept there and at the tensioned
    state, and its ``ZoneBending`` records), beside ``stick_bending_estimate(cable)``; None
    without those states or with a zero curvature."""
    from ...analytical import StickSlipLaw, stick_bending_estimate
    from ...model.layer_fields import zone_layer_fields

    base, peak = result.tensioned, result.peak_step
    if base is None or result.first_cycle is None or result.peak is None or not result.bending:
        return None
    law = StickSlipLaw(cable, tension)
    plane = np.array([lay.K * lay.r for lay in law.layers])  # N m: axial force per unit κ
    rows = {row.step: row.measures for row in result.bending}
    first, largest = result.bending[0].measures, rows.get(peak.number)
    if largest is None or 0.0 in (first.curvature, largest.curvature):
        return None
    fields = [
        zone_layer_fields(cells, base, zone, zb.curvature, plane)
        for cells, zb in ((result.first_cycle, first), (result.peak, largest))
    ]
    slopes = [zb.moment_zone_middle / zb.curvature / law.ei_max for zb in (first, largest)]
    return StickRolling(*fields, *slopes, stick_bending_estimate(cable))


def slip_onset(
    n_layers: int, first_leg: list[StepBending], kappa, slip: list[SlipFractions]
) -> list[float]:
    """Per layer 1 … n_layers − 1: the first zone curvature ``kappa`` (1/m) along the steps of
    ``first_leg`` at which 10 % of the pairs on the layer's inner interface slip (NaN: none)."""
    by_step = {row.step: row for row in slip}
    onset = []
    for i in range(1, n_layers):
        hits = [
            float(kj)
            for kj, row in zip(kappa, first_leg, strict=True)
            if row.step in by_step and by_step[row.step].slipping[i - 1] >= 0.1
        ]
        onset.append(hits[0] if hits else np.nan)
    return onset


def bending_lines(zone: float, r: BendingReport | None) -> list[str]:
    """The uniform bending test's summary lines (zone ``zone`` m, report ``r``), beside the
    stick–slip law."""
    if r is None:
        return []
    lines = [
        f"uniform bending, zone {zone:g} m: section moments uniform within "
        f"{100 * r.uniformity:.2f} %, end reactions within {100 * r.reaction_error:.2f} %",
        f"first step M/κ = {r.initial_slope:.0f} N m² = {r.initial_slope / r.ei_max:.2f} "
        f"EI_max ({r.ei_max:.0f}) = {r.initial_slope / r.ei_min:.1f} EI_min ({r.ei_min:.1f})",
        "  κ (1/m)   M model (N m)   stick–slip law: cumulative  own tension",
    ]
    for kappa, m, cum, own in r.table:
        lines.append(f"  {kappa:7.3f}   {m:13.2f}   {cum:26.2f}  {own:11.2f}")
    if r.loop_area is not None:
        ma = r.masing_area
        lines.append(
            f"loop area {r.loop_area:.2f} J/m; Masing on the same κ path: "
            f"{ma['cumulative']:.2f} (cumulative), {ma['own_tension']:.2f} (own tension)"
        )
    law = r.slip_onset_law
    lines.append("slip onset (10 % of the layer's inner pairs in the zone), κ (1/m):")
    for i, k in enumerate(r.slip_onset, start=1):
        lines.append(
            f"  layer {i}: model {k:.4f}   κ_b cumulative {law['cumulative'][i - 1]:.4f}, "
            f"own tension {law['own_tension'][i - 1]:.4f}"
        )
    if r.rolling is not None:
        lines += rolling_lines(r.rolling)
    return lines


def rolling_lines(r: StickRolling) -> list[str]:
    """The table of the wires' fields per layer (``StickRolling``) in the summary."""
    e = r.estimate
    a, b = r.first, r.largest
    lines = [
        "wire fields per layer in the zone, changes since tension per unit κ, fitted over the "
        "zone's cells against φ:",
        "  axial force a sin φ over K r κ (K = E A cos²α), spin b cos φ, torque c sin φ; at the "
        f"first step κ = {a.curvature:.4g} 1/m (M/κ {r.slope_first:.3f} EI_max)",
        f"  and the largest κ = {b.curvature:.4g} 1/m (M/κ {r.slope_largest:.3f} EI_max); "
        f"estimate of wires rolling on stuck ties: M/κ {e.ratio:.3f} EI_max, magnitudes",
        "  layer   axial force share        spin (rad m)               torque (N m²)",
        "          first largest estimate   first  largest estimate    first  largest estimate",
    ]
    for i in range(len(e.axial_share)):
        lines.append(
            f"  {i + 1:5d}   {a.axial_share[i]:5.2f} {b.axial_share[i]:7.2f} "
            f"{e.axial_share[i]:8.2f}   {a.spin[i]:6.3f} {b.spin[i]:8.3f} {e.spin[i]:8.3f}   "
            f"{a.torque[i]:6.2f} {b.torque[i]:8.2f} {e.torque[i]:8.2f}"
        )
    return lines


def bending_figure(case: Case, result, note: str = "") -> Path:
    """``moment_curvature.png`` of the uniform bending test (``result.bending``: its
    ``ZoneBending`` records): the zone's M–κ loop, the section moments and end reactions
    (uniformity), the EI bounds, and the stick–slip law (virgin curve and Masing loop on the
    measured curvature path, for both friction rules). ``note``: a line in red at the bottom (an
    incomplete run)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ...analytical import StickSlipLaw, masing
    from ..plots import save_figure

    zb = [row.measures for row in result.bending]
    steps = [row.step for row in result.bending]
    k = np.r_[0.0, [r.curvature for r in zb]]
    M = np.r_[0.0, [r.moment_zone_middle for r in zb]]
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 4.8), gridspec_kw={"width_ratios": [3, 2]})
    ax.plot(k, M, "o-", ms=3, color="k", label="strand (mid-zone section)")
    span = np.abs(k).max() or 1.0
    for rule, style in (("cumulative", "-"), ("own_tension", "--")):
        law = StickSlipLaw(case.cable, case.load.tension, rule)
        ax.plot(
            k,
            masing(law.moment, k),
            style,
            lw=1.2,
            label=f"stick–slip law, {rule.replace('_', ' ')} (Masing)",
        )
        ei_min, ei_max = law.ei_min, law.ei_max
    line = np.array([-span, span])
    ax.plot(line, ei_max * line, ":", color="tab:red", label=f"EI_max = {ei_max:.0f} N m²")
    ax.plot(line, ei_min * line, ":", color="tab:blue", label=f"EI_min = {ei_min:.1f} N m²")
    ax.set_ylim(1.3 * min(M.min(), 0) - 1e-9, 1.3 * max(M.max(), 0) + 1e-9)
    ax.set_xlabel("zone curvature κ (1/m)")
    ax.set_ylabel("bending moment M (N m)")
    ax.set_title(f"{case.cable.name}, T = {case.load.tension / 1e3:g} kN: uniform bending")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    names = [f.name for f in fields(ZoneBending) if f.name.startswith("moment_")]
    for name in names:
        ax2.plot(
            steps,
            [getattr(r, name) - r.moment_zone_middle for r in zb],
            ".",
            ms=4,
            label=name.removeprefix("moment_").replace("_", " "),
        )
    ax2.set_xlabel("step")
    ax2.set_ylabel("M − M(mid-zone) (N m)")
    ax2.set_title("uniformity: five sections of the zone, end reactions")
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=7)
    return save_figure(fig, Path(result.folder) / "moment_curvature.png", note)
