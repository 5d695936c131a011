"""The public contact API on beams of a user's own mesh: pairs found, gaps measured, closed forms."""

from __future__ import annotations

import numpy as np
import pytest
from dolfinx import fem
from mpi4py import MPI

from forms import CircularSection, ReissnerBeam
from strand.cable.mesh import beam_space, polyline_mesh
from strand.contact import (
    ContactError,
    ElasticSlip,
    PenaltyLaw,
    beam_nodes,
    candidate_pairs,
    candidate_stencils,
    contact_terms,
    dof_values,
    hertz_laws,
    locate_nodes,
    node_pairs,
    sliding_terms,
)
from strand.contact.hertz import point_coefficient
from strand.solver import NewtonOptions, NodalLoad, NonlinearProblem

R = 1.5e-3  # m, both beams
E, NU = 200e9, 0.3
K_N = 5e7  # N/m


def two_beams(direction_b, lift: float, length=0.2, n=40, n_b=None, offset=0.0):
    """Beam a along x at z = 0; beam b along ``direction_b`` (in the xy plane) through
    (offset, 0, 2R + lift). Returns V, the nodes of a and of b."""
    n_b = n_b or n
    s = np.linspace(-length / 2, length / 2, n + 1)
    t = np.linspace(-length / 2, length / 2, n_b + 1)
    d = np.asarray(direction_b, float) / np.linalg.norm(direction_b)
    pts = np.vstack([s[:, None] * [1.0, 0, 0], t[:, None] * d + [offset, 0, 2 * R + lift]])
    cells = np.vstack(
        [
            np.column_stack([np.arange(n), np.arange(1, n + 1)]),
            n + 1 + np.column_stack([np.arange(n_b), np.arange(1, n_b + 1)]),
        ]
    )
    V = beam_space(polyline_mesh(MPI.COMM_WORLD, pts, cells))
    return V, locate_nodes(V, pts[: n + 1]), locate_nodes(V, pts[n + 1 :])


def test_candidate_pairs_of_crossing_beams_is_one_pair_at_the_crossing():
    """Beam b crosses beam a at 90°, 20 µm above it: every node of b within 1 mm of a's surface is
    a candidate, one pair is kept (the crossing's nodes), with the measured gap and n = e_z."""
    lift = 20e-6
    V, a, b = two_beams([0.0, 1.0, 0.0], lift)
    pairs = candidate_pairs(V, a, b, R, R, reach=1e-3)
    assert len(pairs) == 1 and not pairs.line
    assert pairs.a[0] == a[20] and pairs.b[0] == b[20]
    assert pairs.initial_gap[0] == pytest.approx(lift, rel=1e-9)
    np.testing.assert_allclose(pairs.normal[0], [0.0, 0.0, 1.0], atol=1e-15)
    assert pairs.crossing_angle[0] == pytest.approx(np.pi / 2, rel=1e-12)
    with pytest.raises(ValueError, match="no node of beam b is within reach"):
        candidate_pairs(V, a, b, R, R, reach=10e-6)


def test_candidate_pairs_of_parallel_beams_cover_the_contact_line():
    """Beam b lies on beam a (meshed differently): a line pair at every node of b, normals e_z,
    gaps zero, tributary lengths summing to the length of b."""
    V, a, b = two_beams([1.0, 0.0, 0.0], 0.0, length=0.1, n=20, n_b=13)
    pairs = candidate_pairs(V, a, b, R, R, reach=1e-6, line=True)
    assert len(pairs) == 14 and pairs.line
    assert pairs.tributary.sum() == pytest.approx(0.1, rel=1e-12)
    np.testing.assert_allclose(pairs.normal, np.tile([0.0, 0.0, 1.0], (14, 1)), atol=1e-15)
    np.testing.assert_allclose(pairs.initial_gap, 0.0, atol=1e-15)
    with pytest.raises(ValueError, match="parallel"):
        node_pairs(V, pairs.a, pairs.b, R, R)  # as crossings: no normal t_a × t_b


