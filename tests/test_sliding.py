"""Large-sliding contact: exact normal tangent, a beam dragged across segments, agreement with the
small-sliding element when sliding is small."""

from __future__ import annotations

import numpy as np
import pytest

import strand  # noqa: F401

from strand.contact.element import ContactSettings  # isort: skip
from strand.contact.sliding import SlidingGroup, SlidingWindowError  # isort: skip
from strand.problem import StrandProblem  # isort: skip
from strand.solver import LoadStepper, NewtonOptions  # isort: skip

H = 3e-3  # m, segment length
R = 1.5e-3  # m, wire radius
K_N = 5e7  # N/m


def dragged_pair(angle_deg: float = 90.0, reach: int = 3, mu: float = 0.0):
    """Wire a along x (nodes every H), wire b crossing it on top at the window's middle node."""
    na = 2 * reach + 2
    s = (np.arange(na) - reach) * H
    xa = np.column_stack([s, np.zeros(na), np.zeros(na)])
    t = np.radians(angle_deg)
    xb = np.column_stack([s * np.cos(t), s * np.sin(t), np.full(na, 2 * R)])
    X = np.vstack([xa, xb])[None]
    stencil = np.arange(2 * na)[None]
    ends = np.zeros((1, 4), dtype=bool)
    group = SlidingGroup(
        stencil, X, na, False, [[reach, reach]], [K_N], [mu], 5e-6, wire_end=ends,
        radius_a=R, radius_b=R,
    )  # fmt: skip
    return group, na


def test_normal_tangent_is_exact_while_the_point_slides():
    rng = np.random.default_rng(5)
    group, na = dragged_pair(60.0)
    w = np.zeros((2 * na, 6))
    w[na:, 0] = 0.4 * H  # b slid along a by 0.4 segment
    w[na:, 2] = -2e-6  # pressed
    w[:, :3] += rng.normal(scale=2e-7, size=(2 * na, 3))
    f, K = group.evaluate(w, True)
    assert group.state.force[0] > 0
    step = 1e-9
    K_fd = np.zeros_like(K)
    for j in range(K.shape[2]):
        node, comp = divmod(j, 6)
        wp, wm = w.copy(), w.copy()
        wp[node, comp] += step
        wm[node, comp] -= step
        K_fd[:, :, j] = (group.evaluate(wp, False)[0] - group.evaluate(wm, False)[0]) / (2 * step)
    assert np.abs(K - K_fd).max() <= 1e-6 * np.abs(K).max()


@pytest.mark.parametrize("angle", [90.0, 30.0])
def test_a_beam_dragged_along_another_follows_across_segments(angle):
    """Wire b pressed on wire a and dragged 2.5 segments along a: the contact point moves from
    segment to segment, the gap stays at the imposed penetration and the normal stays vertical."""
    group, na = dragged_pair(angle, reach=3)
    w = np.zeros((2 * na, 6))
    w[na:, 2] = -3e-6
    segments = []
    for s in np.linspace(0.0, 2.5 * H, 11):
        w[na:, 0] = s
        group.evaluate(w, True)
        group.commit()
        segments.append(group.segment[0, 0])
        assert group.state.gap[0] == pytest.approx(-3e-6, rel=1e-9)
        assert np.allclose(group.state.normal[0], [0, 0, 1], atol=1e-12)
        assert group.state.force[0] == pytest.approx(K_N * 3e-6, rel=1e-9)
        # the contact point on a is at x = s (b's centreline crosses a's there)
        xi = group._shape[0, 1]
        assert (segments[-1] - 3 + xi) * H == pytest.approx(s, abs=1e-12)
    assert segments[0] in (2, 3) and segments[-1] == 5  # 2.5 segments further
    assert np.all(np.diff(segments) >= 0)
    # beyond the reserved window: a clear error
    w[na:, 0] = 4.5 * H
    group.evaluate(w, True)
    with pytest.raises(SlidingWindowError, match="increase the sliding reach"):
        group.commit()


def test_large_and_small_sliding_agree_when_sliding_is_small():
    """1+6 strand, 0.2 m, 40 kN then a 600 N saddle load: same end displacement, deflection and
    contact forces within a few per cent (the wires slide by micrometres). Tolerance 1e-2 N as in
    strand run: large sliding chatters at ~1e-2 N when a contact point sits on a node shared by two
    segments (every crossing starts there)."""
    from test_contact import seven_wire

    geometry = seven_wire(length=0.2)
    results = {}
    for model in ("small", "large"):
        problem = StrandProblem(
            geometry, ContactSettings(model=model), NewtonOptions(atol=1e-2, max_it=15)
        )
        LoadStepper(problem.solver, 10e3, 100.0).ramp(problem.set_tension, 0.0, 40e3)
        u_tension = problem.end_displacement()
        forces = problem.pair_results()["force"].copy()
        LoadStepper(problem.solver, 100.0, 5.0, max_step=200.0).ramp(
            problem.set_lateral, 0.0, 600.0
        )
        results[model] = (u_tension, forces, problem.midspan_deflection())
    (u_s, f_s, d_s), (u_l, f_l, d_l) = results["small"], results["large"]
    assert u_l == pytest.approx(u_s, rel=1e-3)
    assert f_l.sum() == pytest.approx(f_s.sum(), rel=1e-3)
    assert np.abs(f_l - f_s).max() < 0.02 * np.abs(f_s).max()
    assert d_l == pytest.approx(d_s, rel=0.05)
