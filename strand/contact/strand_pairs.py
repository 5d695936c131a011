"""The contact pairs of a strand, built through the public contact API (``strand.contact.pairs``).

The strand geometry found its pairs analytically (``strand.geometry``): crossings where two wires
are radially aligned, and every layer-1 node against the core. Here they become ``NodePairs``
(nodes as dof blocks, the geometry's radial normals, gaps zero by construction) and, with the laws
that ``ContactSettings`` choose, the small-sliding ``ContactGroup`` of each kind. Units: m, N.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from ..geometry import LINE, POINT, StrandGeometry
from ..partition import DistributionError, owned_rows
from .element import ContactGroup, ContactSettings
from .laws import ElasticSlip, FrictionLaw, NormalLaw, PenaltyLaw, hertz_mindlin
from .pairs import NodePairs, contact_terms, crossing_angle

__all__ = ["strand_pairs", "pair_stencils", "contact_groups", "pair_laws", "wire_neighbours"]


def wire_neighbours(geometry: StrandGeometry, nodes: npt.NDArray[np.int64]):
    """Input indices of the previous and next node on the same wire (the node itself at ends)."""
    wire = geometry.point_wire[nodes]
    lo, hi = geometry.wire_offsets[wire], geometry.wire_offsets[wire + 1] - 1
    return np.maximum(nodes - 1, lo), np.minimum(nodes + 1, hi)


def pair_stencils(geometry: StrandGeometry, sel=None) -> npt.NDArray[np.int64]:
    """(P, 6) input nodes of the geometry's pairs ``sel`` (default: all) in ``ROLES`` order:
    a, b and their neighbours along their wires (a first: the anchor of a distributed pair)."""
    pairs = geometry.pairs
    sel = np.arange(len(pairs)) if sel is None else np.asarray(sel)
    a, b = pairs.a[sel], pairs.b[sel]
    return np.column_stack([a, b, *wire_neighbours(geometry, a), *wire_neighbours(geometry, b)])


def strand_pairs(geometry: StrandGeometry, input_to_block: npt.NDArray[np.int32], sel) -> NodePairs:
    """The geometry's pairs ``sel`` (all of one kind) as ``NodePairs`` on the local dof blocks
    ``input_to_block`` (``mesh.input_to_block``), with zero initial gaps."""
    pairs = geometry.pairs
    sel = np.asarray(sel)
    points = pair_stencils(geometry, sel)
    blocks = input_to_block[points]
    if np.any(blocks < 0):
        raise DistributionError(
            "contact pairs whose nodes are not all on this process: distribute the mesh with "
            "strand.partition.slab_partitioner and keep the pairs this rank owns (owned_rows)"
        )
    kinds = pairs.kind[sel]
    if len(np.unique(kinds)) > 1:
        raise ValueError("strand_pairs: the selected pairs mix crossings and line pairs")
    return NodePairs(
        blocks.astype(np.int32),
        geometry.points[points],
        bool(len(kinds) and kinds[0] == LINE),
        pairs.radius_a[sel],
        pairs.radius_b[sel],
        pairs.normal[sel],
        np.zeros(len(sel)),
        pairs.tributary[sel],
        sel,
    )


def contact_groups(
    geometry: StrandGeometry,
    input_to_block: npt.NDArray[np.int32],
    settings: ContactSettings,
    n_owned: int | None = None,
) -> list[ContactGroup]:
    """The contact pairs of a strand as ``ContactGroup`` objects (one per pair kind present).
    With ``n_owned`` (a distributed mesh: the number of dof blocks this rank owns), only the
    pairs whose node a this rank owns (``partition.owned_rows``)."""
    groups = []
    for kind in (POINT, LINE):
        sel = np.flatnonzero(geometry.pairs.kind == kind)
        if n_owned is not None:
            blocks = input_to_block[pair_stencils(geometry, sel)]
            sel = sel[owned_rows(blocks, n_owned, "contact pairs")]
        if len(sel):
            pairs = strand_pairs(geometry, input_to_block, sel)
            laws = pair_laws(geometry, sel, settings, pairs.tangents)
            groups.append(contact_terms(pairs, *laws, normal=settings.normal))
    return groups


def pair_laws(
    geometry: StrandGeometry, sel, settings: ContactSettings, tangents
) -> tuple[NormalLaw, FrictionLaw | None]:
    """The normal and friction laws of the geometry's pairs ``sel`` (all of one kind).

    ``tangents`` (P, 2, 3): the initial unit tangents of the wires at a and b (their crossing
    angle sizes a Hertz contact).
    """
    pairs = geometry.pairs
    line = bool(np.all(pairs.kind[sel] == LINE))
    mu = pairs.friction[sel] if settings.friction else np.zeros(len(sel))
    if settings.compliance == "penalty":
        k = settings.k_line * pairs.tributary[sel] if line else np.full(len(sel), settings.k_point)
        return PenaltyLaw(k), ElasticSlip(mu, settings.g_lim) if settings.friction else None
    wires = [layer.wire for layer in geometry.cable.layers]
    inner, outer = pairs.interface[sel], pairs.interface[sel] + 1
    E_a, nu_a = (np.array([getattr(w, key) for w in wires])[inner] for key in ("E", "nu"))
    E_b, nu_b = (np.array([getattr(w, key) for w in wires])[outer] for key in ("E", "nu"))
    return hertz_mindlin(
        line, pairs.radius_a[sel], pairs.radius_b[sel], crossing_angle(tangents), pairs.tributary[sel],
        E_a, nu_a, E_b, nu_b, mu if settings.friction else None,
    )  # fmt: skip