def test_candidate_stencils_on_the_input_arrays_are_the_pairs_of_the_mesh():
    """The pairs found on a mesh's input arrays before it is built (what a partitioner is given)
    are those ``candidate_pairs`` finds on its space: the same nodes in the same roles, at the
    same positions, for crossings and line pairs; a per-pair initial gap follows its pair."""
    n, n_b = 20, 13
    s, t = np.linspace(-0.05, 0.05, n + 1), np.linspace(-0.04, 0.05, n_b + 1)
    for direction, line in (([0.0, 1.0, 0.0], False), ([1.0, 0.0, 0.0], True)):
        pts = np.vstack([s[:, None] * [1.0, 0, 0], t[:, None] * direction + [0, 0, 2 * R]])
        cells = np.vstack([np.c_[0:n, 1 : n + 1], n + 1 + np.c_[0:n_b, 1 : n_b + 1]])
        V = beam_space(polyline_mesh(MPI.COMM_WORLD, pts, cells))
        a, b = locate_nodes(V, pts[: n + 1]), locate_nodes(V, pts[n + 1 :])
        reach = 1e-6 if line else 1e-3  # no node of b at the crossing
        rows = candidate_stencils(
            pts, cells, range(n + 1), range(n + 1, n + n_b + 2), R, R, reach, line=line
        )
        gaps = -1e-6 * np.arange(1, len(rows) + 1)
        pairs = candidate_pairs(V, a, b, R, R, reach, line=line, initial_gap=gaps)
        assert len(rows) == len(pairs) == (n_b + 1 if line else 1)
        x = V.tabulate_dof_coordinates()
        np.testing.assert_array_equal(x[pairs.nodes], pts[rows])
        np.testing.assert_array_equal(pairs.positions, pts[rows])
        np.testing.assert_array_equal(pairs.initial_gap, gaps[pairs.index])


def test_dof_values_reads_nodes_and_cells_at_points_in_their_order():
    """The unknowns of the nodes at given points, in the points' order, whatever the dof order;
    a DG0 function's values at its cells' midpoints; a point with no dof is refused, naming it
    (on N ranks: ``test_mpi.py``)."""
    V, a, b = two_beams([0.0, 1.0, 0.0], 0.0, n=4)
    w = fem.Function(V)
    w.interpolate(lambda p: np.vstack([p, 10 * p]))
    x = V.tabulate_dof_coordinates()
    points = x[np.r_[b[::-1], a]]
    np.testing.assert_array_equal(dof_values(w, points), np.c_[points, 10 * points])
    np.testing.assert_array_equal(dof_values(w, points[3]), [[*points[3], *(10 * points[3])]])
    c = fem.Function(fem.functionspace(V.mesh, ("DG", 0)))
    c.interpolate(lambda p: p[0] + p[1])
    mid = 0.5 * (x[a[1:]] + x[a[:-1]])
    np.testing.assert_allclose(dof_values(c, mid)[:, 0], mid[:, 0], rtol=1e-15)
    with pytest.raises(ValueError, match=r"point \[0.001, 0.0, 0.0\] is 0.001 m from"):
        dof_values(w, [0.001, 0.0, 0.0])
    with pytest.raises(ValueError, match="points must be"):
        dof_values(w, [0.0, 0.0])


def test_bad_pairs_are_refused_in_one_line():
    V, a, b = two_beams([0.0, 1.0, 0.0], 0.0, n=4)
    with pytest.raises(ValueError, match="from the nearest node"):
        locate_nodes(V, [0.001, 0.0, 0.0])
    with pytest.raises(ValueError, match="share nodes"):
        candidate_pairs(V, a, a, R, R, reach=1e-3)
    with pytest.raises(ValueError, match="radii must be positive"):
        node_pairs(V, a[2], b[2], 0.0, R)
    pairs = candidate_pairs(V, a, b, R, R, reach=1e-3)
    with pytest.raises(ContactError, match="share no cell of V"):
        sliding_terms(V, pairs, [a[[0, 2, 1, 3, 4]], b], 1e-3, PenaltyLaw(K_N))
    with pytest.raises(ContactError, match="on none of the chains"):
        sliding_terms(V, pairs, [a], 1e-3, PenaltyLaw(K_N))
    # three cells at one node: not a chain of cells
    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
    star = beam_space(polyline_mesh(MPI.COMM_WORLD, pts, [[0, 1], [0, 2], [0, 3]]))
    with pytest.raises(ValueError, match="joins 3 cells"):
        beam_nodes(star)


