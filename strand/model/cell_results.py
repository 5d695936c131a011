"""What is read from a strand state per element and per section: wire axial forces, section
forces and moments, spins and torques, angular sectors, and the resultants of a cross-section.

Conventions (docs/theory.md §4). The lateral load acts along ``direction`` d; the neutral axis of bending
is s = e_z × d. A wire's angle φ is measured from s towards d, so φ = +90° is the fibre stretched
at midspan by a positive load. Moments and curvatures are reported positive for a positive load.
Units: m, N, N m, rad.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import ufl
from dolfinx import fem
from mpi4py import MPI

from .model import StrandModel

__all__ = [
    "CellEvaluator",
    "CellResults",
    "cell_results",
    "section_spin",
    "section_torque",
    "sector_of",
    "section_resultants",
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
