"""Bending at a fairlead: the uniform bending test whose tension also cycles (the set-up of the
``fairlead`` kind, ``strand.app.kinds.fairlead``).

A mooring line passes over a fairlead sheave or through a bend stiffener: there it is bent to the
curvature of the sheave (κ = 1/R of the strand axis) or of the stiffener, while its tension swings
with the waves. The set-up is ``UniformBendingTest``'s: the ends turn by ±κ_n L/2 (the curvature),
and a strut along the core carries the strand's tension as a follower compression, so that the
strand is loaded by the end couples alone and its section moment is uniform, whatever the tension.
Here the strut force is the mean ``tension`` plus a ``tension_swing`` (the parameters of the
``tension_cycle`` kind), and the nominal curvature the held ``curvature`` plus a
``curvature_swing``, so that either the tension or the curvature can be cycled about its mean
while the other is held. What it leaves out: the sheave's contact pressure on the strand's outer wires (the strut
applies the equilibrating transverse load T κ per unit length at the core instead). Units: m, N,
N m, 1/m.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy.typing as npt

from ..beam.records import quantity
from ..model.model import StrandModel
from .bending import UniformBendingTest

__all__ = ["FairleadTest", "FairleadState"]


@dataclass(frozen=True, kw_only=True)
class FairleadState:
    """Loads and measures of the fairlead test at one state."""

    tension: float = quantity("N", "mean tension")
    tension_swing: float = quantity("N", "strand tension less the mean")
    end_force: float = quantity("N", "the strand's tension: tension + tension_swing")
    curvature_held: float = quantity("1_per_m", "the held (mean) nominal curvature")
    curvature_swing: float = quantity("1_per_m", "nominal curvature less the held one")
    curvature_nominal: float = quantity("1_per_m", "end rotations / (L/2): held + swing")
    curvature: float = quantity("1_per_m", "core curvature over the measuring zone")
    end_displacement: float = quantity("m", "displacement of the free end along its axis")

    def progress(self) -> str:
        """The measure a progress line shows."""
        return f"κ = {self.curvature:7.4f} 1/m"


class FairleadTest(UniformBendingTest):
    """The uniform bending test (``UniformBendingTest``: end rotations, core strut) whose strut
    force, the strand's tension, is ``tension`` + ``tension_swing`` (N), and whose nominal
    curvature κ_n (end rotations ±κ_n L/2) is ``curvature`` + ``curvature_swing`` (1/m). Either
    swing may be cycled while the rest is held: ``cycle_parameter`` names it. Other arguments:
    those of ``UniformBendingTest`` (``zone``, ``direction``, ``link_stiffness``)."""

    parameters = ("tension", "curvature", "tension_swing", "curvature_swing")
    units = {
        "tension": "N",
        "curvature": "1_per_m",
        "tension_swing": "N",
        "curvature_swing": "1_per_m",
    }
    cycle_parameter = "tension_swing"
    state_type = FairleadState

    def __init__(
        self,
        model: StrandModel,
        zone: float | None = None,
        direction: npt.ArrayLike = (1.0, 0.0, 0.0),
        *,
        cycle_parameter: str = "tension_swing",
        link_stiffness: float = 1e11,
    ):
        super().__init__(model, zone=zone, direction=direction, link_stiffness=link_stiffness)
        if cycle_parameter not in ("tension_swing", "curvature_swing"):
            raise ValueError(
                f"cycle_parameter {cycle_parameter!r}: tension_swing or curvature_swing"
            )
        self.cycle_parameter = cycle_parameter
        self.loads = dict.fromkeys(self.parameters, 0.0)

    def set(self, name: str, value: float) -> None:
        self.check_parameter(name)
        self.loads[name] = value
        if name in ("tension", "tension_swing"):
            self.strut.force = self.loads["tension"] + self.loads["tension_swing"]
        else:
            super().set("curvature", self.loads["curvature"] + self.loads["curvature_swing"])

    def get(self, name: str) -> float:
        self.check_parameter(name)
        return self.loads[name]

    def state(self) -> FairleadState:
        loads = self.loads
        return FairleadState(
            tension=loads["tension"],
            tension_swing=loads["tension_swing"],
            end_force=self.strut.force,
            curvature_held=loads["curvature"],
            curvature_swing=loads["curvature_swing"],
            curvature_nominal=self._curvature,
            curvature=self.zone_curvature(),
            end_displacement=self.end_displacement(),
        )