def test_large_sliding_windows_stop_at_the_beams_ends_and_cut_the_laws_per_pair():
    """Line pairs along beam b lying on a: windows of 20 mm either side, shorter near a's ends,
    so the pairs fall into groups by window size, each with its own pairs' law values."""
    V, a, b = two_beams([1.0, 0.0, 0.0], 0.0, length=0.1, n=20, n_b=13)
    pairs = candidate_pairs(V, a, b, R, R, reach=1e-6, line=True)
    k, mu = K_N * (1 + np.arange(len(pairs))), 0.1 + 0.01 * np.arange(len(pairs))
    groups = sliding_terms(V, pairs, [a, b], 0.02, PenaltyLaw(k), ElasticSlip(mu, 1e-6))
    assert len(groups) > 1
    assert sorted(np.concatenate([g.index for g in groups]).tolist()) == list(range(len(pairs)))
    for g in groups:
        np.testing.assert_array_equal(g.normal_law.k, k[g.index])
        np.testing.assert_array_equal(g.friction_law.mu, mu[g.index])
        assert g.friction_law.g_lim == 1e-6
        window = g.X[:, : g.na, 0]  # along beam a: 20 mm either side of node a, or to a's end
        x_a = pairs.positions[g.index, 0, 0]
        np.testing.assert_array_equal(g.X[:, g.na], pairs.positions[g.index, 1])  # b: its own
        assert np.all((window[:, 0] <= x_a - 0.02 + 1e-12) | (window[:, 0] == -0.05))
        assert np.all((window[:, -1] >= x_a + 0.02 - 1e-12) | (window[:, -1] == 0.05))


def test_hertz_laws_of_crossed_wires_use_their_crossing_angle():
    V, a, b = two_beams([np.cos(0.4), np.sin(0.4), 0.0], 0.0)
    pairs = candidate_pairs(V, a, b, R, R, reach=1e-6)
    law, friction = hertz_laws(pairs, E, NU, E, NU, mu=0.3)
    c = point_coefficient(R, R, pairs.crossing_angle, E, NU, E, NU)
    assert pairs.crossing_angle[0] == pytest.approx(0.4, rel=1e-9)
    np.testing.assert_allclose(law.c, c, rtol=1e-15)
    assert friction.mu[0] == 0.3


@pytest.fixture
def pressed_by_a_prescribed_beam():
    """Beam b (upper, along y) clamped at both ends; beam a (lower, along x) moved up as a rigid
    body by prescribed motions of all its nodes into b, which starts ``gap0`` above it."""
    gap0 = 2e-6  # small enough that the membrane stiffening of b stays below 1e-6
    V, a, b = two_beams([0.0, 1.0, 0.0], gap0)
    w = fem.Function(V)
    beam = ReissnerBeam(w, CircularSection(2 * R, E, NU))
    lift = fem.Constant(V.mesh, 0.0)
    bcs = [fem.dirichletbc(np.zeros(6), b[[0, -1]], V)]
    bcs += [fem.dirichletbc(0.0, 6 * a + c, V.sub(c)) for c in (0, 1, 3, 4, 5)]
    bcs.append(fem.dirichletbc(lift, 6 * a + 2, V.sub(2)))
    pairs = candidate_pairs(V, a, b, R, R, reach=1e-4)
    contact = contact_terms(pairs, PenaltyLaw(K_N))
    # the upper beam's own midspan stiffness, from a unit load on it alone
    unit = NodalLoad([b[20]], [[0, 0, 1, 0, 0, 0]], 0.05)  # N, about the contact's force
    alone = NonlinearProblem(beam.residual(), w, bcs, terms=[unit])
    assert alone.solve().converged
    k_beam = 0.05 / w.x.array.reshape(-1, 6)[b[20], 2]
    alone.destroy()
    w.x.array[:] = 0.0
    solver = NonlinearProblem(beam.residual(), w, bcs, terms=[contact])
    return solver, contact, lift, gap0, 1.0 / (1.0 / K_N + 1.0 / k_beam)


