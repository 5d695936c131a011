"""The seed paper's test: a strand under end tension, bent by a saddle load at midspan.

Set-up (the project's choices where the seed paper is silent): end z = 0 clamped; end z = L a
rigid section that keeps all wire ends in one plane, free to move axially and held against every
rotation; the tension is a force on that section (a pilot node, the core's end, tied to the other
wire ends by stiff penalty links on u_z); the lateral load P is a saddle at midspan: inward radial
forces on the outer-layer nodes of the pressed face, weighted so that they sum to exactly P along
the load direction. It measures the midspan deflection, the end's axial displacement, and the
moment and curvature of the midspan section. Units: m, N, N m.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from dolfinx import fem

from ..model import StrandModel
from ..post import section_resultants
from .base import TestSetup, owned_load, pilot_links, quantity

__all__ = ["SaddleTest", "SaddleState", "MidspanBending", "saddle_weights"]

Array = npt.NDArray[np.float64]


def saddle_weights(points: Array, direction: Array) -> tuple[npt.NDArray[np.intp], Array]:
    """Nodes and nodal force vectors (per unit load) of a saddle pressing along ``direction``.

    ``points`` (n, 3) are candidate outer-layer nodes. The pressed ones are those on the face the
    load comes from (inward radial direction e_i with cosψ_i = e_i·direction > 0). Their forces
    w_i e_i use w_i = cosψ_i (α + β sinψ_i), with α, β such that Σ w_i e_i = direction exactly:
    no net force across the load direction.
    """
    d = np.asarray(direction, float)
    d = d / np.linalg.norm(d)
    radial = points.copy()
    radial[:, 2] = 0.0
    inward = -radial / np.linalg.norm(radial, axis=1)[:, None]
    side = np.cross([0.0, 0.0, 1.0], d)
    cos_psi, sin_psi = inward @ d, inward @ side
    pressed = np.flatnonzero(cos_psi > 1e-12)
    if len(pressed) < 2:
        raise ValueError(
            "the saddle covers fewer than two outer-layer nodes: lengthen it ([load] "
            "saddle_length) or refine the mesh ([mesh] h_max)"
        )
    c, s = cos_psi[pressed], sin_psi[pressed]
    A = np.array([[np.sum(c * c), np.sum(c * c * s)], [np.sum(c * s), np.sum(c * s * s)]])
    alpha, beta = np.linalg.solve(A, [1.0, 0.0])
    weights = c * (alpha + beta * s)
    return pressed, weights[:, None] * inward[pressed]


@dataclass(frozen=True)
class SaddleState:
    """Loads and displacements of the saddle test at one state."""

    tension: float = quantity("N", "end force")
    lateral: float = quantity("N", "saddle load P along the load direction")
    deflection: float = quantity("m", "core's lateral displacement at midspan")
    end_displacement: float = quantity("m", "axial displacement of the end section")

    def progress(self) -> str:
        """The measure a progress line shows."""
        return f"δ = {1e3 * self.deflection:7.2f} mm"


@dataclass(frozen=True)
class MidspanBending:
    """Moment and curvature of the midspan section (under the saddle: indicative only)."""

    lateral: float = quantity("N")
    curvature: float = quantity("1_per_m")
    moment: float = quantity("Nm")
    axial_sum: float = quantity("N", "Σ N_z over the section: equals the tension")


class SaddleTest(TestSetup):
    """A strand of ``model`` under end tension and a midspan saddle load.

    Args:
        model: the strand.
        saddle_length: axial length of the saddle centred at midspan, m.
        direction: direction of a positive lateral load (across the strand axis).
        link_stiffness: penalty of the rigid-end links, N/m.
    """

    parameters = ("tension", "lateral")
    units = {"tension": "N", "lateral": "N"}
    cycle_parameter = "lateral"
    state_type = SaddleState
    bending_type = MidspanBending

    def __init__(
        self,
        model: StrandModel,
        saddle_length: float = 0.02,
        direction=(1.0, 0.0, 0.0),
        link_stiffness: float = 1e11,
    ):
        self.model = model
        geometry, V = model.geometry, model.V
        L = geometry.length
        self.direction = np.asarray(direction, float) / np.linalg.norm(direction)

        # ends: z = 0 clamped; z = L: only u_z free, tied to the pilot (the core's end node)
        start, end = model.end_vertices(0), model.end_vertices(1)
        bcs = [fem.dirichletbc(np.zeros(6), fem.locate_dofs_topological(V, 0, start), V)]
        for i in (0, 1, 3, 4, 5):
            Vi = V.sub(i)
            bcs.append(fem.dirichletbc(0.0, fem.locate_dofs_topological(Vi, 0, end), Vi))
        self.bcs = bcs
        ends = model.wire_ends(1)
        self.pilot, self.links, _ = pilot_links(model, ends, link_stiffness)

        # loads: tension on the pilot, one saddle for each sign of P
        self.tension_load = owned_load(model, [self.pilot], [[0, 0, 1.0, 0, 0, 0]])
        outer_layer = len(geometry.cable.layers) - 1
        outer = np.flatnonzero(geometry.wire_layer[geometry.point_wire] == outer_layer)
        near = outer[np.abs(geometry.points[outer, 2] - L / 2) <= saddle_length / 2 + 1e-12]
        self.saddles = []
        for sign in (1.0, -1.0):
            idx, forces = saddle_weights(geometry.points[near], sign * self.direction)
            values = np.zeros((len(idx), 6))
            values[:, :3] = sign * forces  # per unit signed load P
            self.saddles.append(owned_load(model, near[idx], values))
        self.terms = [self.links, self.tension_load, *self.saddles]
        core = model.core_points()
        self._mid_core = core[np.argmin(np.abs(geometry.points[core, 2] - L / 2))]

    # -- loads -------------------------------------------------------------------------------------
    def set(self, name: str, value: float) -> None:
        self.check_parameter(name)
        if name == "tension":
            self.tension_load.factor = value
        else:
            self.saddles[0].factor = max(value, 0.0)
            self.saddles[1].factor = min(value, 0.0)

    def get(self, name: str) -> float:
        self.check_parameter(name)
        if name == "tension":
            return self.tension_load.factor
        return self.saddles[0].factor + self.saddles[1].factor

    def set_tension(self, T: float) -> None:
        """Axial force on the end section, N."""
        self.set("tension", T)

    def set_lateral(self, P: float) -> None:
        """Lateral saddle load at midspan, N (signed along ``direction``)."""
        self.set("lateral", P)

    @property
    def tension(self) -> float:
        return self.get("tension")

    @property
    def lateral(self) -> float:
        return self.get("lateral")

    # -- measures ----------------------------------------------------------------------------------
    def end_displacement(self) -> float:
        """Axial displacement of the end section (the pilot's u_z), m."""
        return float(self.model.node_values()[self.pilot, 2])

    def midspan_deflection(self) -> float:
        """Lateral displacement of the core at midspan along ``direction``, m."""
        return float(self.model.node_values()[self._mid_core, :3] @ self.direction)

    def state(self) -> SaddleState:
        return SaddleState(
            self.tension, self.lateral, self.midspan_deflection(), self.end_displacement()
        )

    def moment_curvature(self, cells, residual=None, fit_half_length=0.015) -> MidspanBending:
        """Bending moment (N m) of the cross-section at z = L/2 and curvature (1/m) of the core.

        M = Σ_wires [(x_w − x_core) × n_w + m_w] · (e_z × d), from the elements that the section
        cuts; κ = −u_d″ from a quadratic fit of the core's lateral displacement over
        ±``fit_half_length``. Both change sign so that a positive load gives positive values.
        """
        model = self.model
        g = model.geometry
        L = g.length
        b = np.cross([0.0, 0.0, 1.0], self.direction)
        M_vec, force = section_resultants(model, cells, L / 2)
        idx = model.core_points()
        zc = g.points[idx, 2] - L / 2
        near = np.abs(zc) <= fit_half_length
        u = model.node_values()[idx[near], :3] @ self.direction
        c2 = np.polyfit(zc[near], u, 2)[0]
        return MidspanBending(self.lateral, -2.0 * c2, -float(M_vec @ b), float(force[2]))
