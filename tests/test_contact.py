"""The contact element: exact tangents, crossed beams, a helix on a core, objectivity, Newton rate."""

from __future__ import annotations

import numpy as np
import pytest
from dolfinx import fem
from mpi4py import MPI

from forms import CircularSection, ReissnerBeam
from strand.cable.description import CableError
from strand.cable.geometry import LINE, POINT
from strand.cable.mesh import beam_space, input_to_block, polyline_mesh
from strand.contact.element import ContactGroup
from strand.contact.friction_laws import ElasticSlip, Mindlin
from strand.contact.hertz import compliance as compliance_of
from strand.contact.hertz import mindlin_ratio, point_coefficient
from strand.contact.kinematics import (
    NORMALS,
    gap_derivatives,
    rotation_matrix,
    stencil_nodes,
    tangent_map,
)
from strand.contact.microslip import MindlinDeresiewicz
from strand.contact.normal_laws import HertzLineLaw, HertzPointLaw, PenaltyLaw
from strand.model.contact_settings import ContactSettings
from strand.model.problem import StrandProblem
from strand.model.strand_contact import centreline_gaps
from strand.setups.saddle import SaddleTest, saddle_weights
from strand.solver import LoadStepFailure, LoadStepper, NewtonOptions, NodalLoad, NonlinearProblem
from strand_cases import check_state_and_tangent, nineteen_wire, seven_wire

R_A, R_B = 1.5e-3, 2.0e-3  # m
K_N, MU, G_LIM = 5e7, 0.5, 5e-6
KINDS = [(n, line) for n in NORMALS for line in (False, True)]
HERTZ = ("hertz", "hertz_microslip")


def pair_laws(compliance: str, line: bool, angle: float, n_pairs: int):
    """Penalty + elastic slip (K_N, G_LIM), or Hertz + Mindlin (or Mindlin–Deresiewicz's
    microslip) for steel wires of R_A, R_B."""
    full = np.full(n_pairs, 1.0)
    if compliance == "penalty":
        return PenaltyLaw(K_N * full), ElasticSlip(MU * full, G_LIM)
    c = compliance_of(2.1e11 * full, 0.3)
    normal = (
        HertzLineLaw(R_A * full, R_B * full, c, c, 5e-3 * full)
        if line
        else HertzPointLaw(point_coefficient(R_A, R_B, angle, 2.1e11, 0.3, 2.1e11, 0.3) * full)
    )
    kind = MindlinDeresiewicz if compliance == "hertz_microslip" else Mindlin
    return normal, kind(MU * full, mindlin_ratio(2.1e11, 0.3, 2.1e11, 0.3))


def crossed_pair(
    normal: str,
    line: bool,
    angle: float,
    n_pairs: int = 4,
    h: float = 3e-3,
    compliance: str = "penalty",
    slip: str = "surface",
    offset: float = 0.0,
):
    """Pairs of two straight wires crossing at ``angle`` (a along x, b above it), as a group.

    Each pair uses its own nodes (stencil blocks 0..k·n_pairs), so random per-pair states can be
    imposed. For line pairs the wires are nearly parallel (angle 0.1 rad; Hertz: a 5 mm line);
    ``offset``: b faces a's centre line that far along a from node a (m).
    """
    if line:
        angle = 0.1
    ta = np.array([1.0, 0.0, 0.0])
    tb = np.array([np.cos(angle), np.sin(angle), 0.0])
    xa, xb = np.zeros(3), np.array([0.0, 0.0, R_A + R_B])
    where = {"a": xa, "b": xb, "a-": xa - h * ta, "a+": xa + h * ta}
    where |= {"b-": xb - h * tb, "b+": xb + h * tb}
    roles = stencil_nodes(normal, line)
    k = len(roles)
    X = np.repeat(np.stack([where[r] for r in roles])[None], n_pairs, 0)
    stencils = np.arange(n_pairs * k).reshape(n_pairs, k)
    n0 = np.tile([0.0, 0.0, 1.0], (n_pairs, 1))
    t0 = np.repeat(np.stack([ta, tb])[None], n_pairs, 0)
    full = np.full(n_pairs, 1.0)
    laws = pair_laws(compliance, line, angle, n_pairs)
    return ContactGroup(
        stencils,
        X,
        line,
        R_A * full,
        R_B * full,
        n0,
        laws[0],
        friction_law=laws[1],
        normal=normal,
        tangent0=t0,
        slip=slip,
        offset=offset * full if offset else None,
    )


