"""Uniform bending of a strand under constant tension: the section's moment–curvature law.

Why not simply rotate the ends of a tensioned strand? A tension T applied at the ends acts along a
fixed line; once the strand bends, every section sits a distance v off that line and carries
M(z) = M_end + T·v(z). At T = 40 kN, v = 1 mm already adds 40 N m, more than Cardinal's whole
friction moment: the measured moment would be the set-up's, not the strand's.

The set-up here keeps the tension's line of action on the strand axis everywhere:

* **An axial strut along the core.** Every core element carries a constant compression T along
  its current chord t_e (a follower load: node a receives −T t_e, node b +T t_e). At a core node
  the strut's two elements add T(t_{e−1} − t_e) = T κ ds pointing away from the centre of
  curvature: exactly the transverse load that equilibrates the tension on the arc. The strut is
  pushed apart at the ends, so the wires carry the tension T.
* **Rigid end sections whose rotations are prescribed** (the load): every wire end at z = 0 and
  z = L turns with its section by θ = ±(κ_n L/2) about b = e_z × d (d the bending direction),
  κ_n the nominal curvature. End z = 0 is fixed in space; end z = L (a pilot, the core's end,
  tied to the other wire ends by penalty links that follow the section's rotation) is free to
  translate.

Strand plus strut is then loaded by the two end couples alone: no external force, so every cut
transmits the same moment and no force (the strand's tension and the strut's compression cancel,
and the strut's force passes through the core point of the cut). Hence **the strand's section
moment M is uniform along the whole length, exactly**, whatever the curvature distribution, and the
wires carry the tension T. What it costs: the strut's transverse load Tκ per unit length enters the
strand at the core and reaches the outer layers through the contacts (at κ = 0.5 1/m and 40 kN,
20 kN/m on the side away from the centre of curvature, against the 169/137/94/52 kN/m of radial
load that tension alone puts on the interfaces 0|1 … 3|4); at the curvatures where layers start to
slip (κ ≤ 0.1 1/m) it is under 5 % of those. The strut makes the core a column under T, held
sideways by its contacts; a core that touches no wire (a vaulted first layer) is held on the
layer's axis by springs instead (``centring.CoreCentring``), which the section's moment does not
see (they act between the core and the ring).

The wire ends stick to their sections, so the ends are stiffer than a free strand: the curvature
is measured on a central zone (``zone`` long), from the rotation of the core's tangent between the
zone's ends over the core's arc length there. Measures: section resultants at five sections of
the zone, the reaction couples at both ends, the axial force of the section. Units: m, N, N m, 1/m.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from dolfinx import fem

from ..beam.records import quantity
from ..cable.centring import ring_centres
from ..contact.kinematics import rotation_matrix
from ..model.cell_results import CellResults, section_resultants
from ..model.layer_states import first_layer_lift
from ..model.model import StrandModel
from .base import TestSetup, pilot_links
from .centring import CENTRING_STIFFNESS, CoreCentring

__all__ = ["UniformBendingTest", "CoreStrut", "UniformBendingState", "ZoneBending"]

Array = npt.NDArray[np.float64]


class CoreStrut:
    """A constant compression ``force`` (N) along the current chord of every core element: node a
    receives −F t, node b +F t. A ``PairTerms`` on (a, b); its tangent is the geometric stiffness
    of a compressed bar, ∂f_b/∂x_b = −F (I − t⊗t)/ℓ (negative: it follows the chord)."""

    def __init__(self, stencils: npt.ArrayLike, initial_chords: npt.ArrayLike):
        self.stencils = np.asarray(stencils, dtype=np.int32).reshape(-1, 2)
        self.chords0 = np.asarray(initial_chords, dtype=float).reshape(-1, 3)
        self.force = 0.0
        self.dofs = np.r_[0:3, 6:9]  # translations only

    def evaluate(self, w, jacobian):
        c = self.chords0 + w[self.stencils[:, 1], :3] - w[self.stencils[:, 0], :3]
        length = np.linalg.norm(c, axis=1)
        t = c / length[:, None]
        F = self.force
        f = np.concatenate([F * t, -F * t], axis=1)  # residual = −(force on the strand)
        if not jacobian:
            return f, None
        P = (np.eye(3) - t[:, :, None] * t[:, None, :]) * (F / length)[:, None, None]
        K = np.zeros((len(t), 6, 6))
        K[:, :3, :3] = K[:, 3:, 3:] = -P
        K[:, :3, 3:] = K[:, 3:, :3] = P
        return f, K

    def commit(self) -> None:
        pass

    def rollback(self) -> None:
        pass


@dataclass(frozen=True)
class UniformBendingState:
    """Loads and measures of the uniform bending test at one state."""

    tension: float = quantity("N", "strut force = the strand's tension")
    curvature_nominal: float = quantity("1_per_m", "end rotations / (L/2)")
    curvature: float = quantity("1_per_m", "core curvature over the measuring zone")
    end_displacement: float = quantity("m", "displacement of the free end along its axis")

    def progress(self) -> str:
        """The measure a progress line shows."""
        return f"κ = {self.curvature:7.4f} 1/m"


@dataclass(frozen=True)
class ZoneBending:
    """Moment–curvature measures of the zone: curvature, section moments (about b = e_z × d) at
    five sections (zone start, quarter, middle, three quarters, end), the reaction couples at the
    two ends, and the section's axial force along the core tangent at mid-zone."""

    curvature_nominal: float = quantity("1_per_m")
    curvature: float = quantity("1_per_m")
    moment_zone_start: float = quantity("Nm")
    moment_zone_quarter: float = quantity("Nm")
    moment_zone_middle: float = quantity("Nm")
    moment_zone_three_quarters: float = quantity("Nm")
    moment_zone_end: float = quantity("Nm")
    moment_end_reaction_0: float = quantity("Nm", "couple at z = 0")
    moment_end_reaction_L: float = quantity("Nm", "couple at z = L")
    axial_force: float = quantity("N")

    @property
    def section_moments(self) -> Array:
        return np.array(
            [
                self.moment_zone_start,
                self.moment_zone_quarter,
                self.moment_zone_middle,
                self.moment_zone_three_quarters,
                self.moment_zone_end,
            ]
        )


