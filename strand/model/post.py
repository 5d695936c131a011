"""Post-processing of a strand state: wire axial forces, spins and torques, angular sectors,
midspan moment–curvature, per-layer fits of the wire fields against φ, and the analytical
references they are compared with (fibre model, bending-stiffness bounds).

Conventions (docs/theory.md §4). The lateral load acts along ``direction`` d; the neutral axis of bending
is s = e_z × d. A wire's angle φ is measured from s towards d, so φ = +90° is the fibre stretched
at midspan by a positive load. Moments and curvatures are reported positive for a positive load.
Units: m, N, N m, 1/m.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import ufl
from dolfinx import fem
from mpi4py import MPI

from ..cable.description import Cable
from ..cable.geometry import LINE
from .model import StrandModel

__all__ = [
    "CellEvaluator",
    "CellResults",
    "cell_results",
    "section_spin",
    "section_torque",
    "sector_of",
    "LayerFields",
    "harmonic_fit",
    "layer_fields",
    "zone_layer_fields",
    "section_resultants",
    "fibre_model",
    "bending_stiffness_bounds",
    "SlidingCheck",
    "sliding_check",
]

Array = npt.NDArray[np.float64]


@dataclass
class CellResults:
    """Per element, in the geometry's cell order: wire, layer, z (m, initial midpoint), angle φ
    (deg, current, about the core; 0 for the core itself), axial force N (N), the spatial
    section force n (N) and moment m (N m) vectors, the current unit tangent t and radial
    vector, the spin θ·t (rad, ``section_spin``) and the torque m·t (N m, ``section_torque``)."""

    wire: npt.NDArray[np.int32]
    layer: npt.NDArray[np.int32]
    z: Array
    phi: Array
    axial: Array
    force: Array
    moment: Array
    tangent: Array | None = None  # (n, 3) current unit tangent
    radial: Array | None = None  # (n, 3) current midpoint less the core's point at the same z
    spin: Array | None = None  # (n,) rotation of the section about t, rad
    torque: Array | None = None  # (n,) torsional moment about t, N m


class CellEvaluator:
    """Evaluates cell-wise beam quantities (DG0) and maps them to the geometry's cell order."""

    def __init__(self, model: StrandModel):
        mesh = model.cmesh.mesh
        beam = model.beam
        self.D = fem.functionspace(mesh, ("DG", 0, (7,)))
        self.f = fem.Function(self.D)
        n, m = beam.spatial_force(), beam.spatial_moment()
        expr = [beam.N[0], n[0], n[1], n[2], m[0], m[1], m[2]]
        self.expr = fem.Expression(ufl.as_vector(expr), self.D.element.interpolation_points)
        n_local = mesh.topology.index_map(1).size_local
        self.order = np.asarray(mesh.topology.original_cell_index)[:n_local]
        self.dofs = self.D.dofmap.list[:n_local, 0]
        self.n_cells = len(model.geometry.cells)
        self.comm = mesh.comm

    def __call__(self) -> Array:
        """(E, 7) values (N, n, m) of every element in the geometry's order, on every rank."""
        self.f.interpolate(self.expr)
        out = np.zeros((self.n_cells, 7))
        out[self.order] = self.f.x.array.reshape(-1, 7)[self.dofs]
        if self.comm.size > 1:  # each cell is owned by one rank: the sum is exact
            self.comm.Allreduce(MPI.IN_PLACE, out, op=MPI.SUM)
        return out


def section_spin(theta: Array, cells: npt.NDArray[np.integer], tangent: Array) -> Array:
    """Rotation (rad) of each element's section about its own current unit ``tangent`` (E, 3):
    the mean of its two nodes' rotation vectors ``theta`` (N, 3; total, from the initial
    configuration) projected on the tangent, θ·t; ``cells`` (E, 2) are the nodes."""
    return np.einsum("ij,ij->i", theta[cells].mean(axis=1), tangent)