@pytest.mark.parametrize(("normal", "line"), KINDS)
def test_gap_hessian_matches_finite_differences(normal, line):
    """The complex-step Hessian of the gap agrees with differences of the hand-written gradient."""
    rng = np.random.default_rng(3)
    group = crossed_pair(normal, line, np.radians(40))
    P, k = group.stencils.shape
    x = group.X + rng.normal(scale=2e-4, size=group.X.shape)
    theta = rng.normal(scale=0.3, size=group.X.shape)
    ref = gap_derivatives(normal, line, x, theta, group.data, hessian_where=lambda g: g < np.inf)
    H_ref = ref.full_hessian()
    y = np.concatenate([x, theta], axis=2).reshape(P, 6 * k)  # stencil dofs, (u, θ) per node
    H = np.zeros_like(H_ref)
    step = 1e-8
    for j in range(6 * k):
        yp, ym = y.copy(), y.copy()
        yp[:, j] += step
        ym[:, j] -= step
        gp = gap_derivatives(normal, line, *np.split(yp.reshape(P, k, 6), 2, axis=2), group.data)
        gm = gap_derivatives(normal, line, *np.split(ym.reshape(P, k, 6), 2, axis=2), group.data)
        H[:, :, j] = (gp.gradient - gm.gradient) / (2 * step)
        # the gradient itself against differences of the gap
        assert np.allclose((gp.gap - gm.gap) / (2 * step), ref.gradient[:, j], atol=1e-6)
    scale = np.abs(H_ref).max()
    assert scale > 1.0 if normal != "frozen" else scale == 0.0
    assert np.abs(H - H_ref).max() <= 1e-6 * max(scale, 1.0)
    assert np.allclose(H_ref, H_ref.transpose(0, 2, 1), atol=1e-9 * max(scale, 1.0))


@pytest.mark.parametrize(
    ("normal", "line", "compliance", "slip", "offset"),
    [(n, line, "penalty", "surface", 0.0) for n, line in KINDS]
    + [("director", line, c, "surface", 0.0) for line in (False, True) for c in HERTZ]
    + [
        (n, line, c, "centreline", 0.0)
        for n in ("frozen", "director")
        for line in (False, True)
        for c in ("penalty", "hertz")
    ]
    + [("director", True, c, "surface", 1.5e-3) for c in ("penalty", *HERTZ)],
)
def test_pair_tangent_matches_finite_differences_open_stick_slip(
    normal, line, compliance, slip, offset
):
    """Residual derivatives in the three states, after a committed step with random rotations
    (line pairs also with b facing a 1.5 mm from node a: the same-layer pairs' "node" stencil)."""
    rng = np.random.default_rng(7)
    group = crossed_pair(
        normal, line, np.radians(25), compliance=compliance, slip=slip, offset=offset
    )
    P, k = group.stencils.shape
    w = np.zeros((P * k, 6))
    w[:, 3:] = rng.normal(scale=0.05, size=(P * k, 3))
    w[group.stencils[:, 1], 2] -= 2e-6
    group.evaluate(w, True)
    group.commit()
    assert np.all(group.committed_force > 0)
    states = {"stick": (1e-7, -1e-6), "slip": (3e-5, -1e-6), "open": (0.0, 5e-5)}
    for state, (tangential, normal_move) in states.items():
        w2 = w.copy()
        w2[group.stencils[:, 1], 0] += tangential
        w2[group.stencils[:, 1], 2] += normal_move
        w2[:, :3] += rng.normal(scale=1e-8, size=(P * k, 3))
        K_fd, scale = check_state_and_tangent(group, w2, state)
        K = group.evaluate(w2, True)[1]
        assert np.abs(K - K_fd[:, :, group.dofs]).max() <= 2e-6 * scale, state
        left_out = np.setdiff1d(np.arange(6 * k), group.dofs)  # dofs the layout omits: no effect
        assert np.abs(K_fd[:, :, left_out]).max(initial=0.0) <= 2e-6 * scale
        if state == "slip":
            assert not np.allclose(K, K.transpose(0, 2, 1))  # the slip tangent is unsymmetric


