"""Node-to-segment contact (``strand.contact.segment``): exact tangents, objectivity, given gaps."""

import numpy as np
import pytest

from strand.contact.friction_laws import ElasticSlip, Mindlin
from strand.contact.hertz import compliance, mindlin_ratio
from strand.contact.kinematics import rotation_matrix
from strand.contact.normal_laws import HertzLineLaw, PenaltyLaw
from strand.contact.segment import (
    SEGMENT_NORMALS,
    SegmentGroup,
    _projected_gap,
    _projected_gap_hessian,
)
from strand_cases import check_state_and_tangent

R = 1.66e-3  # m, wire radius


def side_by_side(n_pairs=3, compliance_kind="hertz", gap=None, mu=0.5, seed=3, normal="neighbour"):
    """Node a of one wire against segment (b0, b1) of its neighbour, a distance 2R (+ gap) apart
    along a normal near +y, the segment 4 mm long along z."""
    rng = np.random.default_rng(seed)
    xi = rng.uniform(0.1, 0.9, n_pairs)
    n = np.tile([0.0, 1.0, 0.0], (n_pairs, 1)) + rng.normal(scale=0.05, size=(n_pairs, 3))
    n[:, 2] = 0.0
    n /= np.linalg.norm(n, axis=1)[:, None]
    g = np.zeros(n_pairs) if gap is None else np.broadcast_to(gap, (n_pairs,))
    xa = rng.normal(scale=1e-3, size=(n_pairs, 3))
    facing = xa + (2 * R + g)[:, None] * n
    ez = np.array([0.0, 0.0, 4e-3])
    X = np.stack([xa, facing - xi[:, None] * ez, facing + (1 - xi)[:, None] * ez], axis=1)
    stencils = np.arange(3 * n_pairs).reshape(n_pairs, 3)
    r = np.full(n_pairs, R)
    if compliance_kind == "hertz":
        c = np.full(n_pairs, compliance(65e9, 0.33))
        law = HertzLineLaw(r, r, c, c, np.full(n_pairs, 4e-3))
        friction = Mindlin(np.full(n_pairs, mu), mindlin_ratio(65e9, 0.33, 65e9, 0.33))
    else:
        law, friction = PenaltyLaw(np.full(n_pairs, 5e7)), ElasticSlip(np.full(n_pairs, mu), 5e-6)
    group = SegmentGroup(
        stencils,
        xi,
        r,
        r,
        n,
        law,
        friction_law=friction,
        initial_gap=gap,
        normal=normal,
        initial_positions=X,
    )
    group.X_nodes = X.reshape(-1, 3)  # the nodes' positions, in stencil order
    return group, xi


def _press(group, xi, approach):
    """Unknowns (3P, 6) moving the segment towards a by ``approach`` (m) along the normal."""
    P = len(group)
    w = np.zeros((3 * P, 6))
    w[group.stencils[:, 1], :3] -= approach * group.n0
    w[group.stencils[:, 2], :3] -= approach * group.n0
    return w


@pytest.mark.parametrize("normal", SEGMENT_NORMALS)
@pytest.mark.parametrize("kind", ["hertz", "penalty"])
def test_tangent_matches_finite_differences_open_stick_slip(kind, normal):
    """Residual derivatives in the three states, after a committed step with random rotations."""
    rng = np.random.default_rng(11)
    group, xi = side_by_side(compliance_kind=kind, normal=normal)
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


def _complex_step_hessian(d: np.ndarray, c: np.ndarray, eps: float = 1e-30) -> np.ndarray:
    """Reference ∂²g/∂z² (P, 6, 6) of g = ‖P_c d‖, z = (d, c): H[:, :, j] = Im ∇g(z + iεe_j)/ε
    (the gradient is complex-analytic; no difference is taken)."""
    H = np.empty((len(d), 6, 6))
    for j in range(6):
        dz = np.zeros(6, dtype=complex)
        dz[j] = 1j * eps
        H[:, :, j] = _projected_gap(d + dz[:3], c + dz[3:])[2].imag / eps
    return H