def section_torque(moment: Array, tangent: Array) -> Array:
    """Torsional moment (N m) of each element's section: its spatial moment resultant ``moment``
    (E, 3; the beam's m = Λ Λ₀ M) projected on its current unit ``tangent`` (E, 3), m·t."""
    return np.einsum("ij,ij->i", moment, tangent)


def sector_of(phi_deg: Array, sectors: int = 8) -> npt.NDArray[np.int32]:
    """Angular sector of each angle φ (deg): ``sectors`` bins of 360/sectors degrees, bin 0
    starting at φ = −180°. With 8 sectors, bin 6 is [90°, 135°): next to the stretched fibre."""
    width = 360.0 / sectors
    return (np.floor((np.asarray(phi_deg) + 180.0) / width).astype(np.int32)) % sectors


def cell_results(
    model: StrandModel, direction=(1.0, 0.0, 0.0), evaluator: CellEvaluator | None = None
) -> CellResults:
    """Axial forces, section resultants, spins and torques of every element, with its wire,
    layer, z and φ (measured from the neutral axis e_z × ``direction`` towards ``direction``)."""
    g = model.geometry
    evaluator = evaluator or CellEvaluator(model)
    values = evaluator()
    w = model.node_values()
    x = g.points + w[:, :3]
    mid = x[g.cells].mean(axis=1)
    core = x[g.wire_offsets[0] : g.wire_offsets[1]]
    z0 = g.points[g.cells].mean(axis=1)[:, 2]
    centre = np.column_stack([np.interp(z0, core[:, 2], core[:, i]) for i in range(3)])
    r = mid - centre
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    s = np.cross([0.0, 0.0, 1.0], d)
    # the core is the axis: its φ would be the angle of a round-off vector (rank-dependent)
    phi = np.where(g.cell_layer == 0, 0.0, np.degrees(np.arctan2(r @ d, r @ s)))
    tangent = x[g.cells[:, 1]] - x[g.cells[:, 0]]
    tangent /= np.linalg.norm(tangent, axis=1)[:, None]
    moment = values[:, 4:7]
    return CellResults(
        g.cell_wire,
        g.cell_layer,
        z0,
        phi,
        values[:, 0],
        values[:, 1:4],
        moment,
        tangent,
        r,
        section_spin(w[:, 3:], g.cells, tangent),
        section_torque(moment, tangent),
    )


def section_resultants(model: StrandModel, cells: CellResults, z: float) -> tuple[Array, Array]:
    """Moment (N m) and force (N) resultants of the cross-section at initial height ``z``, about
    the core's current point in that section: M = Σ_wires [(x_w − x_core) × n_w + m_w], F = Σ n_w
    (spatial vectors), from the elements that the section cuts (points interpolated along them)."""
    g = model.geometry
    x = model.positions()
    z0, z1 = g.points[g.cells, 2].T
    cut = np.flatnonzero((z0 <= z) & (z1 > z))
    t = (z - z0[cut]) / (z1[cut] - z0[cut])
    at = x[g.cells[cut, 0]] * (1 - t)[:, None] + x[g.cells[cut, 1]] * t[:, None]
    core = at[g.cell_wire[cut] == 0][0]
    M = (np.cross(at - core, cells.force[cut]) + cells.moment[cut]).sum(axis=0)
    return M, cells.force[cut].sum(axis=0)


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


def fibre_model(cable: Cable, tension: float) -> dict:
    """Axial stiffness (N), strain and wire forces (N) per layer for ends held against rotation
    (docs/theory.md §5.1: ε_w = ε cos²α, F = Σ n E A cos³α ε)."""
    k = 0.0
    per_layer = []
    for lay in cable.layers:
        c = np.cos(lay.alpha)
        n = max(lay.wires, 1)
        k += n * lay.wire.E * lay.wire.area * c**3
        per_layer.append(lay.wire.E * lay.wire.area * c**2)
    eps = tension / k
    return {"EA": k, "strain": eps, "wire_force": [f * eps for f in per_layer]}


