"""Node-to-segment contact (``strand.contact.segment``): exact tangents, objectivity, given gaps."""

import numpy as np
import pytest

from strand.contact.hertz import compliance, mindlin_ratio
from strand.contact.kinematics import rotation_matrix
from strand.contact.laws import ElasticSlip, HertzLineLaw, Mindlin, PenaltyLaw
from strand.contact.segment import SegmentGroup
from strand_cases import check_state_and_tangent

R = 1.66e-3  # m, wire radius


def side_by_side(n_pairs=3, compliance_kind="hertz", gap=None, mu=0.5, seed=3):
    """Node a of one wire against segment (b0, b1) of its neighbour, normal along +y."""
    rng = np.random.default_rng(seed)
    xi = rng.uniform(0.1, 0.9, n_pairs)
    normal = np.tile([0.0, 1.0, 0.0], (n_pairs, 1)) + rng.normal(scale=0.05, size=(n_pairs, 3))
    stencils = np.arange(3 * n_pairs).reshape(n_pairs, 3)
    r = np.full(n_pairs, R)
    if compliance_kind == "hertz":
        c = np.full(n_pairs, compliance(65e9, 0.33))
        law = HertzLineLaw(r, r, c, c, np.full(n_pairs, 4e-3))
        friction = Mindlin(np.full(n_pairs, mu), mindlin_ratio(65e9, 0.33, 65e9, 0.33))
    else:
        law, friction = PenaltyLaw(np.full(n_pairs, 5e7)), ElasticSlip(np.full(n_pairs, mu), 5e-6)
    group = SegmentGroup(stencils, xi, r, r, normal, law, friction, initial_gap=gap)
    return group, xi


def _press(group, xi, approach):
    """Unknowns (3P, 6) moving the segment towards a by ``approach`` (m) along the normal."""
    P = len(group)
    w = np.zeros((3 * P, 6))
    w[group.stencils[:, 1], :3] -= approach * group.n0
    w[group.stencils[:, 2], :3] -= approach * group.n0
    return w


@pytest.mark.parametrize("kind", ["hertz", "penalty"])
def test_tangent_matches_finite_differences_open_stick_slip(kind):
    """Residual derivatives in the three states, after a committed step with random rotations."""
    rng = np.random.default_rng(11)
    group, xi = side_by_side(compliance_kind=kind)
    P = len(group)
    w = _press(group, xi, 3e-6)
    w[:, 3:] = rng.normal(scale=0.02, size=(3 * P, 3))
    group.evaluate(w, True)
    group.commit()
    assert np.all(group.committed_force > 0)
    t = np.cross(group.n0, [0.0, 0.0, 1.0])
    states = {"stick": (2e-8, 0.0), "slip": (3e-5, 0.0), "open": (0.0, 1e-5)}
    for state, (tangential, opening) in states.items():
        w2 = w.copy()
        w2[group.stencils[:, 1:].ravel(), :3] += np.repeat(
            tangential * t - opening * -group.n0, 2, 0
        )
        w2[:, :3] += rng.normal(scale=1e-9, size=(3 * P, 3))
        K_fd, scale = check_state_and_tangent(group, w2, state)
        K = group.evaluate(w2, True)[1]
        assert np.abs(K - K_fd).max() <= 2e-6 * scale, state


def test_rigid_rotation_neither_opens_nor_slips():
    """Rotate the pair (touching, surface points a distance r_a + r_b apart) rigidly about the
    contact point by ω: the gap and the slip change by O(ω²) only."""
    group, xi = side_by_side(n_pairs=1, gap=0.0)
    n = group.n0[0]
    xa = np.zeros(3)
    x0, x1 = xa + 2 * R * n - [0.0, 0.0, 2e-3], xa + 2 * R * n + [0.0, 0.0, 2e-3]
    xi0 = xi[0]
    x0, x1 = x0 - (xi0 - 0.5) * (x1 - x0), x1 - (xi0 - 0.5) * (x1 - x0)  # b faces a at ξ
    X = np.array([xa, x0, x1])
    centre = xa + R * n
    for omega in (1e-4, 2e-4):
        theta = omega * np.array([0.3, -0.5, 0.8])
        Q = rotation_matrix(theta)
        w = np.zeros((3, 6))
        w[:, :3] = (X - centre) @ Q.T + centre - X
        w[:, 3:] = theta
        group.evaluate(np.zeros((3, 6)), False)
        group.commit()
        group.evaluate(w, False)
        S, dq = group._S, w.reshape(1, 18)
        slip = np.einsum("pij,pj->pi", S, dq)
        assert abs(group.state.gap[0]) < 4 * (2 * R) * omega**2
        assert np.linalg.norm(slip) < 4 * (2 * R) * omega**2
        group.rollback()


def test_a_given_gap_opens_then_closes():
    """With an initial gap of 2 µm the pair carries nothing until it has closed by 2 µm."""
    group, xi = side_by_side(n_pairs=2, gap=np.full(2, 2e-6))
    for approach, closed in ((1.9e-6, False), (2.1e-6, True)):
        group.evaluate(_press(group, xi, approach), False)
        assert np.all((group.state.force > 0) == closed), approach
        np.testing.assert_allclose(group.state.gap, 2e-6 - approach, rtol=1e-9)