def test_a_measured_gap_closes_then_presses_as_springs_in_series(pressed_by_a_prescribed_beam):
    """Lifted by δ < gap0, nothing touches; by δ > gap0, p = k (δ − gap0) with the contact and
    the upper beam in series."""
    solver, contact, lift, gap0, k_series = pressed_by_a_prescribed_beam
    lift.value = 0.5 * gap0
    assert solver.solve().converged
    assert contact.state.force[0] == 0.0
    assert contact.state.gap[0] == pytest.approx(0.5 * gap0, rel=1e-6)
    solver.commit()
    lift.value = 3 * gap0
    assert solver.solve().converged
    assert contact.state.force[0] == pytest.approx(k_series * 2 * gap0, rel=1e-6)


def test_contact_on_prescribed_nodes_keeps_newtons_rate(pressed_by_a_prescribed_beam):
    """Once the contact is closed, a further prescribed lift of the lower beam is a (nearly)
    linear step: the contact stiffness coupling it to the free beam must enter the first Newton
    correction (by lifting, as dolfinx does for forms), so one iteration cuts the residual from
    K_N Δδ by ~1e5 (what is left is the director normal's rotation coupling). Dropping it (the
    old masking) leaves a residual of K_N Δδ after that iteration."""
    solver, contact, lift, gap0, _ = pressed_by_a_prescribed_beam
    lift.value = 2 * gap0
    assert solver.solve().converged
    solver.commit()
    step = 0.5 * gap0
    lift.value = 2 * gap0 + step
    result = solver.solve()
    assert result.converged and result.iterations <= 2, result.residuals
    assert result.residuals[1] < 1e-3 * K_N * step, result.residuals


