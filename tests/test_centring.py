"""A core that touches no wire, held on its first layer's axis by the bending set-ups
(``strand.cable.centring``, ``strand.setups.centring``): the springs see the ring's drift off
the core and nothing else, and they make the vaulted core's column stable under the strut."""

from __future__ import annotations

from functools import partial

import numpy as np
import pytest
from dolfinx.fem import petsc as fem_petsc

from strand.cable.centring import ring_centres
from strand.contact.kinematics import rotation_matrix
from strand.model.contact_settings import ContactSettings
from strand.model.problem import StrandProblem
from strand.setups.bending import UniformBendingTest
from strand.setups.centring import CoreCentring
from strand.solver import LoadStepper, NewtonOptions
from strand_cases import seven_wire


@pytest.fixture(scope="module")
def geometry():
    return seven_wire(length=0.15)


def _springs(geometry, k=1e7):
    rings = ring_centres(geometry)
    return rings, CoreCentring(rings.stencils, rings.weights, k)


def _lateral(f):
    """(P, m·2) → (P, m, 2)."""
    return f.reshape(len(f), -1, 2)


def test_the_ring_centre_is_on_the_core_at_every_core_node(geometry):
    """Every interior core node has a stencil: itself and each layer-1 wire's two nodes about its
    z, interpolated to that z; the weights sum to zero (a rigid translation loads nothing) and
    the ring's centre lies on the core to the chords' sag (h²/8 of the helix's curvature)."""
    rings = ring_centres(geometry)
    core = np.arange(*geometry.wire_offsets[:2])
    assert np.array_equal(rings.stencils[:, 0], core[1:-1])
    assert rings.stencils.shape[1] == 1 + 2 * 6
    assert np.allclose(rings.weights.sum(axis=1), 0.0, atol=1e-15)
    x = geometry.points[rings.stencils]
    z = np.einsum("pk,pk->p", -rings.weights[:, 1:], x[:, 1:, 2])
    assert np.allclose(z, x[:, 0, 2], atol=1e-12)  # each wire taken at the core node's z
    offset = np.einsum("pk,pkc->pc", rings.weights, x[:, :, :2])
    layer = geometry.cable.layers[1]
    radius = float(np.linalg.norm(geometry.points[rings.stencils[0, 1], :2]))
    curvature = np.sin(layer.alpha) ** 2 / radius
    h = np.abs(np.diff(geometry.points[geometry.wire_offsets[1] : geometry.wire_offsets[2], 2]))
    sag = (h.max() / np.cos(layer.alpha)) ** 2 * curvature / 8
    print(f"largest offset {np.abs(offset).max() * 1e6:.3f} µm, sag {sag * 1e6:.3f} µm")
    assert np.abs(offset).max() <= sag
    ends = np.diff(geometry.points[core[[0, 1, -2, -1]], 2])[[0, 2]]
    assert rings.length.sum() == pytest.approx(geometry.length - ends.sum() / 2, rel=1e-12)


