"""``LinePenaltyLaw``: a penalty per unit length of line contact that takes its pairs' tributary
lengths from ``contact_terms``, giving what ``PenaltyLaw(k * pairs.tributary)`` gives."""

from __future__ import annotations

import numpy as np
import pytest
from mpi4py import MPI

from strand.cable.mesh import beam_space, polyline_mesh
from strand.contact import (
    ElasticSlip,
    LinePenaltyLaw,
    PenaltyLaw,
    candidate_pairs,
    contact_terms,
    locate_nodes,
)

R = 1.5e-3  # m, both beams
K_LINE = 5e9  # N/m²
LENGTH = 0.1  # m


def parallel_beams(n_a: int = 20, n_b: int = 13, crossing: bool = False):
    """Beam b lying on beam a along x, meshed differently (so that the pairs' tributary lengths
    differ), or with ``crossing`` across it along y: the space and the nodes of a and b."""
    s = np.linspace(-LENGTH / 2, LENGTH / 2, n_a + 1)
    t = np.linspace(-LENGTH / 2, LENGTH / 2, n_b + 1)
    b = np.c_[0 * t, t, 0 * t + 2 * R] if crossing else np.c_[t, 0 * t, 0 * t + 2 * R]
    pts = np.vstack([np.c_[s, 0 * s, 0 * s], b])
    cells = np.vstack([np.c_[0:n_a, 1 : n_a + 1], np.c_[0:n_b, 1 : n_b + 1] + n_a + 1])
    V = beam_space(polyline_mesh(MPI.COMM_WORLD, pts, cells))
    return V, locate_nodes(V, pts[: n_a + 1]), locate_nodes(V, pts[n_a + 1 :])


def pressed(V, b, depth: float, slide: float = 0.0) -> np.ndarray:
    """Nodal unknowns (blocks, 6): beam b pushed ``depth`` (m) into a and slid ``slide`` along x."""
    imap = V.dofmap.index_map
    w = np.zeros((imap.size_local + imap.num_ghosts, 6))
    w[b, 2] = -depth
    w[b, 0] = slide
    return w


def test_line_penalty_gives_the_forces_of_the_hand_multiplied_penalty():
    """Residual and tangent, frictionless and with friction (stick, after a committed step), equal to
    ``PenaltyLaw(k * pairs.tributary)``'s; and the line load is k δ at every pair: the pair
    forces sum to k δ times the length of b."""
    V, a, b = parallel_beams()
    pairs = candidate_pairs(V, a, b, R, R, reach=1e-6, line=True)
    assert np.ptp(pairs.tributary) > 0  # end pairs stand for half a cell
    depth = 1e-7
    for friction in (None, ElasticSlip(0.3, 1e-6)):
        hand = contact_terms(pairs, PenaltyLaw(K_LINE * pairs.tributary), friction)
        line = contact_terms(pairs, LinePenaltyLaw(K_LINE), friction)
        if friction is not None:  # pressed, committed, then slid: a stick traction
            for group in (hand, line):
                group.evaluate(pressed(V, b, depth))
                group.commit()
        w = pressed(V, b, depth, slide=1e-8 if friction else 0.0)
        f_hand, K_hand = hand.evaluate(w)
        f_line, K_line = line.evaluate(w)
        np.testing.assert_array_equal(f_line, f_hand)
        np.testing.assert_array_equal(K_line, K_hand)
        np.testing.assert_array_equal(line.state.force, hand.state.force)
        np.testing.assert_array_equal(line.state.traction, hand.state.traction)
        assert (np.abs(line.state.traction).max() > 0) == (friction is not None)
        q = line.state.force / pairs.tributary
        np.testing.assert_allclose(q, K_LINE * depth, rtol=1e-9)
        assert line.state.force.sum() == pytest.approx(K_LINE * depth * LENGTH, rel=1e-9)


def test_line_penalty_is_refused_where_it_has_no_tributary():
    """On crossing pairs (no tributary length) and before ``contact_terms`` gives it one."""
    V, a, b = parallel_beams(n_b=14, crossing=True)
    crossings = candidate_pairs(V, a, b, R, R, reach=1e-6)
    assert not crossings.line and len(crossings) == 1
    with pytest.raises(ValueError, match="line pairs"):
        contact_terms(crossings, LinePenaltyLaw(K_LINE))
    with pytest.raises(ValueError, match="no tributary lengths yet"):
        LinePenaltyLaw(K_LINE).force(np.zeros(3))
    with pytest.raises(ValueError, match="positive tributary"):
        LinePenaltyLaw(K_LINE).for_pairs(np.zeros(3))
