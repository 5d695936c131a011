"""The seed paper's test: a strand under end tension, bent by a saddle load at midspan.

Set-up (the project's choices where the seed paper is silent): end z = 0 clamped; end z = L a
rigid section that keeps all wire ends in one plane, free to move axially and held against every
rotation; the tension is a force on that section (a pilot node, the core's end, tied to the other
wire ends by stiff penalty links on u_z); the lateral load P is a saddle at midspan: inward radial
forces on the outer-layer nodes of the pressed face, weighted so that they sum to exactly P along
the load direction. It measures the midspan deflection, the end's axial displacement, and the
moment and curvature of the midspan section. Under displacement control (``control``, a
``ControlledDisplacement``) its cycle parameter prescribes the core's lateral displacement at a
height (midspan, or Y_b's point near the clamp) and every step finds the saddle load that gives
it (``strand.solver.displacement_control``). Units: m, N, N m.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from dolfinx import fem

from ..analytical.fibre import bending_stiffness_bounds
from ..beam.records import quantity
from ..model.cell_results import CellResults, section_resultants
from ..model.model import StrandModel
from ..solver.displacement_control import DisplacementControl
from .base import TestSetup, owned_load, pilot_links

__all__ = [
    "SaddleTest",
    "SaddleState",
    "SaddleControlState",
    "MidspanBending",
    "ControlledDisplacement",
    "saddle_weights",
    "beam_compliance",
]

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
class SaddleControlState:
    """Loads and displacements of the saddle test under displacement control at one state."""

    tension: float = quantity("N", "end force")
    lateral: float = quantity("N", "saddle load P that the control found")
    deflection: float = quantity("m", "core's lateral displacement at midspan")
    end_displacement: float = quantity("m", "axial displacement of the end section")
    measured: float = quantity("m", "core's lateral displacement at the controlled point")
    prescribed: float = quantity("m", "the displacement prescribed there")
    solves: int = quantity("", "solves the step took to find P (secant)")

    def progress(self) -> str:
        """The measure a progress line shows: the load found."""
        return f"P = {self.lateral / 1e3:+7.3f} kN, {self.solves} solves"


@dataclass(frozen=True)
class ControlledDisplacement:
    """What the saddle load imposes under displacement control (``SaddleTest(control=...)``).

    Attributes:
        parameter: the cycle's load parameter that prescribes it ("deflection", "yb").
        height: z of the core's point whose displacement along the load direction is prescribed
            (m; linear between the core's nodes); None: midspan, the core's node that the
            deflection is read at.
        per_unit: the prescribed displacement (m) per unit of the parameter: 1, or ½ when the
            parameter is a peak-to-peak amplitude (Y_b).
        tolerance: the largest distance between measured and prescribed displacements, m.
    """

    parameter: str
    height: float | None = None
    per_unit: float = 1.0
    tolerance: float = 1e-7


def beam_compliance(ei: float, tension: float, length: float, z: float) -> float:
    """Displacement (m) at ``z`` ≤ L/2 per newton of midspan load of the clamped–clamped beam
    of bending stiffness ``ei`` (N m²) under ``tension`` (N):
    w(z)/P = [z − sinh(pz)/p + tanh(pa/2)(cosh(pz) − 1)/p] / 2T, p = √(T/EI), a = L/2 (at
    z = a: docs/theory.md's midspan deflection); z²(3L − 4z)/48EI without tension."""
    a = length / 2
    p = np.sqrt(tension / ei)
    if p * a < 1e-3:
        return z**2 * (3 * length - 4 * z) / (48 * ei)
    return float(
        (z - (np.sinh(p * z) - np.tanh(p * a / 2) * (np.cosh(p * z) - 1)) / p) / (2 * tension)
    )


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
        control: under displacement control, the displacement the cycle parameter prescribes
            (the saddle load is then found at every step); None: the load is prescribed.
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
        direction: npt.ArrayLike = (1.0, 0.0, 0.0),
        link_stiffness: float = 1e11,
        control: ControlledDisplacement | None = None,
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
        self.control = control
        self._driver: DisplacementControl | None = None
        if control is not None:
            name = control.parameter
            self.parameters = (*self.parameters, name)
            self.units = {**self.units, name: "m"}
            self.cycle_parameter, self.state_type = name, SaddleControlState
            self._prescribed = 0.0  # the parameter's value
            self._measuring = self._core_point(control.height)

    def _core_point(self, height: float | None) -> tuple[npt.NDArray[np.intp], Array]:
        """The core's nodes and weights that interpolate its displacement at ``height`` (m;
        None: the midspan node)."""
        if height is None:
            return np.array([self._mid_core]), np.ones(1)
        core = self.model.core_points()
        z = self.model.geometry.points[core, 2]
        order = np.argsort(z)
        core, z = core[order], z[order]
        j = int(np.clip(np.searchsorted(z, height), 1, len(core) - 1))
        t = (height - z[j - 1]) / (z[j] - z[j - 1])
        return core[j - 1 : j + 1], np.array([1 - t, t])

    # -- loads -------------------------------------------------------------------------------------
    def set(self, name: str, value: float) -> None:
        self.check_parameter(name)
        if name == "tension":
            self.tension_load.factor = value
        elif self.control is not None and name == self.control.parameter:
            self._prescribed = value
        else:
            self.saddles[0].factor = max(value, 0.0)
            self.saddles[1].factor = min(value, 0.0)

    def get(self, name: str) -> float:
        self.check_parameter(name)
        if name == "tension":
            return self.tension_load.factor
        if self.control is not None and name == self.control.parameter:
            return self._prescribed
        return self.saddles[0].factor + self.saddles[1].factor

    def driver(self, solver, parameter: str):
        """Under displacement control, for a stage of the controlled parameter: the
        ``DisplacementControl`` of the saddle load on ``solver``, started from the current
        state (a new one from the unloaded saddle, so that a sweep's members are separate
        runs); ``solver`` itself otherwise."""
        control = self.control
        if control is None or parameter != control.parameter:
            return solver
        unloaded = self.lateral == 0.0 and self._prescribed == 0.0
        if self._driver is None or self._driver.solver is not solver or unloaded:
            self._driver = DisplacementControl(
                solver,
                lambda: self.lateral,
                self.set_lateral,
                self.measured_displacement,
                lambda: self._prescribed * control.per_unit,
                self.reference_stiffness,
                tolerance=control.tolerance,
            )
        else:
            self._driver.start()
        return self._driver

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

    def measured_displacement(self) -> float:
        """Under displacement control: the core's displacement along ``direction`` at the
        controlled height, m."""
        nodes, weights = self._measuring
        return float(weights @ (self.model.node_values()[nodes, :3] @ self.direction))

    def reference_stiffness(self) -> float:
        """Load per displacement at the controlled height (N/m) of the clamped–clamped beam
        with every wire slipping (EI_min) under the current tension: the control's first
        guess, on the soft side (a first load that falls short is gentle on Newton)."""
        g = self.model.geometry
        ei_min = bending_stiffness_bounds(g.cable)[0]
        height = self.control.height
        z = g.length / 2 if height is None else height
        return 1.0 / beam_compliance(ei_min, self.tension, g.length, z)

    def state(self) -> SaddleState | SaddleControlState:
        loads = (self.tension, self.lateral, self.midspan_deflection(), self.end_displacement())
        if self.control is None:
            return SaddleState(*loads)
        solves = self._driver.solves if self._driver is not None else 0
        return SaddleControlState(
            *loads, self.measured_displacement(), self._prescribed * self.control.per_unit, solves
        )

    def moment_curvature(
        self, cells: CellResults, residual: Array | None = None, fit_half_length: float = 0.015
    ) -> MidspanBending:
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