def test_the_springs_see_the_ring_drift_and_nothing_else(geometry):
    """The ring's own motions load no spring: a uniform contraction and an ovalisation (to the
    interpolation's accuracy; an ovalisation cos 2φ sums to zero over n ≠ 2 wires), a turn of
    the whole section about the axis, a translation of everything. The
    core moved by δ sideways is pulled back by k δ, the ring pushed by as much in all (the
    springs are internal: their forces sum to zero), and the tangent is the residual's
    derivative (linear springs: K u = f(u))."""
    rings, springs = _springs(geometry)
    k = 1e7
    n = len(geometry.points)
    x = geometry.points
    ring = geometry.point_wire >= 1
    scale = 1e-6  # m

    def force(u):
        w = np.zeros((n, 6))
        w[:, :3] = u
        return _lateral(springs.evaluate(w, False)[0])

    radial = np.zeros((n, 3))
    radial[ring, :2] = -scale * x[ring, :2] / np.linalg.norm(x[ring, :2], axis=1)[:, None]
    assert np.abs(force(radial)).max() < 1e-3 * k * scale
    phi = np.arctan2(x[:, 1], x[:, 0])
    oval = radial * -np.cos(2 * phi)[:, None]
    assert np.abs(force(oval)).max() < 1e-3 * k * scale
    R = rotation_matrix(np.array([[0.0, 0.0, 1e-3]]))[0]
    assert np.abs(force(x @ (R - np.eye(3)).T)).max() < 1e-4 * k * scale
    assert np.abs(force(np.tile([scale, -scale, scale], (n, 1)))).max() < 1e-12 * k * scale

    shifted = np.zeros((n, 3))
    shifted[geometry.point_wire == 0, 0] = scale
    f = force(shifted)
    assert np.allclose(f[:, 0], [k * scale, 0.0])
    assert np.allclose(f.sum(axis=1), 0.0, atol=1e-12 * k * scale)

    rng = np.random.default_rng(0)
    w = rng.standard_normal((n, 6)) * scale
    f, K = springs.evaluate(w, True)
    u = w[springs.stencils].reshape(len(f), -1)[:, springs.dofs]
    assert np.allclose(np.einsum("pij,pj->pi", K, u), f, rtol=1e-12, atol=1e-12 * k * scale)
    assert np.allclose(K, K.transpose(0, 2, 1))


def _lowest_eigenvalue(problem, without=None) -> float:
    """Lowest eigenvalue of the Jacobian's symmetric part at the current state (one rank), the
    Dirichlet rows aside; ``without``: a term set whose tangent is taken out."""
    solver = problem.solver
    x = solver._x.duplicate()
    fem_petsc.assign(solver.w, x)
    solver._pairs.forget()
    solver._jacobian(None, x, solver._A, solver._A)
    A = solver._A.convert("dense").getDenseArray().copy()
    if without is not None:
        _, K = without.evaluate(solver.w.x.array.reshape(-1, 6), True)
        idx = 6 * without.stencils[:, without.dofs // 6] + without.dofs % 6
        for p in range(len(K)):
            A[np.ix_(idx[p], idx[p])] -= K[p]
    free = ~solver._pairs.bc_mask[: len(A)]
    A = A[np.ix_(free, free)]
    return float(np.linalg.eigvalsh(0.5 * (A + A.T))[0])


def test_the_centring_holds_a_vaulted_core_under_the_strut():
    """A 1+6 vaulted over its core (``first_layer = "ring"``), frictionless, in the uniform
    bending set-up: the strut makes its core a free column of 0.15 m under 10 kN, several times
    its Euler load (4π²EI/L² = 2.2 kN clamped), so the tangent at the tensioned state has a
    negative eigenvalue without the centring springs, and none with them. On its core
    (``on_core``) the set-up adds none."""
    geometry = seven_wire(length=0.15)
    settings = ContactSettings(same_layer="packed", first_layer="ring", friction=False)
    problem = StrandProblem(
        geometry,
        settings,
        NewtonOptions(atol=1e-4, max_it=15),
        setup=partial(UniformBendingTest, zone=0.05),
    )
    setup = problem.setup
    assert isinstance(setup.centring, CoreCentring)
    LoadStepper(problem.solver, 200.0, 10.0).ramp(partial(setup.set, "tension"), 0.0, 10e3)
    offsets = setup.centring.offsets(problem.solver.w.x.array.reshape(-1, 6))
    print(f"core off the ring's axis by at most {np.abs(offsets).max() * 1e6:.3f} µm")
    held = _lowest_eigenvalue(problem)
    free = _lowest_eigenvalue(problem, without=setup.centring)
    print(f"lowest eigenvalue: {held:.4g} with the springs, {free:.4g} without")
    assert held > 0 > free
    on_core = StrandProblem(
        geometry,
        ContactSettings(same_layer="packed", friction=False),
        setup=partial(UniformBendingTest, zone=0.05),
    )
    assert on_core.setup.centring is None
