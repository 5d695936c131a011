"""Large sliding with the centre-line slip and with same-layer contact:
exact tangents, spin-blindness, agreement with the small-sliding element, and the same answer on
1 and 2 ranks (same-layer pairs opening and closing in both models: tests/test_same_layer.py)."""

from __future__ import annotations

import numpy as np
import pytest
from test_mpi import TOUCHING, _run_and_compare
from test_restart import QUIET, assert_continues, uninterrupted_with_checkpoint

from strand.app.case import load_case
from strand.app.run import run_case
from strand.contact.element import ContactGroup, centreline_slip_operator
from strand.contact.friction_laws import ElasticSlip
from strand.contact.group import tangential_part
from strand.contact.hertz import hertz_mindlin
from strand.contact.kinematics import rotation_matrix, tangent_map
from strand.contact.normal_laws import PenaltyLaw
from strand.contact.sliding import SlidingGroup
from strand.model.contact_settings import ContactSettings
from strand.model.model import strand_stencils
from strand.model.problem import StrandProblem
from strand.model.same_layer import facing_point_motion, same_layer_pairs
from strand.model.strand_contact import same_layer_windows
from strand.setups import SaddleTest
from strand.solver import LoadStepper, NewtonOptions
from strand_cases import SEVEN_WIRE, check_state_and_tangent, fd_tangent, needs_mpirun, seven_wire

H = 3e-3  # m, segment length
R_A, R_B = 1.5e-3, 2.0e-3  # m, wire radii
K_N, MU, G_LIM = 5e7, 0.5, 5e-6


def _laws(compliance: str, line: bool, angle: float):
    if compliance == "penalty":
        return PenaltyLaw(np.array([K_N])), ElasticSlip(np.array([MU]), G_LIM)
    return hertz_mindlin(
        line, [R_A], R_B, angle, H, E_a=2.1e11, nu_a=0.3, E_b=2.1e11, nu_b=0.3, mu=MU
    )


def _group(X, tangents, na, line, compliance="penalty", angle=np.pi / 2, slip="centreline"):
    """One large-sliding pair on the window X (na nodes of a, then b's), starting at a's middle
    node (and b's)."""
    reach = na // 2 - 1
    normal_law, friction_law = _laws(compliance, line, angle)
    return SlidingGroup(
        np.arange(len(X))[None],
        X[None],
        na,
        line,
        [[reach, 0 if line else reach]],
        normal_law,
        friction_law=friction_law,
        wire_end=np.zeros((1, 4), dtype=bool),
        radius_a=R_A,
        radius_b=R_B,
        tangents=tangents[None],
        slip=slip,
    )


def arc_pair(line: bool, compliance="penalty", slip="centreline", rho=0.05, angle=60.0):
    """Wire a along a circular arc of radius ``rho`` in the x–z plane with its exact tangents, and
    wire b straight on top of it at ``angle`` (°) to the arc's middle tangent (a line pair: one
    node b above a's middle node)."""
    na = 4
    phi = (np.arange(na) - 1) * H / rho
    xa = np.column_stack([rho * np.sin(phi), np.zeros(na), rho * (np.cos(phi) - 1)])
    ta = np.column_stack([np.cos(phi), np.zeros(na), -np.sin(phi)])
    t = np.radians(angle)
    tb = np.tile([np.cos(t), np.sin(t), 0.0], (na, 1))
    xb = (np.arange(na) - 1)[:, None] * H * tb + [0.0, 0.0, R_A + R_B]
    if line:
        xb, tb = xb[1:2], np.zeros((1, 3))
    return _group(np.vstack([xa, xb]), np.vstack([ta, tb]), na, line, compliance, t, slip), na


def straight_pairs(line: bool, angle_deg: float = 35.0):
    """Two straight wires crossing at ``angle_deg`` (a along x, b on top; line pairs: 0.1 rad and
    one node b), touching at a's node 1 and b's node 1: the large-sliding pair and the
    small-sliding one (director normal, centre-line slip) on the same nodes."""
    angle = 0.1 if line else np.radians(angle_deg)
    ta, tb = np.array([1.0, 0.0, 0.0]), np.array([np.cos(angle), np.sin(angle), 0.0])
    s = (np.arange(4) - 1)[:, None] * H
    xa, xb = s * ta, s * tb + [0.0, 0.0, R_A + R_B]
    if line:
        xb = xb[1:2]
    X = np.vstack([xa, xb])
    T = np.vstack([np.tile(ta, (4, 1)), np.tile(tb, (len(xb), 1))])
    large = _group(X, T, 4, line, angle=angle)
    laws = _laws("penalty", line, angle)
    small = ContactGroup(
        [[0, 1]],
        np.stack([xa[1], xb[0 if line else 1]])[None],
        line,
        [R_A],
        [R_B],
        [[0.0, 0.0, 1.0]],
        laws[0],
        friction_law=laws[1],
        normal="director",
        tangent0=np.stack([ta, tb])[None],
        slip="centreline",
    )
    return large, small, 4 + (0 if line else 1)  # the window row of b's contact node


