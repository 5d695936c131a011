"""What every test set-up has: supports (Dirichlet conditions), loads and ties (pair terms), named
load parameters, and what it measures, as typed records.

A set-up is built on a ``StrandModel`` and never owns the unknowns: it hands its conditions and
terms to the solver and reads the model's state. Its ``state()`` is a frozen dataclass whose fields
carry their unit in ``metadata["unit"]`` (``strand.beam.records``), so that recorders write any
set-up's records as CSV columns named ``<field>_<unit>``. Units: m, N, N m, rad.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from ..solver import NodalLoad

if TYPE_CHECKING:
    from ..model.cell_results import CellResults

Array = npt.NDArray[np.float64]

__all__ = ["TestSetup", "PenaltyLinks", "pilot_links", "owned_load"]


class TestSetup(ABC):
    """Boundary conditions, loads and measurements of a strand test.

    Attributes:
        parameters: names of the load parameters, e.g. ("tension", "lateral").
        units: each parameter's unit as written in column names ("N", "1_per_m").
        cycle_parameter: the one a load programme cycles after tensioning.
        state_type, bending_type: the record types of ``state()`` and ``moment_curvature()``.
        direction: the unit vector across the strand's axis that its loads bend it towards
            (the neutral axis of the cell results is e_z × ``direction``).
        bcs: Dirichlet conditions on the model's space.
        terms: pair terms (ties, nodal loads) for the solver.
    """

    parameters: tuple[str, ...] = ()
    units: dict[str, str] = {}
    cycle_parameter: str = ""
    state_type: type
    bending_type: type
    direction: npt.NDArray[np.float64]
    bcs: list
    terms: list

    @abstractmethod
    def set(self, name: str, value: float) -> None:
        """Set load parameter ``name`` (its SI unit)."""

    @abstractmethod
    def get(self, name: str) -> float:
        """Current value of load parameter ``name``."""

    @abstractmethod
    def state(self):
        """The set-up's measures at the current state (a frozen dataclass of quantities, with a
        ``progress()`` method giving the measure a progress line shows)."""

    @abstractmethod
    def moment_curvature(self, cells: CellResults, residual: Array):
        """The bending measures at the current state (a frozen dataclass), given the cell
        results (``cell_results.cell_results``) and the unconstrained residual (n_blocks, 6), whose
        values at supported dofs are the reactions."""

    @property
    def measuring_zone(self) -> tuple[float, float]:
        """(z_min, z_max) of initial heights where the set-up measures (m): the middle half of
        the length unless the set-up says otherwise."""
        L = self.model.geometry.length
        return (0.25 * L, 0.75 * L)

    def driver(self, solver, parameter: str):
        """What a load programme's stage of ``parameter`` steps: ``solver`` itself, or a
        stand-in whose solves also find a load the set-up controls (``SaddleTest`` under
        displacement control)."""
        return solver

    def check_parameter(self, name: str) -> None:
        if name not in self.parameters:
            raise KeyError(
                f"{type(self).__name__} has no load parameter {name!r}; "
                f"it has {', '.join(self.parameters)}"
            )


class PenaltyLinks:
    """Penalty ties u_c(b) − u_c(a) = c_p on displacement components c between node pairs (a, b).

    A ``PairTerms`` with constant 12×12 blocks: residual k(u_b − u_a − c)·(−1, +1) on each tied
    component. ``offset`` (P, n_components) is a prescribed relative displacement (m), zero
    unless set (a rigid end section that rotates moves its wire ends relative to its pilot).

    Args:
        pairs: (P, 2) local dof blocks (a, b).
        stiffness: N/m.
        components: displacement components tied (0, 1, 2 = x, y, z).
    """

    def __init__(self, pairs: npt.ArrayLike, stiffness: float, components: Sequence[int] = (2,)):
        self.stencils = np.asarray(pairs, dtype=np.int32).reshape(-1, 2)
        self.k = stiffness
        self.components = np.asarray(components, dtype=np.intp).reshape(-1)
        self.offset = np.zeros((len(self.stencils), len(self.components)))
        K = np.zeros((12, 12))
        for c in self.components:
            i, j = c, 6 + c
            K[i, i] = K[j, j] = stiffness
            K[i, j] = K[j, i] = -stiffness
        self._K = np.broadcast_to(K, (len(self.stencils), 12, 12))

    def evaluate(self, w: Array, jacobian: bool) -> tuple[Array, Array | None]:
        c = self.components
        du = w[self.stencils[:, 1]][:, c] - w[self.stencils[:, 0]][:, c] - self.offset
        f = np.zeros((len(du), 12))
        f[:, c] = -self.k * du
        f[:, 6 + c] = self.k * du
        return f, (self._K.copy() if jacobian else None)

    def commit(self) -> None:
        pass

    def rollback(self) -> None:
        pass


def pilot_links(
    model, ends: npt.ArrayLike, stiffness: float, components=(2,)
) -> tuple[int, PenaltyLinks, npt.NDArray[np.intp]]:
    """A rigid end section: its first wire end (the core's) is the pilot, every other wire end is
    tied to it on ``components``. Returns the pilot's input point, the links this rank evaluates
    (all of them on one rank; on several, the pilot's owner's: ``StrandModel.owned_rows``) and
    their rows among ``ends[1:]``."""
    ends = np.asarray(ends)
    points = np.column_stack([np.full(len(ends) - 1, ends[0]), ends[1:]])
    rows = model.owned_rows(points, "end-section links")
    return int(ends[0]), PenaltyLinks(model.i2b[points[rows]], stiffness, components), rows


def owned_load(model, points: npt.ArrayLike, values: npt.ArrayLike) -> NodalLoad:
    """Nodal forces/moments ``values`` (n, 6) on the input ``points`` (n,) that this rank owns
    (each applied once over the ranks)."""
    points = np.asarray(points).reshape(-1)
    rows = model.owned_rows(points[:, None], "nodal loads")
    return NodalLoad(model.i2b[points[rows]], np.asarray(values, float).reshape(-1, 6)[rows])
