"""Per-layer fits of the wire fields against φ in uniform bending: the amplitudes of the changes
of axial force, spin and torque since the tensioned state, per unit curvature.

Conventions (docs/theory.md §4). The lateral load acts along ``direction`` d; the neutral axis of bending
is s = e_z × d. A wire's angle φ is measured from s towards d, so φ = +90° is the fibre stretched
at midspan by a positive load. Moments and curvatures are reported positive for a positive load.
Units: m, N, N m, 1/m.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from .cell_results import CellResults

__all__ = ["LayerFields", "harmonic_fit", "layer_fields", "zone_layer_fields"]

Array = npt.NDArray[np.float64]


@dataclass(frozen=True)
class LayerFields:
    """Per helical layer 1…N, at one state of uniform bending under tension, the amplitudes of
    the changes of the wire fields since the tensioned state over the measuring zone's cells,
    fitted against φ (``layer_fields``), per unit zone curvature κ.

    Attributes:
        curvature: κ, 1/m.
        axial_share: the axial force's sin φ amplitude over its plane-section value K r κ
            (K = E A cos²α, r the layer's radius).
        spin: the spin's cos φ amplitude over κ, rad m.
        torque: the torque's sin φ amplitude over κ, N m² (a spin Θ cos φ along a helix, where
            dφ/ds = ±sin α / r by the lay's hand, twists the wire by ∓Θ (sin α / r) sin φ per
            unit length: the torque is in phase with the axial force, not with the spin).
        cells: how many cells each layer's fit took.
    """

    curvature: float
    axial_share: Array
    spin: Array
    torque: Array
    cells: npt.NDArray[np.int64]


def harmonic_fit(phi_deg: Array, values: Array) -> Array:
    """(c, a, b) of the least-squares fit values ≈ c + a sin φ + b cos φ over the angles
    ``phi_deg`` (deg); NaN with fewer than three values. The constant and the other harmonic
    are fitted with the one wanted so that neither leaks into it where φ is sampled unevenly."""
    phi = np.radians(np.asarray(phi_deg, float))
    if len(phi) < 3:
        return np.full(3, np.nan)
    basis = np.column_stack([np.ones_like(phi), np.sin(phi), np.cos(phi)])
    return np.linalg.lstsq(basis, np.asarray(values, float), rcond=None)[0]


def layer_fields(
    layer: npt.ArrayLike,
    phi: Array,
    axial: Array,
    spin: Array,
    torque: Array,
    curvature: float,
    plane_axial: Array,
) -> LayerFields:
    """Per helical layer i = 1 … len(``plane_axial``), from its cells (``layer`` == i): the
    sin φ amplitude of the axial force change ``axial`` (N) over ``plane_axial[i − 1]`` × κ
    (K r, N m: the plane-section change is K r κ sin φ), the cos φ amplitude of the spin change
    ``spin`` (rad) and the sin φ amplitude of the torque change ``torque`` (N m), both over
    κ = ``curvature`` (1/m) (``LayerFields``). φ (deg) from the neutral axis towards the
    stretched side (``cell_results``)."""
    layer = np.asarray(layer)
    n = len(plane_axial)
    fits = np.full((3, n), np.nan)
    count = np.zeros(n, dtype=np.int64)
    for i in range(1, n + 1):
        mine = layer == i
        count[i - 1] = mine.sum()
        fits[:, i - 1] = [
            harmonic_fit(phi[mine], values[mine])[k]
            for values, k in ((axial, 1), (spin, 2), (torque, 1))
        ]
    return LayerFields(
        float(curvature),
        fits[0] / (np.asarray(plane_axial) * curvature),
        fits[1] / curvature,
        fits[2] / curvature,
        count,
    )


def zone_layer_fields(
    state: CellResults,
    tensioned: CellResults,
    zone: tuple[float, float],
    curvature: float,
    plane_axial: Array,
) -> LayerFields:
    """``layer_fields`` of the cells whose initial midpoint lies in ``zone`` = (z_min, z_max)
    (m), from the changes of axial force, spin and torque between ``tensioned`` and ``state``,
    at ``state``'s φ."""
    inside = (state.z >= zone[0]) & (state.z <= zone[1])
    return layer_fields(
        state.layer[inside],
        state.phi[inside],
        *((getattr(state, k) - getattr(tensioned, k))[inside] for k in ("axial", "spin", "torque")),
        curvature,
        plane_axial,
    )