def _pressed(group, na, rng, turned=0.05, spinning=None):
    """Window unknowns pressing b 3 µm into a, every node turned at random by up to ``turned`` rad
    except the nodes ``spinning``, whose rotations stay zero; evaluated and committed, then b
    moved 0.1 µm across a (in stick) and committed: the pair carries a traction."""
    n = len(group.X[0])
    w = np.zeros((n, 6))
    w[:, 3:] = rng.uniform(-turned, turned, size=(n, 3))
    if spinning is not None:
        w[spinning, 3:] = 0.0
    w[:, :3] = rng.normal(scale=2e-7, size=(n, 3))
    w[na:, 0] += 0.3 * H  # the contact point between a's nodes
    w[na:, 2] -= 3e-6
    for _ in range(2):
        group.evaluate(w, True)
        group.commit()
        w[na:, 1] += 1e-7
    w[na:, 1] -= 1e-7
    assert group.state.force[0] > 0 and 0.1 < group._shape[0, 1] < 0.9
    assert np.linalg.norm(group.state.traction) > 0 and not group.state.slipping[0]
    return w


# -- the centre-line slip in large sliding -------------------------------------------------------


@pytest.mark.parametrize("compliance", ["penalty", "hertz"])
@pytest.mark.parametrize("line", [False, True])
def test_centreline_slip_tangent_matches_finite_differences(line, compliance):
    """Residual derivatives in stick, slip and open states after a committed step, on a curved
    wire with finite nodal rotations and the contact point between nodes: exact (S is frozen
    over the step, so the friction tangent is Sᵀ(∂t/∂Δg_T)S). Translation and rotation columns
    are checked each on its own scale; central differences of step 1e-8 leave ≤ 2e-7 of it."""
    rng = np.random.default_rng(11)
    group, na = arc_pair(line, compliance)
    w = _pressed(group, na, rng)
    n = len(w)
    states = {"stick": (1e-7, -1e-6), "slip": (3e-5, -1e-6), "open": (0.0, 5e-5)}
    for state, (tangential, normal_move) in states.items():
        w2 = w.copy()
        w2[na:, 1] += tangential  # across a (along a the point would follow the slide)
        w2[na:, 2] += normal_move
        check_state_and_tangent(group, w2, state)
        K_fd = fd_tangent(group, w2, 1e-8)
        K = group.evaluate(w2, True)[1]
        for dofs in (slice(0, 3), slice(3, 6)):
            block = K.reshape(1, -1, n, 6)[..., dofs]
            block_fd = K_fd.reshape(1, -1, n, 6)[..., dofs]
            scale = max(np.abs(block).max(), 1.0)
            assert state == "open" or scale > 1e3
            assert np.abs(block - block_fd).max() <= 1e-6 * scale, (state, dofs)
        if state == "slip":
            assert not np.allclose(K, K.transpose(0, 2, 1))  # the slip tangent is unsymmetric


def _spin(group, w, nodes, angle):
    """``w`` with the nodes ``nodes`` (rotations zero) turned by ``angle`` about their own
    tangents: the centreline of their wire does not move."""
    spun = w.copy()
    spun[nodes, 3:] = angle * group.T0[0, nodes]
    return spun


@pytest.mark.parametrize("spinning", ["a", "b"])
def test_centreline_slip_is_blind_to_a_wire_spinning_about_its_axis(spinning):
    """A crossing's wire spun about its own axis (a curved wire a, or a straight b): its
    centreline, the gap and the closest points stay, and the centre-line traction stays the
    committed one to round-off, for a spin of 0.3 rad; under a spin of 1e-4 rad the surface
    points slip by r × 1e-4 rad, as the surface measure says (its traction changes by K_T r φ,
    in stick)."""
    for slip, angle in (("centreline", 0.3), ("surface", 1e-4)):
        group, na = arc_pair(False, slip=slip)
        nodes = np.arange(na) if spinning == "a" else np.arange(na, 2 * na)
        w = _pressed(group, na, np.random.default_rng(3), spinning=nodes)
        # the committed traction, carried onto the committed tangent plane
        t_old = tangential_part(group.state.traction, group.state.normal)[0]
        gap, shape, p = group.state.gap.copy(), group._shape, group.state.force[0]
        group.evaluate(_spin(group, w, nodes, angle), True)
        assert group.state.gap[0] == pytest.approx(gap[0], abs=1e-18)
        assert np.allclose(group._shape, shape, rtol=0, atol=1e-14)
        change = np.linalg.norm(group.state.traction[0] - t_old)
        if slip == "centreline":
            assert change <= 1e-12 * np.linalg.norm(t_old)
        else:
            assert not group.state.slipping[0]
            radius = R_A if spinning == "a" else R_B
            assert change == pytest.approx(MU * p / G_LIM * radius * angle, rel=1e-3)