def test_large_sliding_pairs_from_node_pairs_press_then_follow_the_slide():
    """Beam a (lower, along x) lifted as a rigid body into beam b (upper, along y, clamped at its
    ends) from ``gap0`` below it, then slid along b by two cells. Large-sliding pairs built from
    the same ``NodePairs`` and the beams' node chains give the small-sliding pair's gap and force
    while nothing slides (the contact and b in series); slid, they press b at its new point,
    where b is 3 % stiffer, which a pair fixed at the first nodes would not see."""
    gap0, h = 2e-6, 0.2 / 40  # m: the initial gap and the cell size
    V, a, b = two_beams([0.0, 1.0, 0.0], gap0)
    pairs = candidate_pairs(V, a, b, R, R, reach=1e-4)
    w = fem.Function(V)
    beam = ReissnerBeam(w, CircularSection(2 * R, E, NU))
    lift, slide = fem.Constant(V.mesh, 0.0), fem.Constant(V.mesh, 0.0)
    bcs = [fem.dirichletbc(np.zeros(6), b[[0, -1]], V)]
    bcs += [fem.dirichletbc(0.0, 6 * a + c, V.sub(c)) for c in (0, 3, 4, 5)]
    bcs += [fem.dirichletbc(slide, 6 * a + 1, V.sub(1)), fem.dirichletbc(lift, 6 * a + 2, V.sub(2))]

    def k_series(node):  # the contact in series with b's own stiffness at ``node``
        alone = NonlinearProblem(
            beam.residual(), w, bcs, terms=[NodalLoad([node], [[0, 0, 1, 0, 0, 0]], 0.05)]
        )
        assert alone.solve().converged
        k_beam = 0.05 / w.x.array.reshape(-1, 6)[node, 2]
        alone.destroy()
        w.x.array[:] = 0.0
        return 1.0 / (1.0 / K_N + 1.0 / k_beam)

    k_middle, k_moved = k_series(b[20]), k_series(b[22])
    assert k_moved > 1.02 * k_middle
    states = {}
    for model in ("small", "large"):
        if model == "small":
            terms = [contact_terms(pairs, PenaltyLaw(K_N))]
        else:
            terms = sliding_terms(V, pairs, [a, b], 15e-3, PenaltyLaw(K_N))
        solver = NonlinearProblem(beam.residual(), w, bcs, terms=terms)
        for value in (0.5 * gap0, 3 * gap0):
            lift.value = value
            assert solver.solve().converged
            solver.commit()
            states[model, value] = (terms[0].state.gap[0], terms[0].state.force[0])
        if model == "large":
            for value in np.linspace(0.0, 2 * h, 9)[1:]:
                slide.value = value
                assert solver.solve().converged
                solver.commit()
            contact = terms[0]
        solver.destroy()
        w.x.array[:] = 0.0
        lift.value = slide.value = 0.0
    assert len(terms) == 1 and terms[0].index.tolist() == [0]
    assert states["large", 0.5 * gap0] == pytest.approx((0.5 * gap0, 0.0), rel=1e-6)
    for model in ("small", "large"):
        assert states[model, 3 * gap0][1] == pytest.approx(k_middle * 2 * gap0, rel=1e-6)
    assert states["large", 3 * gap0] == pytest.approx(states["small", 3 * gap0], rel=1e-6)
    # slid by two cells: the contact point is on b at y = 2h (its node 22), the normal vertical but
    # for b's slope there (1e-5)
    j, eta = contact.segment[0, 1], contact.parameter[0, 1]
    y = contact.X[0, contact.na + j : contact.na + j + 2, 1] @ [1 - eta, eta]
    assert y == pytest.approx(2 * h, abs=1e-6)
    assert contact.state.force[0] == pytest.approx(k_moved * 2 * gap0, rel=1e-4)
    np.testing.assert_allclose(contact.state.normal[0], [0.0, 0.0, 1.0], atol=1e-4)


def deflection_alone(V, node: int, force: float, bcs) -> float:
    """The vertical displacement (m) of ``node`` of a beam of ``V`` under a vertical ``force``
    (N) there alone, with Dirichlet conditions ``bcs`` (on a function of its own)."""
    w = fem.Function(V)
    beam = ReissnerBeam(w, CircularSection(2 * R, E, NU))
    load = NodalLoad([node], [[0, 0, force, 0, 0, 0]], 1.0)
    alone = NonlinearProblem(beam.residual(), w, [bc(w) for bc in bcs], terms=[load])
    assert alone.solve().converged
    alone.destroy()
    return float(w.x.array.reshape(-1, 6)[node, 2])