def test_an_offset_line_pair_slips_with_the_facing_point_of_a_turning_section():
    """b faces a's centre line s along a's tangent t from node a: turning node a's section by a
    small δ about the pair's normal n moves that facing point by δ n × (s t), so b's surface
    point slips by −δ s n × t against it (no offset: no slip), while the gap stays."""
    s, delta = 1.5e-3, 1e-6
    for offset, expected in [(s, -delta * s), (0.0, 0.0)]:
        group = crossed_pair("director", True, 0.0, n_pairs=1, offset=offset)
        w = np.zeros((2, 6))
        w[1, 2] = -1e-6  # pressed: the pair carries a force, so friction is evaluated
        group.evaluate(w, True)
        group.commit()
        n = group.state.normal[0]
        t_a = np.array([1.0, 0.0, 0.0])
        w2 = w.copy()
        w2[0, 3:] = delta * n
        group.evaluate(w2, True)
        slip = group._friction[0][0]
        assert np.allclose(slip, expected * np.cross(n, t_a), rtol=1e-6, atol=1e-15)
        assert group.state.gap[0] == pytest.approx(-1e-6, rel=1e-9)


@pytest.mark.parametrize("angle", [90.0, 25.0])
def test_crossed_pair_friction_stick_slip_unload_reload(angle):
    """A pressed crossing dragged tangentially: stick with slip |t|/K_T, slip at μP, unload, reload."""
    group = crossed_pair("neighbour", False, np.radians(angle), n_pairs=1)
    k = group.stencils.shape[1]
    w = np.zeros((k, 6))
    press = 4e-6
    w[1, 2] = -press  # node b down by 4 µm
    group.evaluate(w, True)
    group.commit()
    P = K_N * press
    assert group.committed_force[0] == pytest.approx(
        P, rel=1e-9
    )  # normal force = K_N × penetration
    K_T = MU * P / G_LIM
    direction = np.array([np.cos(0.3), np.sin(0.3), 0.0])

    def drag(s):
        w2 = w.copy()
        w2[1, :3] += s * direction
        w2[2:, :3] += 0.0
        group.evaluate(w2, True)
        return group.state.traction[0], group.state.slipping[0]

    s_stick = 0.4 * MU * P / K_T
    t, slipping = drag(s_stick)
    assert not slipping
    assert np.allclose(t, K_T * s_stick * direction, rtol=1e-9, atol=1e-12)
    t, slipping = drag(3 * MU * P / K_T)  # beyond the cone: slips at μP along the motion
    assert slipping
    assert np.allclose(t, MU * P * direction, rtol=1e-9)
    # commit the slipped state, then unload by half the elastic range: sticks, traction drops
    w[1, :3] += 3 * MU * P / K_T * direction
    group.evaluate(w, True)
    group.commit()
    back = -0.5 * MU * P / K_T
    t, slipping = drag(back)
    assert not slipping
    assert np.allclose(t, 0.5 * MU * P * direction, rtol=1e-9)
    t, slipping = drag(-2.5 * MU * P / K_T)  # reload the other way: slips at −μP
    assert slipping
    assert np.allclose(t, -MU * P * direction, rtol=1e-9)


def clamped_clamped_stiffness(section_d, E, nu, length):
    """Midspan stiffness P/δ of a clamped-clamped Timoshenko beam (N/m)."""
    s = CircularSection(section_d, E, nu)
    return 1.0 / (length**3 / (192 * s.EI) + length / (4 * s.GA))