@pytest.mark.parametrize("line", [False, True])
def test_centreline_slip_is_objective(line):
    """No centre-line slip for an infinitesimal rigid rotation of the whole window about any
    point, on a curved wire whose nodes are already turned by up to 0.3 rad: S Δq below 1e-12 of
    |ω| d, a node's motion (measured 2e-16)."""
    group, na = arc_pair(line)
    w = _pressed(group, na, np.random.default_rng(5), turned=0.3)
    S = group.slip_operator()[0]
    omega = np.array([2e-4, -1e-4, 3e-4])
    centre = np.array([1e-3, -2e-3, 4e-3])
    x = group.X[0] + w[:, :3]
    dq = np.zeros_like(w)
    dq[:, :3] = np.cross(omega, x - centre)
    dq[:, 3:] = [np.linalg.solve(tangent_map(theta), omega) for theta in w[:, 3:]]
    assert np.linalg.norm(S @ dq.ravel()) < 1e-12 * np.linalg.norm(omega) * (R_A + R_B)


@pytest.mark.parametrize("line", [False, True])
def test_centreline_slip_is_the_small_sliding_one_on_straight_wires(line):
    """Straight wires touching at a node (a crossing at 35°, a line pair at 0.1 rad), turned
    together by a rotation of 0.37 rad and committed: the large-sliding S on the contact nodes is
    the small-sliding element's, and zero on the window's other nodes; pressed 2 µm, it is
    ``element.centreline_slip_operator`` at the centrelines' distance. The two are the same
    formula here (the Hermite centrelines are straight, so J has no curvature term), reached by
    different arithmetic (a complex step through the projection against a Gram inverse): they
    differ by round-off, a few 1e-16 of S times the 2×2 solves' condition (1/sin²35° ≈ 3) and
    the rotation maps' sums (measured 4e-15); the tolerance is 1e-12 of S."""
    large, small, b_row = straight_pairs(line)
    omega = np.array([0.2, -0.3, 0.1])
    Q = rotation_matrix(omega)
    X = large.X[0]
    w = np.zeros((len(X), 6))
    w[:, :3] = X @ Q.T - X
    w[:, 3:] = omega
    large.evaluate(w, True)
    large.commit()
    pair = [1, b_row]  # the contact nodes in the window
    w_small = w[pair]
    small.evaluate(w_small, True)
    small.commit()
    S_large = large.slip_operator()[0].reshape(3, -1, 6)
    S_small = small.slip_operator()[0].reshape(3, 2, 6)
    scale = np.abs(S_small).max()
    assert np.abs(S_large[:, pair] - S_small).max() <= 1e-12 * scale
    others = np.setdiff1d(np.arange(len(X)), pair)
    assert np.abs(S_large[:, others]).max() <= 1e-12 * scale
    # pressed: the lever arm is the centrelines' distance
    w[4:, :3] -= 2e-6 * (Q @ [0.0, 0.0, 1.0])
    large.evaluate(w, True)
    large.commit()
    assert large.state.gap[0] == pytest.approx(-2e-6, rel=1e-6)
    t = np.stack([Q @ large.T0[0, 0], Q @ large.T0[0, -1]])[None]
    T = tangent_map(omega)[None]
    d = np.array([R_A + R_B - 2e-6])
    expected = centreline_slip_operator(large.state.normal, t, d, T, T, line)[0]
    S_large = large.slip_operator()[0].reshape(3, -1, 6)
    assert np.abs(S_large[:, pair].reshape(3, 12) - expected).max() <= 1e-12 * scale


