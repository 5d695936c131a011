"""The fairlead kind's report (``strand.app.kinds.fairlead``): the model's wire stresses over the
measuring zone at a state, beside the bent strand's closed forms in full stick and full slip
(``analytical.bent_wire_stresses``, docs/theory.md §5.7), and the summary's table of them.
Units: m, N, Pa, 1/m.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from ...analytical import BentWireStresses, bent_wire_stresses
from ...cable.description import Cable
from ...model.layer_fields import harmonic_fit
from ..settings import Case

__all__ = [
    "FairleadReport",
    "BentState",
    "bent_state",
    "LayerStresses",
    "zone_stresses",
    "state_lines",
    "CORE_BENDING_SHARE",
]

Array = npt.NDArray[np.float64]

#: the core's own bending may differ from E κ d/2 at the zone's curvature by this share before the
#: summary warns that the core does not follow the strand's axis (measured: 0.1 % in stick and
#: full slip on a 1+6, a factor 3.9 where the frictionless core snakes)
CORE_BENDING_SHARE = 0.1


@dataclass(frozen=True, kw_only=True)
class LayerStresses:
    """The model's wire stresses per layer (0 = core) over the measuring zone's elements at one
    state, Pa: the axial stress N/A fitted against φ as mean + amplitude sin φ (+ b cos φ; the
    core: its mean, no amplitude), the wire's own bending stress abs(M) r/I (its mean and its
    spread, max − min), and the largest surface stress N/A + abs(M) r/I."""

    tension_stress: Array
    amplitude: Array
    bending: Array
    bending_spread: Array
    peak: Array


def zone_stresses(
    cable: Cable, cells, zone: tuple[float, float], direction: npt.ArrayLike
) -> LayerStresses:
    """``LayerStresses`` of the ``cells`` (``post.CellResults``) whose initial midpoint lies in
    ``zone`` = (z_min, z_max) (m); ``direction``: the set-up's bending direction (the core's
    section frame, ``fatigue.stress.section_frames``)."""
    from ...fatigue.stress import section_components, section_frames

    inside = (cells.z >= zone[0]) & (cells.z <= zone[1])
    e1, e2 = section_frames(cells.tangent, cells.radial, fallback=direction)
    m = section_components(cells.moment, cells.tangent, e1, e2)
    n = len(cable.layers)
    out = {k: np.full(n, np.nan) for k in ("mean", "amp", "bend", "spread", "peak")}
    for i, lay in enumerate(cable.layers):
        mine = inside & (cells.layer == i)
        if not np.any(mine):
            continue
        d = lay.wire.diameter
        axial = cells.axial[mine] / lay.wire.area
        bending = np.hypot(m[mine, 0], m[mine, 1]) * (d / 2) / (np.pi * d**4 / 64)
        if i == 0:
            out["mean"][i], out["amp"][i] = axial.mean(), 0.0
        else:
            out["mean"][i], out["amp"][i], _ = harmonic_fit(cells.phi[mine], axial)
        out["bend"][i], out["spread"][i] = bending.mean(), np.ptp(bending)
        out["peak"][i] = np.max(axial + bending)
    return LayerStresses(
        tension_stress=out["mean"],
        amplitude=out["amp"],
        bending=out["bend"],
        bending_spread=out["spread"],
        peak=out["peak"],
    )


@dataclass(frozen=True, kw_only=True)
class BentState:
    """One state of the fairlead run beside its closed forms.

    Attributes:
        step: its step number.
        tension: the strand's tension there, N.
        nominal, curvature: the nominal (end rotations) and the zone's measured curvature, 1/m.
        model: the model's wire stresses in the zone (``LayerStresses``).
        stick, slip: the closed forms at the zone's curvature and that tension
            (``analytical.BentWireStresses``).
    """

    step: int
    tension: float
    nominal: float
    curvature: float
    model: LayerStresses
    stick: BentWireStresses
    slip: BentWireStresses


@dataclass(frozen=True, kw_only=True)
class FairleadReport:
    """The fairlead run beside its closed forms: the held state (the end of the ramp to κ) and
    the state at the largest swing (None before the cycle), and, with the tension cycled, the
    zone's mean axial stress change per layer between them (Pa) beside the fibre model's
    E cos²α ΔT/EA (empty arrays otherwise)."""

    held: BentState
    peak: BentState | None = None
    swing_change: Array = field(default_factory=lambda: np.zeros(0))
    swing_fibre: Array = field(default_factory=lambda: np.zeros(0))


def bent_state(case: Case, step, cells) -> BentState:
    """The ``BentState`` of the run step ``step`` (a ``RunStep`` of the fairlead set-up) whose
    cell results are ``cells``."""
    L, zone = case.mesh.length, case.load.zone
    tension, kappa = step.state.end_force, step.state.curvature
    closed = {
        state: bent_wire_stresses(case.cable, tension, kappa, state, friction=case.contact.friction)
        for state in ("stick", "slip")
    }
    return BentState(
        step=step.number,
        tension=tension,
        nominal=step.state.curvature_nominal,
        curvature=kappa,
        model=zone_stresses(
            case.cable, cells, (L / 2 - zone / 2, L / 2 + zone / 2), case.load.direction
        ),
        **closed,
    )


def state_lines(title: str, r: BentState, friction: bool) -> list[str]:
    """The summary's table of one state's wire stresses beside the closed forms."""
    m, k, s = r.model, r.stick, r.slip
    change = f" ({100 * (r.curvature / r.nominal - 1):+.1f} %)" if r.nominal else ""
    how = "with the cable's friction" if friction else "frictionless"
    lines = [
        f"  {title}, step {r.step}: tension {r.tension / 1e3:.4g} kN, curvature nominal "
        f"{r.nominal:.4g} 1/m, zone {r.curvature:.4g} 1/m{change}",
        f"    wire stresses in the zone (MPa), model / full stick / full slip ({how}; "
        "docs/theory.md §5.7) at the zone's curvature:",
        "    layer     σ_T (mean axial)          axial sin φ amplitude     own bending (mean)"
        "        largest surface",
    ]
    for i in range(len(m.peak)):
        name = "core" if i == 0 else f"layer {i}"
        columns = [
            (m.tension_stress[i], k.tension_stress[i], s.tension_stress[i]),
            (m.amplitude[i], k.sine_amplitude[i], s.sine_amplitude[i]),
            (m.bending[i], k.bending[i], s.bending[i]),
            (m.peak[i], k.largest[i], s.largest[i]),
        ]
        text = "  ".join(f"{a / 1e6:7.1f} /{b / 1e6:7.1f} /{c / 1e6:7.1f}" for a, b, c in columns)
        lines.append(f"    {name:8s}  {text}")
    spread = ", ".join(
        f"{'core' if i == 0 else f'layer {i}'} {100 * d / b:.0f} %"
        for i, (d, b) in enumerate(zip(m.bending_spread, m.bending, strict=True))
    )
    lines.append(
        f"    own bending's spread over the zone (max − min over mean): {spread} (the wires "
        "spin on their neighbours, which the closed forms leave out)"
    )
    core = m.bending[0] / k.bending[0] if k.bending[0] else 1.0
    if not abs(core - 1) <= CORE_BENDING_SHARE:
        lines.append(
            f"    warning: the core's own bending in the zone is {core:.2f} × E κ d/2 at the "
            "zone's curvature: the core does not follow the strand's axis (frictionless with "
            '[contact] same_layer = "off", the frozen normals let it snake inside its layer: '
            "docs/mooring.md), and the wire stresses are not the strand's"
        )
    return lines