@pytest.mark.parametrize("angle", [90.0, 25.0])
def test_crossed_beams_share_a_load_through_the_contact(angle):
    """Two clamped-clamped beams crossing; a load P on the upper one at the crossing.

    The contact is a spring K_N in series with the lower beam, in parallel with the upper one:
    p = P (1/k_B) / (1/k_A + 1/k_B + 1/K_N), and the penetration δ_B − δ_A = p/K_N.
    """
    length, n = 0.2, 40  # m, cells per beam
    d, E, nu = 2 * R_A, 200e9, 0.3  # both beams alike (R_A = R_B would not matter here)
    s = np.linspace(-length / 2, length / 2, n + 1)
    tb = np.array([np.cos(np.radians(angle)), np.sin(np.radians(angle)), 0.0])
    pts = np.vstack([s[:, None] * [1.0, 0, 0], s[:, None] * tb + [0, 0, 2 * R_A]])
    cells = np.vstack([np.column_stack([np.arange(n), np.arange(1, n + 1)])] * 2)
    cells[n:] += n + 1
    mesh = polyline_mesh(MPI.COMM_WORLD, pts, cells)
    V = beam_space(mesh)
    w = fem.Function(V)
    beam = ReissnerBeam(w, CircularSection(d, E, nu))
    i2b = input_to_block(V)
    ends = i2b[[0, n, n + 1, 2 * n + 1]]
    bc = fem.dirichletbc(np.zeros(6), ends.astype(np.int32), V)
    a, b = i2b[n // 2], i2b[n + 1 + n // 2]
    stencil = i2b[[n // 2, n + 1 + n // 2, n // 2 - 1, n // 2 + 1, n + n // 2, n + 2 + n // 2]]
    group = ContactGroup(
        stencil[None],
        pts[[n // 2, n + 1 + n // 2, n // 2 - 1, n // 2 + 1, n + n // 2, n + 2 + n // 2]][None],
        False,
        [R_A],
        [R_A],
        [[0, 0, 1.0]],
        PenaltyLaw(np.array([K_N])),
        friction_law=None,
        normal="neighbour",
    )
    load = NodalLoad([b], [[0, 0, -1.0, 0, 0, 0]])
    P = 2.0  # N: deflection 50 µm = d/60, so the membrane stiffening stays below 1e-3
    # the discrete midspan stiffness of one beam, at the load each beam will carry (P/2)
    load.factor = P / 2
    alone = NonlinearProblem(beam.residual(), w, [bc], terms=[load], petsc_options_prefix="alone_")
    assert alone.solve().converged
    k_beam = -P / 2 / w.x.array.reshape(-1, 6)[b, 2]
    assert k_beam == pytest.approx(clamped_clamped_stiffness(d, E, nu, length), rel=5e-3)
    w.x.array[:] = 0.0
    load.factor = P
    solver = NonlinearProblem(beam.residual(), w, [bc], terms=[group, load])
    result = solver.solve()
    assert result.converged and result.iterations <= 4
    p_expected = P / (2 + k_beam / K_N)
    u = w.x.array.reshape(-1, 6)
    p = group.state.force[0]
    assert p == pytest.approx(p_expected, rel=1e-5)
    assert u[a, 2] - u[b, 2] == pytest.approx(p / K_N, rel=1e-6)  # penetration = p/K_N
    assert u[a, 2] == pytest.approx(-p / k_beam, rel=1e-5)
    assert np.allclose(u[[a, b], :2], 0.0, atol=1e-12)  # a pure normal force: no sideways push


@pytest.mark.parametrize("normal", ["neighbour", "director"])
@pytest.mark.parametrize("line", [False, True])
def test_rigid_rotation_leaves_pair_forces_unchanged(normal, line):
    rng = np.random.default_rng(11)
    group = crossed_pair(normal, line, np.radians(60))
    P, k = group.stencils.shape
    w = np.zeros((P * k, 6))
    w[:, :3] = rng.normal(scale=1e-6, size=(P * k, 3))
    w[group.stencils[:, 1], 2] -= 3e-6
    w[:, 3:] = rng.normal(scale=0.02, size=(P * k, 3))
    f0, _ = group.evaluate(w, True)
    g0, n0 = group.state.gap.copy(), group.state.normal.copy()
    assert np.all(group.state.force > 0)
    Q = rotation_matrix(np.array([0.4, -0.9, 1.3]))  # a 93° rotation about an oblique axis
    centre = np.array([0.01, -0.02, 0.005])
    X = group.X.reshape(-1, 3)
    x = X + w[group.stencils.ravel(), :3]
    x_rot = (x - centre) @ Q.T + centre
    w_rot = w.copy()
    w_rot[group.stencils.ravel(), :3] = x_rot - X
    for i in range(len(w)):
        w_rot[i, 3:] = _log(Q @ rotation_matrix(w[i, 3:]))
    group.evaluate(w_rot, True)
    assert np.allclose(group.state.gap, g0, rtol=1e-9, atol=1e-15)
    assert np.allclose(group.state.normal, n0 @ Q.T, atol=1e-9)
    # the frozen normal is not objective: the same motion changes its gap by millimetres
    if not line and normal == "neighbour":
        frozen = crossed_pair("frozen", False, np.radians(60))
        ws = w[: 2 * P].copy()
        frozen.evaluate(ws, True)
        before = frozen.state.gap.copy()
        ws2 = w_rot[: 2 * P].copy()
        frozen.evaluate(ws2, True)
        assert np.abs(frozen.state.gap - before).max() > 1e-4


def _log(R):
    """Rotation vector of a rotation matrix (angles below π)."""
    c = np.clip((np.trace(R) - 1) / 2, -1, 1)
    angle = np.arccos(c)
    axial = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]) / 2
    return axial * (angle / np.sin(angle) if angle > 1e-12 else 1.0)


def test_small_rigid_rotation_makes_no_slip():
    """An incremental rigid rotation moves both surface points alike: slip O(ω²), traction ~0."""
    group = crossed_pair("neighbour", False, np.radians(50), n_pairs=1)
    k = group.stencils.shape[1]
    w = np.zeros((k, 6))
    w[1, 2] = -3e-6
    group.evaluate(w, True)
    group.commit()
    omega = np.array([2e-4, -1e-4, 3e-4])
    Q = rotation_matrix(omega)
    x = group.X[0] + w[:, :3]
    w2 = w.copy()
    w2[:, :3] = x @ Q.T - group.X[0]
    w2[:, 3] = w[:, 3] + omega[0]
    w2[:, 4] = w[:, 4] + omega[1]
    w2[:, 5] = w[:, 5] + omega[2]
    group.evaluate(w2, True)
    K_T = MU * group.committed_force[0] / G_LIM
    slip = np.linalg.norm(group.state.traction[0]) / K_T
    assert slip < 1e-3 * np.linalg.norm(omega) * (R_A + R_B)


def _committed_pairs(line: bool, turned: float):
    """A surface-slip and a centre-line-slip pair, pressed and committed with their nodes turned
    by random rotations of up to ``turned`` rad."""
    groups = [
        crossed_pair("director", line, np.radians(35), n_pairs=1, slip=s)
        for s in ("surface", "centreline")
    ]
    k = groups[0].stencils.shape[1]
    w = np.zeros((k, 6))
    w[1, 2] = -3e-6
    w[:, 3:] = np.random.default_rng(5).uniform(-turned, turned, size=(k, 3))
    for group in groups:
        group.evaluate(w, True)
        group.commit()
    return groups, w


def _increment(group, w, omega, du_b=None, spin_b=None):
    """(Δu_a, Δθ_a, Δu_b, Δθ_b) of a small rigid rotation ω (spatial) of the pair about node a,
    then b moved by du_b and turned by spin_b (spatial; default none)."""
    du_b = np.zeros(3) if du_b is None else du_b
    spin_b = np.zeros(3) if spin_b is None else spin_b
    x_b = (R_A + R_B) * group.state.normal[0]
    dq = np.zeros(12)
    dq[3:6] = np.linalg.solve(tangent_map(w[0, 3:]), omega)
    dq[9:12] = np.linalg.solve(tangent_map(w[1, 3:]), omega + spin_b)
    dq[6:9] = np.cross(omega, x_b) + du_b
    return dq


@pytest.mark.parametrize("line", [False, True])
def test_centreline_slip_is_objective(line):
    """No centre-line slip for a small rigid rotation of a pair whose nodes are already turned by
    up to 0.3 rad; a translation in the tangent plane is slip as it is for the surface points."""
    (surface, centre), w = _committed_pairs(line, 0.3)
    S = centre.slip_operator()[0]
    omega = np.array([2e-4, -1e-4, 3e-4])
    rigid = S @ _increment(centre, w, omega)
    assert np.linalg.norm(rigid) < 1e-9 * np.linalg.norm(omega) * (R_A + R_B)
    shift = np.cross(centre.state.normal[0], [0.3, -0.5, 0.8]) * 1e-6  # in the tangent plane
    dq = _increment(centre, w, np.zeros(3), du_b=shift)
    assert np.allclose(S @ dq, shift, atol=1e-15)
    assert np.allclose(surface.slip_operator()[0] @ dq, shift, atol=1e-15)


def test_centreline_slip_is_blind_to_spin_and_sees_rolling():
    """A crossing wire's spin about its own axis: the surface points slip by r_b × spin, the
    centre lines not at all. Rolling (the spin with b's centre moving so that its surface point
    stays): no surface slip, a centre-line slip of the centre's motion."""
    (surface, centre), w = _committed_pairs(False, 0.0)
    n = centre.state.normal[0]
    angle = np.radians(35)
    spin = 1e-3 * np.array([np.cos(angle), np.sin(angle), 0.0])  # about b's axis
    turned = R_B * np.cross(spin, -n)  # the motion of b's surface point
    spun = _increment(centre, w, np.zeros(3), spin_b=spin)
    rolling = _increment(centre, w, np.zeros(3), du_b=-turned, spin_b=spin)
    S_surface, S_centre = surface.slip_operator()[0], centre.slip_operator()[0]
    assert np.linalg.norm(S_centre @ spun) < 1e-15
    assert np.allclose(S_surface @ spun, turned, atol=1e-15)
    assert np.linalg.norm(S_surface @ rolling) < 1e-15
    assert np.allclose(S_centre @ rolling, -turned, atol=1e-15)


def test_helix_on_core_line_load():
    """Contact line load of a tensioned helix on its core: X = T sin²α / r (docs/theory.md §5.6)."""
    geometry = seven_wire(lay_angle=12.0)
    problem = StrandProblem(
        geometry, ContactSettings(same_layer="off"), NewtonOptions(atol=1e-4), setup=SaddleTest
    )
    problem.setup.set_tension(20e3)
    assert problem.solver.solve().converged
    layer = geometry.cable.layers[1]
    alpha, r = layer.alpha, layer.radius
    # axial force of the layer-1 wires, from the section forces, away from the ends
    Q = fem.functionspace(problem.cmesh.mesh, ("DG", 0))
    N = fem.Function(Q)
    N.interpolate(fem.Expression(problem.beam.N[0], Q.element.interpolation_points))
    mid = problem.cmesh.mesh.geometry.x[problem.cmesh.mesh.geometry.dofmaps[0]].mean(axis=1)[:, 2]
    cells = problem.cmesh.layer_tags.indices[problem.cmesh.layer_tags.values == 1]
    inner = cells[np.abs(mid[cells] - geometry.length / 2) < geometry.length / 4]
    T_wire = N.x.array[inner].mean()
    pairs = geometry.pairs
    res = problem.pair_results()
    z = geometry.points[pairs.b, 2]
    inside = np.abs(z - geometry.length / 2) < geometry.length / 4
    X = res.force[inside].sum() / pairs.tributary[inside].sum()  # N per m of wire
    print(f"X = {X:.1f} N/m, T sin²α/r = {T_wire * np.sin(alpha) ** 2 / r:.1f} N/m")
    assert X == pytest.approx(T_wire * np.sin(alpha) ** 2 / r, rel=0.02)
    assert T_wire == pytest.approx(20e3 / 7, rel=0.2)  # sanity: the wires share the load


@pytest.mark.parametrize("normal", ["director", "neighbour"])
def test_newton_converges_quadratically_on_a_seven_wire_strand(normal):
    """Errors of the Newton iterates (vs the converged state) fall quadratically, 40 kN, friction on."""
    geometry = seven_wire()
    iterates = []
    options = NewtonOptions(atol=1e-12, rtol=1e-16, stol=0.0, max_it=6)
    problem = StrandProblem(
        geometry, ContactSettings(same_layer="off", normal=normal), options, setup=SaddleTest
    )
    snes = problem.solver.solver
    problem.solver.monitor = lambda i, r: iterates.append(snes.getSolution().array_r.copy())
    histories = []
    for T in (10e3, 40e3):  # the second step carries friction (K_T from the first)
        iterates.clear()
        problem.setup.set_tension(T)
        result = problem.solver.solve()
        histories.append(result.residuals)
        problem.solver.commit()
        final = problem.w.x.array
        errors = [np.linalg.norm(x - final) / np.linalg.norm(final) for x in iterates]
        print(f"T = {T / 1e3:.0f} kN: residuals", " ".join(f"{r:.1e}" for r in result.residuals))
        print("   relative errors", " ".join(f"{e:.1e}" for e in errors))
        e = [x for x in errors if x > 1e-11]
        assert len(e) >= 3
        orders = [np.log(e[i + 1] / e[i]) / np.log(e[i] / e[i - 1]) for i in range(1, len(e) - 1)]
        assert max(orders) > 1.8, orders
        assert result.residuals[3] < 1e-8 * result.residuals[0]
    assert np.mean(problem.contact[0].committed_force > 0) > 0.95  # all but the end pairs


@pytest.mark.parametrize("normal", ["director", "neighbour"])
def test_gap_consistency_on_a_bent_strand(normal):
    """The element's gaps match the gaps measured on the deformed centrelines (within 2 µm).

    Measured gap: the change since t = 0 of the closest distance between the deformed polylines
    near the pair (two cells either side of each node) minus the radii.
    """
    geometry = nineteen_wire()
    problem = StrandProblem(
        geometry,
        ContactSettings(same_layer="off", normal=normal),
        NewtonOptions(atol=1e-4),
        setup=SaddleTest,
    )
    stepper = LoadStepper(problem.solver, 10e3, 1e3)
    stepper.ramp(problem.setup.set_tension, 0.0, 20e3)
    stepper.step = 250.0
    stepper.ramp(problem.setup.set_lateral, 0.0, 2000.0)
    deflection = problem.setup.midspan_deflection()
    print(f"deflection {deflection * 1e3:.3f} mm, steps {[r.iterations for r in stepper.history]}")
    assert deflection > 1e-4
    x = problem.positions()
    measured = centreline_gaps(geometry, x) - centreline_gaps(geometry, geometry.points)
    element = problem.pair_results().gap
    pairs = geometry.pairs
    for kind in (LINE, POINT):
        sel = pairs.kind == kind
        assert np.abs(element[sel]).max() > 5e-7  # the pairs are really loaded
        error = np.abs(element[sel] - measured[sel])
        print(
            f"kind {kind}: max |g| {np.abs(element[sel]).max():.2e} m, max error {error.max():.2e} m"
        )
        assert error.max() < 2e-6


def test_saddle_forces_sum_to_the_load_with_no_side_force():
    rng = np.random.default_rng(0)
    phi = rng.uniform(0, 2 * np.pi, 40)
    points = np.column_stack([0.01 * np.cos(phi), 0.01 * np.sin(phi), rng.uniform(0, 0.02, 40)])
    for direction in ([1.0, 0, 0], [0, -1.0, 0]):
        idx, forces = saddle_weights(points, np.array(direction))
        assert np.allclose(forces.sum(axis=0), direction, atol=1e-12)
        inward = -points[idx, :2] / np.linalg.norm(points[idx, :2], axis=1)[:, None]
        assert np.all(np.einsum("pi,pi->p", forces[:, :2], inward) > 0)  # every force presses in


def test_contact_settings_default_normal_follows_friction():
    assert ContactSettings().normal == "director"
    assert ContactSettings(friction=False).normal == "frozen"
    assert ContactSettings(normal="neighbour", friction=False).normal == "neighbour"


def test_contact_settings_reject_bad_input():
    with pytest.raises(CableError, match="normal = 'radial' is unknown"):
        ContactSettings(normal="radial")
    with pytest.raises(CableError, match="k_point = -1"):
        ContactSettings(k_point=-1)
    with pytest.raises(CableError, match="model = 'huge' is unknown"):
        ContactSettings(model="huge")
    with pytest.raises(CableError, match="reach = 0"):
        ContactSettings(model="large", reach=0)
    with pytest.raises(CableError, match="g_lim apply to compliance"):
        ContactSettings(compliance="hertz", g_lim=1e-6)
    with pytest.raises(CableError, match="compliance = 'stiff' is unknown"):
        ContactSettings(compliance="stiff")
    with pytest.raises(
        CableError, match="slip = 'centre' is unknown; choose surface or centreline"
    ):
        ContactSettings(slip="centre")
    from strand.app.case import CaseError, case_from_dict  # unknown keys: the case file's [contact]

    with pytest.raises(CaseError, match=r"unknown setting\(s\) in \[contact\]: \['kn'\]"):
        case_from_dict({"contact": {"kn": 1}})


@pytest.mark.parametrize("angle", [0.0, 1e-6, 0.01, 0.1, 0.2999, 0.3001, 1.0, 3.0])
def test_rotation_coefficients_exact_on_both_sides_of_the_series_switch(angle):
    """sin x/x, (1 − cos x)/x², (x − sin x)/x³ against their series in exact rational arithmetic."""
    from fractions import Fraction
    from math import factorial

    from strand.contact.kinematics import _rotation_coefficients

    def exact(first):
        x = Fraction(angle)
        return float(sum((-1) ** k * x ** (2 * k) / factorial(2 * k + first) for k in range(40)))

    theta = np.array([[0.6, -0.8, 0.0]]) * angle
    values = _rotation_coefficients(theta)
    for value, first in zip(values, (1, 2, 3), strict=True):
        assert value[0] == pytest.approx(exact(first), rel=1e-14 if angle < 0.3 else 1e-9)


def test_rotation_coefficients_of_a_wild_iterate_do_not_raise():
    """A diverging Newton iterate (rotations of 1e200 rad) gives non-finite coefficients, which
    SNES reports as DIVERGED_FUNCTION_NANORINF so that the step is cut, instead of an
    OverflowError from the series' term count (it crashed a Cardinal run at κ = 0.5 1/m)."""
    from strand.contact.kinematics import _rotation_coefficients

    with np.errstate(all="ignore"):
        c = _rotation_coefficients(np.array([[1e200, 0.0, 0.0], [0.1, 0.0, 0.0]]))
    assert all(np.isfinite(v[1]) for v in c)
    assert c[0][1] == pytest.approx(np.sin(0.1) / 0.1, rel=1e-15)


def test_a_diverged_newton_under_friction_is_cut_not_accepted():
    """Two crossed beams pressed together (P) and a tangential load on the upper one, which is
    free to slide along x: beyond μP there is no equilibrium. Newton then blows up (residual
    ~1e31 N, ||w|| ~ 1e19 m) until PETSc's relative step test ``stol`` is met; that must count as
    a failure. The load stepper must cut, commit only states in equilibrium below μP, and stop
    with a clear message at the last converged one."""
    length, n = 0.2, 40
    s = np.linspace(-length / 2, length / 2, n + 1)
    pts = np.vstack([s[:, None] * [1.0, 0, 0], s[:, None] * [0, 1.0, 0] + [0, 0, 2 * R_A]])
    cells = np.vstack([np.column_stack([np.arange(n), np.arange(1, n + 1)])] * 2)
    cells[n:] += n + 1
    mesh = polyline_mesh(MPI.COMM_WORLD, pts, cells)
    V = beam_space(mesh)
    w = fem.Function(V)
    beam = ReissnerBeam(w, CircularSection(2 * R_A, 200e9, 0.3))
    i2b = input_to_block(V)
    bcs = [fem.dirichletbc(np.zeros(6), i2b[[0, n]].astype(np.int32), V)]
    upper_ends = i2b[[n + 1, 2 * n + 1]]
    for c in range(1, 6):  # the upper beam's ends: free along x only
        bcs.append(fem.dirichletbc(0.0, (6 * upper_ends + c).astype(np.int32), V.sub(c)))
    a, b = n // 2, n + 1 + n // 2
    group = ContactGroup(
        i2b[[a, b]][None],
        pts[[a, b]][None],
        False,
        [R_A],
        [R_A],
        [[0, 0, 1.0]],
        PenaltyLaw(np.array([K_N])),
        friction_law=ElasticSlip(np.array([MU]), G_LIM),
        normal="director",
        tangent0=np.array([[[1.0, 0, 0], [0, 1.0, 0]]]),
    )
    press = NodalLoad([i2b[b]], [[0, 0, -2.0, 0, 0, 0]], 1.0)
    drag = NodalLoad([i2b[b]], [[1.0, 0, 0, 0, 0, 0]], 0.0)
    options = NewtonOptions(atol=1e-7)
    solver = NonlinearProblem(beam.residual(), w, bcs, terms=[group, press, drag], options=options)
    assert solver.solve().converged
    solver.commit()
    mu_p = MU * group.state.force[0]

    drag.factor = 1.2 * mu_p
    result = solver.solve()
    assert not result.converged
    assert not result.residual <= 1.0  # it did blow up: this is the case the check is for
    solver.rollback()

    committed = []
    stepper = LoadStepper(
        solver, first_step=0.6 * mu_p, min_step=0.6 * mu_p / 2**6, on_step=committed.append
    )
    with pytest.raises(LoadStepFailure, match="no convergence"):
        stepper.ramp(lambda f: setattr(drag, "factor", f), 0.0, 1.5 * mu_p, "drag")
    assert committed and all(r.load < mu_p for r in committed)
    assert max(r.load for r in committed) > 0.95 * mu_p  # the cuts closed in on μP
    assert all(r.residuals[-1] <= options.atol for r in committed)
    assert np.all(np.isfinite(w.x.array)) and np.abs(w.x.array).max() < 1e-3
    assert drag.factor == committed[-1].load  # the load is back at the last converged state