def test_large_and_small_sliding_agree_with_the_centreline_slip():
    """1+6 strand, 0.2 m, 40 kN then a 600 N saddle load, with the centre-line slip in both
    models (core | layer-1 line pairs; no same-layer contact): end displacement and contact
    forces within ``test_sliding``'s tolerances for the surface slip, the deflection within 1e-3
    (measured 4.5e-5); the slip measure moves the deflection over ten times as much as the
    model (measured 1.6e-3, 36 times)."""
    geometry = seven_wire(length=0.2)
    results = {}
    for model, slip in (("small", "centreline"), ("large", "centreline"), ("large", "surface")):
        problem = StrandProblem(
            geometry,
            ContactSettings(same_layer="off", model=model, slip=slip),
            NewtonOptions(atol=1e-2, max_it=15),
            setup=SaddleTest,
        )
        LoadStepper(problem.solver, 10e3, 100.0).ramp(problem.setup.set_tension, 0.0, 40e3)
        u_tension = problem.setup.end_displacement()
        LoadStepper(problem.solver, 100.0, 5.0, max_step=200.0).ramp(
            problem.setup.set_lateral, 0.0, 600.0
        )
        forces = problem.pair_results().force.copy()
        results[model, slip] = (u_tension, forces, problem.setup.midspan_deflection())
    (u_s, f_s, d_s), (u_l, f_l, d_l) = (
        results["small", "centreline"],
        results["large", "centreline"],
    )
    assert u_l == pytest.approx(u_s, rel=1e-3)
    assert f_l.sum() == pytest.approx(f_s.sum(), rel=1e-3)
    assert np.abs(f_l - f_s).max() < 0.02 * np.abs(f_s).max()
    assert d_l == pytest.approx(d_s, rel=1e-3)
    assert abs(results["large", "surface"][2] - d_l) > 10 * abs(d_l - d_s)


# -- same-layer contact in large sliding ---------------------------------------------------------


def test_facing_point_motion_sees_sliding_and_not_rigid_motion():
    """On a 1+6, a rigid rotation of the strand moves no facing point; one wire slid by 20 µm
    along itself moves the facing points on it by 20 µm (to the chords' turn between nodes,
    1e-3), and those of its own nodes by −20 µm along the neighbour, −20 µm t_a·t_b."""
    geometry = seven_wire(length=0.05)
    pairs = same_layer_pairs(geometry, "packed")
    omega = np.array([0.05, -0.02, 0.1])
    w = np.zeros((len(geometry.points), 6))
    w[:, :3] = geometry.points @ rotation_matrix(omega).T - geometry.points
    w[:, 3:] = omega
    assert np.abs(facing_point_motion(geometry, pairs, w)).max() < 1e-12
    wire = geometry.wire_offsets[2], geometry.wire_offsets[3]  # layer 1's second wire
    w[:] = 0.0
    w[wire[0] : wire[1], :3] = 20e-6 * geometry.tangents()[wire[0] : wire[1]]
    motion = facing_point_motion(geometry, pairs, w)
    on = (pairs.b0 >= wire[0]) & (pairs.b0 < wire[1])
    own = (pairs.a >= wire[0]) & (pairs.a < wire[1])
    assert on.any() and own.any()
    np.testing.assert_allclose(motion[on], 20e-6, rtol=1e-3)
    t = geometry.tangents()
    t_b = (1 - pairs.weight[:, None]) * t[pairs.b0] + pairs.weight[:, None] * t[pairs.b1]
    along = np.einsum("pi,pi->p", t[pairs.a], t_b) / np.linalg.norm(t_b, axis=1)
    np.testing.assert_allclose(motion[own], -20e-6 * along[own], rtol=1e-9)
    assert np.all(motion[~on & ~own] == 0)


def _packed_seven_wire(model: str, h_max: float, lateral: float = 0.0):
    """The 1+6 (0.1 m, elements ≤ ``h_max``) with packed layers, pulled to 10 kN (then pressed by
    a saddle load ``lateral``, N): end displacement at 10 kN, the mid-piece same-layer force per
    length there (N/m), the core | layer-1 forces' sum, and the deflection."""
    geometry = seven_wire(length=0.1, h_max=h_max)
    problem = StrandProblem(
        geometry,
        ContactSettings(same_layer="packed", model=model),
        NewtonOptions(atol=1e-2, max_it=25, stall_after=0),
        setup=SaddleTest,
    )
    LoadStepper(problem.solver, 5e3, 100.0).ramp(problem.setup.set_tension, 0.0, 10e3)
    pairs = same_layer_pairs(geometry, "packed")
    middle = np.abs(geometry.points[pairs.a, 2] - 0.05) < 0.03
    force = problem.model.same_layer_history()["force"]
    per_length = force[middle].sum() / pairs.tributary[middle].sum()
    out = [problem.setup.end_displacement(), per_length, problem.pair_results().force.sum()]
    if lateral:
        LoadStepper(problem.solver, 100.0, 5.0, max_step=200.0).ramp(
            problem.setup.set_lateral, 0.0, lateral
        )
    return (*out, problem.setup.midspan_deflection())