def bending_stiffness_bounds(cable: Cable) -> tuple[float, float]:
    """(EI_min, EI_max) in N m²: Σ n EI of free-slipping wires, plus Σ (n/2) E A r² cos³α when
    every layer sticks (docs/theory.md §5.3)."""
    ei_min = sum(
        max(lay.wires, 1) * lay.wire.E * np.pi * lay.wire.diameter**4 / 64 for lay in cable.layers
    )
    stick = sum(
        lay.wires / 2 * lay.wire.E * lay.wire.area * lay.radius**2 * np.cos(lay.alpha) ** 3
        for lay in cable.layers[1:]
    )
    return ei_min, ei_min + stick


@dataclass(frozen=True)
class SlidingCheck:
    """How far the small-sliding assumption holds at a state, per interface i|i+1 (crossings):
    the largest drift (m) of a pair's gap caused by sliding, the share of its closed pairs whose
    drift exceeds ``LIMIT`` × the interface's mean contact approach (m, over its closed pairs),
    and the z (m) of the largest drift."""

    drift: Array
    share: Array
    approach: Array
    z: Array

    #: the drift, as a share of the mean approach, beyond which a pair's force is unreliable
    LIMIT = 0.25

    def exceeded(self) -> npt.NDArray[np.intp]:
        """Interfaces with at least one pair beyond the limit."""
        return np.flatnonzero(self.share > 0)

    def message(self) -> str:
        i = int(self.exceeded()[0])
        return (
            f"beyond small sliding at interface {i}|{i + 1}: the wires slid round the strand so "
            f"far that the gaps of {100 * self.share[i]:.1f} % of its pairs (fixed at t = 0) "
            f"drift by more than {100 * self.LIMIT:.0f} % of the mean contact approach "
            f"({1e6 * self.approach[i]:.2f} µm), by up to {1e6 * self.drift[i]:.2f} µm at "
            f"z = {self.z[i]:.3f} m: their forces are unreliable (docs/theory.md §3.2; "
            '[contact] model = "large" re-projects the pairs)'
        )


def sliding_check(geometry, positions: Array, gap: Array) -> SlidingCheck:
    """The small-sliding check of ``geometry``'s crossings from the node ``positions`` (N, 3)
    and the pairs' current gaps (P,) (m, negative in contact).

    Pairs are fixed at t = 0. The outer node of a crossing stays on its layer's cylinder of
    radius R; when it moves round the strand by s relative to the inner node (across the pair's
    initial normal), the pair's gap drifts by s²/(2R) although the surfaces did not move apart
    (docs/theory.md §3.2; a test checks it against the element's own gap). Axial sliding leaves
    the gap as it is; so does any sliding of a line pair on the straight core (not checked)."""
    p = geometry.pairs
    radius = np.array([lay.radius for lay in geometry.cable.layers])[p.interface + 1]
    around = np.cross([0.0, 0.0, 1.0], p.normal)
    around /= np.linalg.norm(around, axis=1)[:, None]
    moved = positions - geometry.points
    s = np.einsum("ij,ij->i", moved[p.b] - moved[p.a], around)
    drift = s**2 / (2 * radius)
    n = len(geometry.cable.layers) - 1
    out = {k: np.zeros(n) for k in ("drift", "share", "z")}
    out["approach"] = np.full(n, np.inf)
    for i in range(n):
        closed = np.flatnonzero((p.interface == i) & (p.kind != LINE) & (gap < 0))
        if not len(closed):
            continue
        worst = closed[np.argmax(drift[closed])]
        approach = -gap[closed].mean()
        out["drift"][i], out["z"][i] = drift[worst], geometry.points[p.a[worst], 2]
        out["approach"][i] = approach
        out["share"][i] = np.mean(drift[closed] > SlidingCheck.LIMIT * approach)
    return SlidingCheck(**out)
