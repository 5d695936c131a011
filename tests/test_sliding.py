"""Large-sliding contact: exact normal tangent, a beam dragged across segments, agreement with the
small-sliding element when sliding is small."""

from __future__ import annotations

import numpy as np
import pytest

from strand.contact.friction_laws import ElasticSlip
from strand.contact.normal_laws import PenaltyLaw
from strand.contact.sliding import SlidingGroup, SlidingWindowError
from strand.model.contact_settings import ContactSettings
from strand.model.problem import StrandProblem
from strand.setups import SaddleTest
from strand.solver import LoadStepper, NewtonOptions
from strand_cases import fd_tangent, nineteen_wire, seven_wire

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
    tangents = np.repeat([[1.0, 0.0, 0.0], [np.cos(t), np.sin(t), 0.0]], na, axis=0)[None]
    group = SlidingGroup(
        stencil,
        X,
        na,
        False,
        [[reach, reach]],
        PenaltyLaw(np.array([K_N])),
        friction_law=ElasticSlip(np.array([mu]), 5e-6),
        wire_end=ends,
        radius_a=R,
        radius_b=R,
        tangents=tangents,
    )
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
    K_fd = fd_tangent(group, w, 1e-9)
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
    with pytest.raises(SlidingWindowError, match="increase contact reach"):
        group.commit()


def test_large_and_small_sliding_agree_when_sliding_is_small():
    """1+6 strand, 0.2 m, 40 kN then a 600 N saddle load: same end displacement, deflection and
    contact forces within a few per cent (the wires slide by micrometres). Tolerance 1e-2 N as in
    strand run: large sliding chatters at ~1e-2 N when a contact point sits on a node shared by two
    segments (every crossing starts there)."""
    geometry = seven_wire(length=0.2)
    results = {}
    for model in ("small", "large"):
        problem = StrandProblem(
            geometry,
            ContactSettings(same_layer="off", model=model),
            NewtonOptions(atol=1e-2, max_it=15),
            setup=SaddleTest,
        )
        LoadStepper(problem.solver, 10e3, 100.0).ramp(problem.setup.set_tension, 0.0, 40e3)
        u_tension = problem.setup.end_displacement()
        forces = problem.pair_results().force.copy()
        LoadStepper(problem.solver, 100.0, 5.0, max_step=200.0).ramp(
            problem.setup.set_lateral, 0.0, 600.0
        )
        results[model] = (u_tension, forces, problem.setup.midspan_deflection())
    (u_s, f_s, d_s), (u_l, f_l, d_l) = results["small"], results["large"]
    assert u_l == pytest.approx(u_s, rel=1e-3)
    assert f_l.sum() == pytest.approx(f_s.sum(), rel=1e-3)
    assert np.abs(f_l - f_s).max() < 0.02 * np.abs(f_s).max()
    assert d_l == pytest.approx(d_s, rel=0.05)


def arc_pair(curvature_radius: float = 0.05, line: bool = False, reach: int = 3):
    """Wire a along a circular arc in the x–z plane (centre (0, 0, −ρ), top at the window's middle
    node), with its exact tangents; wire b straight along y on top of it (or, for a line pair, a
    single node b above a's middle node)."""
    na = 2 * reach + 2
    rho = curvature_radius
    phi = (np.arange(na) - reach) * H / rho
    xa = np.column_stack([rho * np.sin(phi), np.zeros(na), rho * (np.cos(phi) - 1)])
    ta = np.column_stack([np.cos(phi), np.zeros(na), -np.sin(phi)])
    s = (np.arange(na) - reach) * H
    if line:
        xb, tb = np.array([[0.0, 0.0, 2 * R]]), np.zeros((1, 3))
    else:
        xb = np.column_stack([np.zeros(na), s, np.full(na, 2 * R)])
        tb = np.tile([0.0, 1.0, 0.0], (na, 1))
    X = np.vstack([xa, xb])[None]
    group = SlidingGroup(
        np.arange(len(X[0]))[None],
        X,
        na,
        line,
        [[reach, 0 if line else reach]],
        PenaltyLaw(np.array([K_N])),
        friction_law=None,
        wire_end=np.zeros((1, 4), dtype=bool),
        radius_a=R,
        radius_b=R,
        tangents=np.vstack([ta, tb])[None],
    )
    return group, na, rho