class UniformBendingTest(TestSetup):
    """A strand of ``model`` under tension T (a core strut) bent by end rotations ±κ_n L/2.

    Args:
        model: the strand.
        zone: length of the central measuring zone, m (default: 40 % of the length).
        direction: bending direction d: a positive curvature stretches the fibre on the +d side
            (φ = +90°), as a positive saddle load does at midspan.
        link_stiffness: penalty of the rigid-end links, N/m.
    """

    parameters = ("tension", "curvature")
    units = {"tension": "N", "curvature": "1_per_m"}
    cycle_parameter = "curvature"
    state_type = UniformBendingState
    bending_type = ZoneBending

    def __init__(
        self,
        model: StrandModel,
        zone: float | None = None,
        direction: npt.ArrayLike = (1.0, 0.0, 0.0),
        link_stiffness: float = 1e11,
    ):
        self.model = model
        g, V, i2b = model.geometry, model.V, model.i2b  # i2b: −1 where a point is not local
        L = g.length
        self.zone = 0.4 * L if zone is None else zone
        if not 0 < self.zone < L:
            raise ValueError(f"the measuring zone ({self.zone} m) must be shorter than the strand")
        self.direction = np.asarray(direction, float) / np.linalg.norm(direction)
        self.axis = np.cross([0.0, 0.0, 1.0], self.direction)  # b: rotation axis of bending
        self._curvature = 0.0

        # end z = 0: every dof prescribed (rigid rotation about the core's end point)
        self.ends0 = model.wire_ends(0)
        self.ends1 = model.wire_ends(1)
        self._bc0 = fem.Function(V)
        blocks0 = fem.locate_dofs_topological(V, 0, model.end_vertices(0))
        self._local0 = np.flatnonzero(i2b[self.ends0] >= 0)  # the end's points on this rank
        self._blocks0 = i2b[self.ends0[self._local0]]
        assert set(blocks0) == set(self._blocks0)
        bcs = [fem.dirichletbc(self._bc0, blocks0)]
        # end z = L: rotations prescribed, translations tied to the pilot (the core's end)
        vertices1 = model.end_vertices(1)
        self._theta1 = [fem.Constant(model.cmesh.mesh, 0.0) for _ in range(3)]
        for k in range(3):
            Vk = V.sub(3 + k)
            dofs = fem.locate_dofs_topological(Vk, 0, vertices1)
            bcs.append(fem.dirichletbc(self._theta1[k], dofs, Vk))
        self.bcs = bcs
        self.pilot, self.links, self._link_rows = pilot_links(
            model, self.ends1, link_stiffness, (0, 1, 2)
        )
        self._link_offset = np.zeros((len(self.ends1) - 1, 3))  # every link's, all ranks
        core = model.core_points()
        segments = np.column_stack([core[:-1], core[1:]])
        mine = model.owned_rows(segments, "core strut segments")
        self.strut = CoreStrut(i2b[segments[mine]], np.diff(g.points[core], axis=0)[mine])
        self.terms = [self.links, self.strut]
        #: a core that touches no wire, held on its first layer's axis (``centring``); None else
        self.centring: CoreCentring | None = None
        if first_layer_lift(g.cable, model.contact_settings.first_layer) > 0:
            rings = ring_centres(g)
            mine = model.owned_rows(rings.stencils, "core centring springs")
            self.centring = CoreCentring(
                i2b[rings.stencils[mine]],
                rings.weights[mine],
                CENTRING_STIFFNESS * rings.length[mine],
            )
            self.terms.append(self.centring)
        # the measuring zone: core points at its ends, section heights
        zc = g.points[core, 2]
        a, b = L / 2 - self.zone / 2, L / 2 + self.zone / 2
        self._zone_core = core[(zc >= a - 1e-12) & (zc <= b + 1e-12)]
        self.sections = np.linspace(a, b, 5)
        self._section_core = core[np.argmin(np.abs(zc - self.sections[2]))]

    # -- loads -------------------------------------------------------------------------------------
    def set(self, name: str, value: float) -> None:
        self.check_parameter(name)
        if name == "tension":
            self.strut.force = value
            return
        self._curvature = value
        g = self.model.geometry
        half = 0.5 * value * g.length
        theta0, theta1 = half * self.axis, -half * self.axis
        # end z = 0: u = (R(θ0) − I) X about the core's end point (the origin of the section)
        X = g.points[self.ends0[self._local0]] - g.points[self.ends0[0]]
        R0 = rotation_matrix(theta0[None])[0]
        values = self._bc0.x.array.reshape(-1, 6)
        values[self._blocks0, :3] = X @ (R0 - np.eye(3)).T
        values[self._blocks0, 3:] = theta0
        # end z = L: rotations, and the wire ends' offsets from the pilot
        for k in range(3):
            self._theta1[k].value = theta1[k]
        R1 = rotation_matrix(theta1[None])[0]
        Y = g.points[self.ends1[1:]] - g.points[self.ends1[0]]
        self._link_offset = Y @ (R1 - np.eye(3)).T
        self.links.offset = self._link_offset[self._link_rows]

    def get(self, name: str) -> float:
        self.check_parameter(name)
        return self.strut.force if name == "tension" else self._curvature

    # -- measures ----------------------------------------------------------------------------------
    @property
    def measuring_zone(self) -> tuple[float, float]:
        return (float(self.sections[0]), float(self.sections[-1]))

    def _core_tangents(self, points: npt.NDArray[np.int64]) -> Array:
        theta = self.model.node_values()[points, 3:]
        return rotation_matrix(theta) @ np.array([0.0, 0.0, 1.0])

    def zone_curvature(self) -> float:
        """Rotation of the core's tangent between the zone's ends, in the bending plane, over the
        core's current arc length there (1/m); positive when the +d fibre is stretched."""
        ends = self._zone_core[[0, -1]]
        t = self._core_tangents(ends)
        beta = np.arctan2(t @ self.direction, t[:, 2])
        x = self.model.positions()[self._zone_core]
        arc = np.linalg.norm(np.diff(x, axis=0), axis=1).sum()
        return float(-(beta[1] - beta[0]) / arc)

    def end_displacement(self) -> float:
        """Displacement of the free end's pilot along the end section's current axis, m."""
        t = self._core_tangents(self.ends1[:1])[0]
        return float(self.model.node_values()[self.pilot, :3] @ t)

    def state(self) -> UniformBendingState:
        return UniformBendingState(
            self.strut.force, self._curvature, self.zone_curvature(), self.end_displacement()
        )

    def end_reactions(self, residual: Array) -> tuple[float, float]:
        """Reaction couples (N m, about b; positive when they bend the +d fibre into tension) at
        z = 0 and z = L, from the unconstrained residual in the geometry's point order
        (``NonlinearProblem.unconstrained_residual`` through ``StrandModel.gather_nodes``).
        Each end section is a rigid body: M = Σ_j (x_j − x_core) × r_u,j + r_θ,j over its wire
        ends, where at z = L the forces r_u are those of the wires alone (the links' share, which
        holds the free end's translations, is taken out)."""
        u = self.model.node_values()[:, :3]
        x = self.model.geometry.points + u

        def couple(ends, r):
            lever = x[ends] - x[ends[0]]
            return (np.cross(lever, r[:, :3]) + r[:, 3:]).sum(axis=0)

        r1 = residual[self.ends1].copy()
        # the links' forces on the wire ends, k (u_j − u_pilot − offset_j) (PenaltyLinks)
        f_links = self.links.k * (u[self.ends1[1:]] - u[self.ends1[0]] - self._link_offset)
        r1[1:, :3] -= f_links  # the link on wire end j acts on it
        r1[0, :3] -= -f_links.sum(axis=0)  # and the opposite on the pilot
        m0 = couple(self.ends0, residual[self.ends0])
        m1 = couple(self.ends1, r1)
        return float(m0 @ self.axis), float(-m1 @ self.axis)

    def moment_curvature(self, cells: CellResults, residual: Array) -> ZoneBending:
        resultants = [section_resultants(self.model, cells, z) for z in self.sections]
        moments = [-float(M @ self.axis) for M, _ in resultants]
        t_mid = self._core_tangents(np.array([self._section_core]))[0]
        axial = float(resultants[2][1] @ t_mid)  # the middle section, along the core's tangent
        m0, m1 = self.end_reactions(residual)
        return ZoneBending(self._curvature, self.zone_curvature(), *moments, m0, m1, axial)