@pytest.mark.slow
def test_large_and_small_sliding_agree_with_packed_layers():
    """The 1+6 with packed layers (its ring of equal wires jams under tension), 10 kN then a
    300 N saddle: the two models agree on the end displacement (1e-4; measured 7e-6) and the
    deflection (0.5 %; measured 0.1 %). The same-layer force differs by the small-sliding pairs'
    discretisation: their facing points lie on the neighbour's chord, whose tilt against the
    wire grows with the element (an O(h) error on approaches of 0.1 µm): 2.1 % at h = 4 mm,
    1.2 % at 2 mm, while the re-found facing points' force per length moves by 0.1 % (measured
    1718 → 1719 N/m; 1715 N/m at 1 mm). The core | layer-1 forces give way as the ring takes
    more (measured −1.3 %)."""
    small, large = (_packed_seven_wire(m, 4e-3, 300.0) for m in ("small", "large"))
    assert large[0] == pytest.approx(small[0], rel=1e-4)
    assert large[3] == pytest.approx(small[3], rel=5e-3)
    coarse = large[1] / small[1] - 1
    assert 0.01 < coarse < 0.03
    assert large[2] == pytest.approx(small[2], rel=0.02) and large[2] < small[2]
    fine_small, fine_large = (_packed_seven_wire(m, 2e-3) for m in ("small", "large"))
    assert fine_large[1] / fine_small[1] - 1 < 0.65 * coarse
    assert fine_large[1] == pytest.approx(large[1], rel=3e-3)


def test_large_sliding_builds_same_layer_pairs():
    """The centre-line slip is accepted in large sliding; each same-layer window holds the
    neighbour's facing segment (reach either side of it) and ends with node a, and the
    distributed mesh keeps it whole."""
    assert ContactSettings(model="large", slip="centreline").slip == "centreline"
    geometry = seven_wire(length=0.05)
    pairs = same_layer_pairs(geometry, "packed")
    settings = ContactSettings(model="large")
    windows = same_layer_windows(geometry, pairs, settings.reach)
    rows = np.concatenate([w.rows for w in windows])
    assert np.array_equal(np.sort(rows), np.arange(len(pairs)))
    x = geometry.points
    for w in windows:
        assert np.array_equal(w.nodes[:, -1], pairs.a[w.rows])
        a_nodes = w.nodes[:, : w.na]
        b0 = np.flatnonzero(a_nodes[0] == pairs.b0[w.rows[0]])
        assert len(b0) == 1 and a_nodes[0, b0[0] + 1] == pairs.b1[w.rows[0]]
        room = np.linalg.norm(x[a_nodes[:, 1:]] - x[a_nodes[:, :-1]], axis=2).sum(axis=1)
        assert np.all(room > 2 * settings.reach) or np.any(w.ends)
    stencils = strand_stencils(geometry, settings)
    assert sum(len(s) for s in stencils) >= len(pairs) + len(geometry.pairs)


@needs_mpirun
@pytest.mark.slow
def test_large_sliding_same_layer_pairs_are_the_same_on_1_and_2_ranks(tmp_path):
    """``test_mpi.test_same_layer_pairs_are_the_same_on_1_and_2_ranks`` in large sliding: the
    1+6's touching ring, every same-layer window (the neighbour's nodes within reach of the
    facing segment, then node a) kept whole on the rank that evaluates it; at a tight tolerance
    on a fixed load path the tables agree to 1e-8."""
    (tmp_path / "seven.toml").write_text(SEVEN_WIRE)
    same = ["--set", 'contact.model="large"', *TOUCHING]
    _run_and_compare(
        tmp_path, ["seven.toml", *same], ranks=(2,), tag="large_same_layer", counts=("cuts",)
    )


def test_a_large_sliding_run_with_both_variants_continues_from_a_checkpoint(tmp_path):
    """The 1+6 case in large sliding with same-layer pairs and the centre-line slip, continued
    from the checkpoint of its 8th step, takes the uninterrupted run's steps to 1e-10: the
    same-layer pairs' sliding segments and the centre-line slip operator (rebuilt from the
    restored closest points) come back with it."""
    seven = tmp_path / "seven.toml"
    seven.write_text(SEVEN_WIRE)
    large = ['contact.model="large"', 'contact.same_layer="nominal"', 'contact.slip="centreline"']
    case = load_case(seven, [*QUIET, *large])
    checkpoint = uninterrupted_with_checkpoint(case, tmp_path / "whole", 8)
    run_case(case, tmp_path / "continued", restart=checkpoint)
    assert_continues(tmp_path / "whole", tmp_path / "continued", 8, 1e-10)