@pytest.mark.parametrize("line", [False, True])
def test_gap_follows_a_curved_wire_across_its_nodes(line):
    """b slides over a circular arc: the gap equals the distance to the exact arc within 20 nm (C¹
    Hermite centreline, measured ≤ 5 nm; a polyline would be off by up to the sagitta h²/8ρ =
    22 µm), and the contact force stays radial to the arc, also while crossing nodes."""
    group, na, rho = arc_pair(line=line)
    w = np.zeros((len(group.X[0]), 6))
    for x_b in np.linspace(-1.7 * H, 1.7 * H, 37):  # crosses two nodes each way, and a midpoint
        w[na:, 0] = x_b
        w[na:, 2] = -2e-6  # pressed
        f, _ = group.evaluate(w, True)
        group.commit()
        centre = np.array([0.0, 0.0, -rho])
        d = np.array([x_b, 0.0, 2 * R - 2e-6]) - centre
        exact_gap = np.linalg.norm(d) - rho - 2 * R
        assert group.state.gap[0] == pytest.approx(exact_gap, abs=2e-8)
        # (a polyline chord would tilt it by up to hκ/2 = 0.03)
        assert np.allclose(group.state.normal[0], d / np.linalg.norm(d), atol=1e-5)
        # no sideways force on b, and Newton's third law across the two wires
        f_nodes = f[0].reshape(-1, 6)
        assert np.allclose(f_nodes[:na, :3].sum(0), -f_nodes[na:, :3].sum(0), atol=1e-9)


@pytest.mark.parametrize("line", [False, True])
def test_hermite_tangent_is_exact_with_rotations(line):
    """FD check of the normal tangent on a curved wire with finite nodal rotations (which turn the
    Hermite tangents) and the contact point between nodes."""
    rng = np.random.default_rng(11)
    group, na, _ = arc_pair(line=line, reach=1)
    n = len(group.X[0])
    w = np.zeros((n, 6))
    w[:, 3:] = rng.normal(scale=0.05, size=(n, 3))
    w[:, :3] = rng.normal(scale=2e-7, size=(n, 3))
    w[na:, 0] += 0.3 * H
    w[na:, 2] -= 3e-6
    f, K = group.evaluate(w, True)
    assert group.state.force[0] > 0 and 0.2 < group._shape[0, 1] < 0.5
    K_fd = fd_tangent(group, w, 1e-8)
    # columns of translations and of rotations (N/m and N/rad) checked each on its own scale
    for dofs in (slice(0, 3), slice(3, 6)):
        block = K.reshape(len(K), -1, n, 6)[..., dofs]
        block_fd = K_fd.reshape(len(K), -1, n, 6)[..., dofs]
        assert np.abs(block).max() > 1e3  # the rotations do enter (turning the tangents)
        assert np.abs(block - block_fd).max() <= 1e-6 * np.abs(block).max()


def test_large_sliding_tension_on_a_nineteen_wire_strand():
    """Helical layers touch at nodes, where polyline centrelines have kinks (the closest points
    flip between segments and Newton diverged at a few kN on Cardinal): on Hermite centrelines
    tension converges like the small-sliding element, to the same end displacement."""
    geometry = nineteen_wire(length=0.1)
    ends, histories = {}, {}
    for model in ("small", "large"):
        problem = StrandProblem(
            geometry,
            ContactSettings(same_layer="off", model=model),
            NewtonOptions(atol=1e-2, max_it=12),
            setup=SaddleTest,
        )
        stepper = LoadStepper(problem.solver, 10e3, 100.0)
        stepper.ramp(problem.setup.set_tension, 0.0, 40e3)
        ends[model] = problem.setup.end_displacement()
        histories[model] = [r.iterations for r in stepper.history]
    print(histories, ends)
    assert sum(r for r in histories["large"]) <= sum(histories["small"]) + 4
    assert ends["large"] == pytest.approx(ends["small"], rel=2e-3)


def test_windows_reach_the_sliding_room_and_no_further():
    """Every pair's window covers ``reach`` of arc length either side of its node (or stops at the
    wire's end), and dropping its outermost segment would not: Cardinal has segments from 1 µm
    to 4 mm, so windows counted in segments would leave some pairs no room at all."""
    from strand.cable.description import cardinal
    from strand.cable.geometry import build_geometry
    from strand.model.strand_contact import wire_chains

    geometry = build_geometry(cardinal(), 0.3)
    reach = 1e-3
    nodes = np.concatenate([geometry.pairs.a, geometry.pairs.b])
    chains = wire_chains(geometry)
    first, last, ends = chains.stretch(nodes, reach)
    first, last = chains.nodes[first], chains.nodes[last]  # the wires' input nodes
    x = geometry.points

    def arc(i, j):  # arc length from node i to node j ≥ i along one wire
        steps = np.linalg.norm(np.diff(x, axis=0), axis=1)
        c = np.concatenate([[0.0], np.cumsum(steps)])
        return c[j] - c[i]

    assert np.all(geometry.point_wire[first] == geometry.point_wire[nodes])
    assert np.all(geometry.point_wire[last] == geometry.point_wire[nodes])
    assert np.all((arc(first, nodes) >= reach) | ends[:, 0])
    assert np.all((arc(nodes, last) >= reach) | ends[:, 1])
    assert np.all(arc(first + 1, nodes) < reach)
    assert np.all(arc(nodes, last - 1) < reach)
    assert np.ptp(last - first) > 0  # the sizes do vary
