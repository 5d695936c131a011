"""Contact pairs between the nodes of any beams in one dolfinx mesh: the public contact API.

A pair joins a node a of one beam and a node b of another that touch, or may touch (at small
sliding the pair is fixed for the whole run; at large sliding it is where its contact point
starts). ``NodePairs`` holds, for pairs of one kind, all the
contact element needs and nothing of where the pairs came from:

* crossing pairs (``line=False``): two beams crossing at an angle touch at a point; the normal is
  n = ±(t_a × t_b)/‖t_a × t_b‖ (from a to b), t the beams' unit tangents;
* line pairs (``line=True``): two beams lying along each other touch along a line; each pair
  stands for a ``tributary`` length of it and its normal is the part of x_b − x_a orthogonal to
  beam a.

The initial gap is g = (x_b − x_a)·n − r_a − r_b unless given (one value or one per pair: a
negative one is an initial penetration). Tangents come from the chords x₊ − x₋ between each node's
neighbours along its beam.

Build pairs from nodes (``node_pairs``; ``strand.contact.nodes.locate_nodes`` turns points into
nodes) or let ``candidate_pairs`` (``strand.contact.candidates``) find them between two beams;
then ``contact_terms`` makes the small-sliding contact element (a ``PairTerms`` for
``strand.solver.NonlinearProblem``) with the laws of ``strand.contact.normal_laws`` and
``strand.contact.friction_laws`` (``strand.contact.windows.sliding_terms`` the large-sliding
one):

>>> pairs = candidate_pairs(V, lower, upper, 1e-3, 1e-3, reach=1e-4)      # doctest: +SKIP
>>> contact = contact_terms(pairs, PenaltyLaw(1e7), ElasticSlip(0.3, 1e-6))  # doctest: +SKIP
>>> NonlinearProblem(beam.residual(), w, bcs, terms=[contact]).solve()      # doctest: +SKIP

Nodes are local dof blocks of the beam space V (dolfinx's blocked P1 space of (u, θ)): what
``fem.locate_dofs_geometrical(V, marker)`` and ``locate_dofs_topological(V, 0, vertices)`` return.
Units: m.
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    from dolfinx import fem

from .element import ContactGroup
from .friction_laws import FrictionLaw
from .hertz import hertz_mindlin
from .kinematics import stencil_nodes
from .nodes import BeamNodes, beam_nodes
from .normal_laws import LinePenaltyLaw, NormalLaw

__all__ = [
    "ROLES",
    "NodePairs",
    "node_pairs",
    "contact_terms",
    "crossing_angle",
    "hertz_laws",
]

Array = npt.NDArray[np.float64]
Blocks = npt.NDArray[np.int32]

#: the nodes a pair knows, in order: its two nodes and their neighbours along each beam
ROLES = ("a", "b", "a-", "a+", "b-", "b+")


@dataclass(frozen=True)
class NodePairs:
    """Contact pairs of one kind: what the contact element needs, whatever built them.

    Attributes:
        nodes: (P, 6) local dof blocks of ``ROLES``: a, b, and their neighbours a−, a+, b−, b+.
        positions: (P, 6, 3) initial positions of those nodes, m.
        line: line pairs (beams along each other) rather than crossings.
        radius_a, radius_b: (P,) radii of the two beams, m.
        normal: (P, 3) initial unit normals from a to b.
        initial_gap: (P,) gap at t = 0, m (negative: penetration).
        tributary: (P,) length of contact line that a line pair stands for, m (0 for crossings).
        index: (P,) the pairs' ids for reporting (default 0..P−1).
    """

    nodes: Blocks
    positions: Array
    line: bool
    radius_a: Array
    radius_b: Array
    normal: Array
    initial_gap: Array
    tributary: Array
    index: npt.NDArray[np.intp]

    def __len__(self) -> int:
        return len(self.nodes)

    @property
    def a(self) -> Blocks:
        return self.nodes[:, 0]

    @property
    def b(self) -> Blocks:
        return self.nodes[:, 1]

    @property
    def tangents(self) -> Array:
        """(P, 2, 3) initial unit tangents at a and b: chords between their neighbours."""
        c = self.positions[:, [3, 5]] - self.positions[:, [2, 4]]
        return c / np.linalg.norm(c, axis=2)[..., None]

    @property
    def crossing_angle(self) -> Array:
        """(P,) angle between the two beams at the pair, rad, in [0, π/2]."""
        return crossing_angle(self.tangents)

    def stencil(self, normal: str) -> tuple[Blocks, Array]:
        """The nodes (P, k) and their positions (P, k, 3) that the contact normal ``normal``
        ("frozen", "neighbour", "director") reads."""
        cols = [ROLES.index(r) for r in stencil_nodes(normal, self.line)]
        return self.nodes[:, cols], self.positions[:, cols]

    def select(self, mask: npt.ArrayLike) -> NodePairs:
        """The pairs ``mask`` (boolean or indices) of these."""
        return NodePairs(
            **{
                f.name: (getattr(self, f.name) if f.name == "line" else getattr(self, f.name)[mask])
                for f in fields(self)
            }
        )


def crossing_angle(tangents) -> Array:
    """Angle (rad, in [0, π/2]) between the unit tangents (P, 2, 3) of the two beams of pairs."""
    cos = np.abs(np.einsum("pi,pi->p", tangents[:, 0], tangents[:, 1]))
    return np.arccos(np.clip(cos, 0.0, 1.0))


def _per_pair(value, n: int, name: str) -> Array:
    out = np.broadcast_to(np.asarray(value, dtype=float), (n,)).copy()
    if not np.all(np.isfinite(out)):
        raise ValueError(f"{name} must be finite numbers (m)")
    return out


def node_pairs(
    V: fem.FunctionSpace,
    a: npt.ArrayLike,
    b: npt.ArrayLike,
    radius_a: npt.ArrayLike,
    radius_b: npt.ArrayLike,
    *,
    line: bool = False,
    initial_gap: npt.ArrayLike | None = None,
    tributary: npt.ArrayLike | None = None,
    nodes: BeamNodes | None = None,
) -> NodePairs:
    """Pairs joining the nodes ``a`` of one beam and ``b`` of another (local dof blocks of ``V``).

    Args:
        radius_a, radius_b: beam radii, m (one value, or one per pair).
        line: the beams lie along each other (line contact) rather than cross.
        initial_gap: gap at t = 0 (m, one value or one per pair); default: measured,
            (x_b − x_a)·n − r_a − r_b.
        tributary: line pairs: the length of contact line each pair stands for, m; default the
            half-lengths of the cells of beam b on either side of b.
        nodes: ``beam_nodes(V)``, if already built.
    """
    nodes = nodes or beam_nodes(V)
    a = np.atleast_1d(np.asarray(a, dtype=np.int32))
    b = np.atleast_1d(np.asarray(b, dtype=np.int32))
    if a.shape != b.shape or a.ndim != 1:
        raise ValueError(f"a and b must be equal-length lists of nodes; got {a.shape}, {b.shape}")
    n = len(nodes.positions)
    if len(a) and (min(a.min(), b.min()) < 0 or max(a.max(), b.max()) >= n):
        raise ValueError(f"nodes must be local dof blocks of V, in 0..{n - 1}")
    if np.any(a == b):
        raise ValueError("a pair joins a node to itself")
    table = np.column_stack([a, b, nodes.neighbours[a], nodes.neighbours[b]]).astype(np.int32)
    return _pairs_of(
        table,
        nodes.positions[table],
        radius_a,
        radius_b,
        line,
        initial_gap,
        tributary,
        np.arange(len(a)),
    )


def _pairs_of(table, x, radius_a, radius_b, line, initial_gap, tributary, index) -> NodePairs:
    """``NodePairs`` of the node table (P, 6) (``ROLES``) whose nodes are at ``x`` (P, 6, 3)."""
    P = len(table)
    r_a, r_b = _per_pair(radius_a, P, "radius_a"), _per_pair(radius_b, P, "radius_b")
    if np.any(r_a <= 0) or np.any(r_b <= 0):
        raise ValueError("beam radii must be positive (m)")
    d = x[:, 1] - x[:, 0]
    chords = x[:, [3, 5]] - x[:, [2, 4]]
    ta, tb = np.moveaxis(chords / np.linalg.norm(chords, axis=2)[..., None], 1, 0)
    if line:
        m = d - np.einsum("pi,pi->p", d, ta)[:, None] * ta
    else:
        m = np.cross(ta, tb)
        if np.any(np.linalg.norm(m, axis=1) < 1e-3):
            raise ValueError(
                "a crossing pair joins beams that are parallel there (angle < 0.06°); "
                "use line=True for beams lying along each other"
            )
        m *= np.where(np.einsum("pi,pi->p", d, m) < 0, -1.0, 1.0)[:, None]  # from a to b
    size = np.linalg.norm(m, axis=1)
    if np.any(size == 0):
        raise ValueError("a line pair's nodes lie on beam a's axis: its normal is undefined")
    normal = m / size[:, None]
    measured = np.einsum("pi,pi->p", d, normal) - r_a - r_b
    gap = measured if initial_gap is None else _per_pair(initial_gap, P, "initial_gap")
    if tributary is None:
        tributary = 0.5 * (
            np.linalg.norm(x[:, 1] - x[:, 4], axis=1) + np.linalg.norm(x[:, 5] - x[:, 1], axis=1)
        )
    trib = _per_pair(tributary, P, "tributary") if line else np.zeros(P)
    if line and np.any(trib <= 0):
        raise ValueError("line pairs need positive tributary lengths (m)")
    return NodePairs(
        table.astype(np.int32),
        x,
        bool(line),
        r_a,
        r_b,
        normal,
        gap,
        trib,
        np.asarray(index, dtype=np.intp),
    )


def contact_terms(
    pairs: NodePairs,
    normal_law: NormalLaw,
    friction_law: FrictionLaw | None = None,
    normal: str = "director",
    slip: str = "surface",
) -> ContactGroup:
    """The contact element on ``pairs``: a ``PairTerms`` to give ``NonlinearProblem(terms=[...])``.

    Args:
        normal_law: e.g. ``PenaltyLaw(k)`` (N/m, per pair or one for all), for line pairs
            ``LinePenaltyLaw(k)`` (N/m², given the pairs' tributary lengths here), or
            ``hertz_laws``'s.
        friction_law: e.g. ``ElasticSlip(mu, g_lim)``; None: frictionless.
        normal: "director" (n from the nodes' rotated tangents, the default), "neighbour" (from
            the chords of the neighbouring nodes) or "frozen" (the initial normal).
        slip: "surface" (the surface points' relative motion) or "centreline" (the centre lines'
            closest points'; ``strand.contact.element``).
    """
    if isinstance(normal_law, LinePenaltyLaw):
        if not pairs.line:
            raise ValueError("LinePenaltyLaw (N/m²) is for line pairs; crossings take PenaltyLaw")
        normal_law = normal_law.for_pairs(pairs.tributary)
    stencils, positions = pairs.stencil(normal)
    return ContactGroup(
        stencils,
        positions,
        pairs.line,
        pairs.radius_a,
        pairs.radius_b,
        pairs.normal,
        normal_law,
        friction_law=friction_law,
        normal=normal,
        tangent0=pairs.tangents,
        index=pairs.index,
        initial_gap=pairs.initial_gap,
        slip=slip,
    )


def hertz_laws(
    pairs: NodePairs,
    E_a: npt.ArrayLike,
    nu_a: npt.ArrayLike,
    E_b: npt.ArrayLike,
    nu_b: npt.ArrayLike,
    mu: npt.ArrayLike | None = None,
    *,
    microslip: bool = False,
) -> tuple[NormalLaw, FrictionLaw | None]:
    """Contact laws of elastic wires from their radii and moduli (Pa) alone: Hertz crossed
    cylinders at the pairs' crossing angle, or Hertz line contact over the tributary length, and
    Mindlin's initial tangential stiffness with Coulomb coefficients ``mu`` (None: frictionless),
    linear up to the cone or, with ``microslip``, Mindlin–Deresiewicz's curve
    (``microslip.MindlinDeresiewicz``). Material values may be one for all or one per pair
    (``hertz.hertz_mindlin``)."""
    return hertz_mindlin(
        pairs.line,
        pairs.radius_a,
        pairs.radius_b,
        pairs.crossing_angle,
        pairs.tributary,
        E_a=E_a,
        nu_a=nu_a,
        E_b=E_b,
        nu_b=nu_b,
        mu=mu,
        microslip=microslip,
    )
