"""The tension-cycle test: the saddle test whose end force is a mean tension plus a swing, with
an optional saddle load held at midspan (the set-up of the ``tension_cycle`` kind,
``strand.app.kinds.tension_cycle``). Units: m, N, N m.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from ..beam.records import quantity
from ..model.cell_results import section_resultants
from ..model.model import StrandModel
from .saddle import SaddleTest

__all__ = ["TensionCycleTest", "TensionCycleState", "TensionSection"]


@dataclass(frozen=True)
class TensionCycleState:
    """Loads and displacements of the tension cycle at one state."""

    tension: float = quantity("N", "mean end force")
    tension_swing: float = quantity("N", "end force less the mean tension")
    end_force: float = quantity("N", "end force: tension + tension_swing")
    lateral: float = quantity("N", "saddle load held at midspan")
    deflection: float = quantity("m", "core's lateral displacement at midspan")
    end_displacement: float = quantity("m", "axial displacement of the end section")

    def progress(self) -> str:
        """The measure a progress line shows."""
        return f"u = {1e6 * self.end_displacement:6.1f} µm"


@dataclass(frozen=True)
class TensionSection:
    """Resultants of the midspan section z = L/2 during the tension cycle: of the wires' full
    section forces n (axial and shear) and moments over the elements the section cuts. The saddle
    load is lateral, so equilibrium of the half strand makes ``axial_sum`` the end force, up to
    the axial forces that same-layer contact pairs (a node against a neighbour's segment) carry
    across the section where their nodes lie on both sides of it (none without same-layer
    contact: ``tests/test_tension_cycle.py``)."""

    tension_swing: float = quantity("N")
    end_force: float = quantity("N")
    axial_sum: float = quantity("N", "z component of Σ n over the section: the end force")
    moment: float = quantity("Nm", "bending moment along the saddle's moment axis")


class TensionCycleTest(SaddleTest):
    """The saddle test whose end force is ``tension`` + ``tension_swing`` (N), the saddle load
    ``lateral`` (N) held while the swing cycles."""

    parameters = ("tension", "lateral", "tension_swing")
    units = {"tension": "N", "lateral": "N", "tension_swing": "N"}
    cycle_parameter = "tension_swing"
    state_type = TensionCycleState
    bending_type = TensionSection

    def __init__(
        self,
        model: StrandModel,
        saddle_length: float = 0.02,
        direction: npt.ArrayLike = (1.0, 0.0, 0.0),
    ):
        super().__init__(model, saddle_length=saddle_length, direction=direction)
        self._tension = self._swing = 0.0

    def set(self, name: str, value: float) -> None:
        self.check_parameter(name)
        if name == "lateral":
            super().set(name, value)
            return
        if name == "tension":
            self._tension = value
        else:
            self._swing = value
        self.tension_load.factor = self._tension + self._swing

    def get(self, name: str) -> float:
        self.check_parameter(name)
        if name == "lateral":
            return super().get(name)
        return self._tension if name == "tension" else self._swing

    @property
    def tension(self) -> float:
        return self._tension

    def state(self) -> TensionCycleState:
        return TensionCycleState(
            self._tension,
            self._swing,
            self._tension + self._swing,
            self.lateral,
            self.midspan_deflection(),
            self.end_displacement(),
        )

    def moment_curvature(self, cells, residual=None) -> TensionSection:
        """The midspan section's axial resultant Σ n_z (N, axial and shear forces) and bending
        moment (N m, about the axis e_z × ``direction``)."""
        L = self.model.geometry.length
        moment, force = section_resultants(self.model, cells, L / 2)
        b = np.cross([0.0, 0.0, 1.0], self.direction)
        return TensionSection(
            self._swing, self._tension + self._swing, float(force[2]), -float(moment @ b)
        )