def test_closed_form_neighbour_hessian_matches_the_complex_step():
    """∂²g/∂z² in closed form against the complex step, on random pairs: ‖d‖ = 2R, ‖c‖ from 1
    to 4 mm, angles between d and c from 5° to 175° (and d across c)."""
    rng = np.random.default_rng(5)
    n_pairs = 200
    e = rng.normal(size=(n_pairs, 3))
    e /= np.linalg.norm(e, axis=1)[:, None]
    m = np.cross(e, rng.normal(size=(n_pairs, 3)))
    m /= np.linalg.norm(m, axis=1)[:, None]
    angle = rng.uniform(np.radians(5), np.radians(175), n_pairs)
    angle[:20] = np.pi / 2
    d = 2 * R * (np.cos(angle)[:, None] * e + np.sin(angle)[:, None] * m)
    c = rng.uniform(1e-3, 4e-3, n_pairs)[:, None] * e
    H = _projected_gap_hessian(d, c)
    H_ref = _complex_step_hessian(d, c)
    size = np.abs(H_ref).max(axis=(1, 2))[:, None, None]
    assert np.all(np.abs(H - H_ref) <= 1e-10 * size)
    np.testing.assert_array_equal(H, H.transpose(0, 2, 1))


def _rigid(X: np.ndarray, theta: np.ndarray, centre: np.ndarray) -> np.ndarray:
    """Unknowns (N, 6) turning the points X (N, 3) rigidly by the rotation vector θ about
    ``centre``."""
    w = np.zeros((len(X), 6))
    w[:, :3] = (X - centre) @ rotation_matrix(theta).T + centre - X
    w[:, 3:] = theta
    return w


@pytest.mark.parametrize("normal", SEGMENT_NORMALS)
def test_small_rigid_rotation_neither_opens_nor_slips(normal):
    """Rotate the pair (touching, surface points r_a + r_b apart) rigidly about the contact
    point by ω: the gap and the slip change by O(ω²) only."""
    group, xi = side_by_side(n_pairs=1, gap=0.0, normal=normal)
    X = group.X_nodes
    centre = X[0] + R * group.n0[0]
    for omega in (1e-4, 2e-4):
        w = _rigid(X, omega * np.array([0.3, -0.5, 0.8]), centre)
        group.evaluate(np.zeros((3, 6)), False)
        group.commit()
        group.evaluate(w, False)
        S, dq = group.slip_operator(), w.reshape(1, 18)
        slip = np.einsum("pij,pj->pi", S, dq)
        assert abs(group.state.gap[0]) < 4 * (2 * R) * omega**2
        assert np.linalg.norm(slip) < 4 * (2 * R) * omega**2
        group.rollback()


def test_a_finite_rigid_rotation_leaves_the_neighbour_gap_and_turns_the_force():
    """Pairs pressed 2 µm, then turned rigidly by 0.25 rad (the end sections of the uniform
    bending test at κ = 0.5 1/m on 1 m): the neighbour normal keeps every gap and force and
    turns the force with the pair, to round-off; the frozen normal closes them by
    (r_a + r_b)(1 − cos ω⊥) ≈ 0.1 mm."""
    theta = 0.25 * np.array([1.0, 0.0, 0.0])  # about x: across the normals (near +y)
    Q = rotation_matrix(theta)
    for normal in SEGMENT_NORMALS:
        group, xi = side_by_side(n_pairs=4, normal=normal)
        pressed = _press(group, xi, 2e-6)
        group.evaluate(pressed, False)
        gap, force, n = group.state.gap.copy(), group.state.force.copy(), group.state.normal.copy()
        X = group.X_nodes + pressed[:, :3]
        w = _rigid(X, theta, np.zeros(3))
        w[:, :3] += pressed[:, :3]
        group.evaluate(w, False)
        if normal == "neighbour":
            np.testing.assert_allclose(group.state.gap, gap, atol=1e-15)
            np.testing.assert_allclose(group.state.force, force, rtol=1e-9)
            np.testing.assert_allclose(group.state.normal, n @ Q.T, atol=1e-12)
        else:
            closing = gap - group.state.gap
            omega_across = np.linalg.norm(np.cross(theta, group.n0), axis=1)
            np.testing.assert_allclose(closing, 2 * R * (1 - np.cos(omega_across)), rtol=0.02)
            assert np.all(closing > 9e-5)


def test_a_given_gap_opens_then_closes():
    """With an initial gap of 2 µm the pair carries nothing until it has closed by 2 µm."""
    group, xi = side_by_side(n_pairs=2, gap=np.full(2, 2e-6))
    for approach, closed in ((1.9e-6, False), (2.1e-6, True)):
        group.evaluate(_press(group, xi, approach), False)
        assert np.all((group.state.force > 0) == closed), approach
        np.testing.assert_allclose(group.state.gap, 2e-6 - approach, rtol=1e-9)