def test_beams_pressed_into_each_other_at_t0_start_with_the_default_newton_options():
    """Two crossed beams, clamped at their ends, start pressed into each other by a tenth of
    their radius; the ends of the lower one are then moved (prescribed) up and down. With
    ``NewtonOptions()`` as they come (no stall test for a problem of one's own), every step
    converges, and the state kept before the ramp reads each step's values: each beam deflects
    at its middle as it does alone under the pair's Hertz force P there (within 1e-5), and the
    overlap less the two deflections is the Hertz approach at P (springs in series)."""
    overlap = 0.1 * R
    V, a, b = two_beams([0.0, 1.0, 0.0], -overlap)
    w = fem.Function(V)
    beam = ReissnerBeam(w, CircularSection(2 * R, E, NU))
    lift = fem.Constant(V.mesh, 0.0)

    def supports(ends_a_lift):
        zero = [lambda u: fem.dirichletbc(np.zeros(6), b[[0, -1]], u.function_space)]
        ends = [
            lambda u, c=c: fem.dirichletbc(0.0, 6 * a[[0, -1]] + c, V.sub(c))
            for c in (0, 1, 3, 4, 5)
        ]
        ends.append(lambda u: fem.dirichletbc(ends_a_lift, 6 * a[[0, -1]] + 2, V.sub(2)))
        return zero, ends

    zero_b, ends_a = supports(lift)
    bcs = [bc(w) for bc in zero_b + ends_a]
    pairs = candidate_pairs(V, a, b, R, R, reach=1e-4)
    assert pairs.initial_gap[0] == pytest.approx(-overlap, rel=1e-9)
    law, _ = hertz_laws(pairs, E, NU, E, NU)
    contact = contact_terms(pairs, law)
    state, force = contact.state, contact.state.force  # kept before the ramp
    assert NewtonOptions().stall_after is None
    solver = NonlinearProblem(beam.residual(), w, bcs, terms=[contact])
    for value in (0.0, -50e-6, 50e-6):  # m: the lower beam's ends moved
        lift.value = value
        result = solver.solve()
        assert result.converged, result.residuals
        solver.commit()
        P = force[0]
        assert state is contact.state and P == contact.state.force[0] > 0
        d_b = deflection_alone(V, b[20], P, zero_b)
        end = fem.Constant(V.mesh, value)
        u_a = deflection_alone(V, a[20], -P, supports(end)[1])
        # each beam carries P as it would alone; the overlap less their deflections is the gap
        # (to 1e-5 of the overlap: the director normal's own kinematics), at which the law
        # gives P
        assert state.gap[0] == pytest.approx(-overlap + d_b - u_a, abs=1e-5 * overlap)
        assert law.force(state.gap)[0][0] == pytest.approx(P, rel=1e-12)
        np.testing.assert_allclose(
            w.x.array.reshape(-1, 6)[[a[20], b[20]], 2], [u_a, d_b], rtol=1e-5
        )
    solver.destroy()


def test_friction_starts_each_step_from_the_last_commit():
    """Beam b pressed onto beam a by P, a sheared by s into slip (s = 30 µm, slip from 14 µm),
    then brought back to 20 µm. Committing every step, the pair unloads along its stick line
    (Q = μP − k·10 µm); committing the pressing only, friction is measured from there, path-
    independent, and retraces loading (Q stays μP); committing nothing leaves the stick
    stiffness μP/g_lim at the committed P = 0: no friction. Newton converges in all three
    (the library guide's account of ``problem.commit``)."""
    mu, P = 0.3, 50.0
    Q = {}
    for commits in ("every step", "pressing", "none"):
        V, a, b = two_beams([0.0, 1.0, 0.0], 0.0, length=0.04)
        w = fem.Function(V)
        contact = contact_terms(
            candidate_pairs(V, a, b, R, R, reach=1e-4), PenaltyLaw(1e8), ElasticSlip(mu, 5e-6)
        )
        shear = fem.Constant(V.mesh, 0.0)
        ends = b[[0, -1]]
        bcs = [fem.dirichletbc(shear, 6 * a, V.sub(0))]
        bcs += [fem.dirichletbc(0.0, 6 * a + c, V.sub(c)) for c in range(1, 6)]
        bcs += [fem.dirichletbc(0.0, 6 * ends + c, V.sub(c)) for c in (0, 1, 3, 4, 5)]
        press = NodalLoad(ends, [[0.0, 0.0, -P / 2, 0.0, 0.0, 0.0]] * 2)
        beam = ReissnerBeam(w, CircularSection(2 * R, E, NU))
        problem = NonlinearProblem(beam.residual(), w, bcs, terms=[contact, press])
        steps = [(press, "factor", f, commits != "none") for f in (0.25, 0.5, 0.75, 1.0)]
        steps += [
            (shear, "value", s, commits == "every step") for s in 1e-6 * np.r_[2:31:2, 28:19:-2]
        ]
        for target, name, value, commit in steps:
            setattr(target, name, value)
            assert problem.solve().converged
            if commit:
                problem.commit()
        assert contact.state.force[0] == pytest.approx(P, rel=1e-9)
        Q[commits] = -contact.state.traction[0, 0] / (mu * P)  # on b, in units of μP
    assert 0.1 < Q["every step"] < 0.3
    assert Q["pressing"] == pytest.approx(1.0, rel=1e-9)
    assert Q["none"] == 0.0
