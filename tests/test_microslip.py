"""Mindlin–Deresiewicz microslip (``strand.contact.microslip``): a crossed pair's loop and its
energy per cycle against the closed forms, Masing's memory, exact derivatives, history kept
through a checkpoint."""

import numpy as np
import pytest

from strand.contact.element import ContactGroup
from strand.contact.hertz import hertz_mindlin
from strand.contact.microslip import MindlinDeresiewicz, loop_energy, microslip_return

R, E, NU, MU = 1.5e-3, 2.1e11, 0.3, 0.5  # steel wires of 3 mm, m, Pa


def crossed_pair(angle: float = np.radians(25)) -> ContactGroup:
    """One crossing of two straight steel wires (a along x, b above it), Hertz and microslip."""
    ta, tb = np.array([1.0, 0, 0]), np.array([np.cos(angle), np.sin(angle), 0.0])
    X = np.array([[[0.0, 0, 0], [0.0, 0, 2 * R]]])
    normal, friction = hertz_mindlin(
        False, [R], [R], [angle], [0.0], E_a=E, nu_a=NU, E_b=E, nu_b=NU, mu=[MU], microslip=True
    )
    assert isinstance(friction, MindlinDeresiewicz)
    return ContactGroup(
        np.array([[0, 1]]),
        X,
        False,
        [R],
        [R],
        [[0, 0, 1.0]],
        normal,
        friction_law=friction,
        normal="director",
        tangent0=np.stack([ta, tb])[None],
    )


def pressed(group: ContactGroup, approach: float = 2e-6) -> tuple[np.ndarray, float, float]:
    """Press the pair by ``approach`` (m) and commit: nodal unknowns, P (N) and K₀ (N/m)."""
    w = np.zeros((2, 6))
    w[1, 2] = -approach
    group.evaluate(w, True)
    group.commit()
    P = group.committed_force[0]
    k0 = group.friction_law.stiffness(group.committed_force, group.normal_law)[0]
    return w, P, k0


def virgin(d, mu_p, k0):
    """Mindlin–Deresiewicz's monotonic curve Q(δ) = μP [1 − (1 − δ/δ*)^{3/2}], odd in δ."""
    r = np.minimum(np.abs(d) / (1.5 * mu_p / k0), 1.0)
    return np.sign(d) * mu_p * (1 - (1 - r) ** 1.5)


def drive(group, w, path, along):
    """Move b's node along ``along`` through the displacements ``path`` (m), committing each
    step; returns the traction along ``along`` (N) after each, and the branch factors."""
    out, branches = [], []
    for d in path:
        w2 = w.copy()
        w2[1, :3] += d * along
        group.evaluate(w2, True)
        group.commit()
        out.append(group.state.traction[0] @ along)
        branches.append(group._law_history["branch"][0])
    return np.array(out), np.array(branches)


@pytest.mark.parametrize("q", [0.3, 0.8, 1.0])
def test_a_crossed_pair_cycled_at_constant_force_follows_mindlin_deresiewicz(q):
    """Loading to Q* = q μP follows the virgin curve, unloading to −Q* and reloading Masing's
    branches, to round-off; the loop's area (the energy per cycle) and the energy the pair's
    history counts are within 1 % of W(Q*) (Johnson 1985, eq. 7.59)."""
    group = crossed_pair()
    w, P, k0 = pressed(group)
    mu_p = MU * P
    along = np.array([np.cos(0.3), np.sin(0.3), 0.0])
    d_r = 1.5 * mu_p / k0 * (1 - (1 - q) ** (2 / 3))  # where the virgin curve reaches Q*
    up = np.linspace(0, d_r, 201)[1:]
    down = np.linspace(d_r, -d_r, 401)[1:]
    again = np.linspace(-d_r, d_r, 401)[1:]
    Q, _ = drive(group, w, np.concatenate([up, down, again]), along)
    assert group.committed_force[0] == pytest.approx(P, rel=1e-12)  # the normal force stays
    q_up, q_down, q_again = np.split(Q, [len(up), len(up) + len(down)])
    np.testing.assert_allclose(q_up, virgin(up, mu_p, k0), atol=1e-9 * mu_p)
    masing_down = q_up[-1] - 2 * virgin((d_r - down) / 2, mu_p, k0)
    masing_up = -q_up[-1] + 2 * virgin((again + d_r) / 2, mu_p, k0)
    np.testing.assert_allclose(q_down, masing_down, atol=1e-9 * mu_p)
    np.testing.assert_allclose(q_again, masing_up, atol=1e-9 * mu_p)
    assert q_down[-1] == pytest.approx(-q * mu_p, rel=1e-9)  # the loop closes
    x = np.concatenate([[d_r], down, again])
    y = np.concatenate([[q_up[-1]], q_down, q_again])
    area = np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(x))
    W = loop_energy(q * mu_p, mu_p, k0)
    assert area == pytest.approx(W, rel=1e-2)
    work_before = group.history.work[0]
    drive(group, w, np.concatenate([np.linspace(d_r, -d_r, 401)[1:], again]), along)
    assert group.history.work[0] - work_before == pytest.approx(W, rel=1e-2)


def test_loop_energy_is_the_loop_area_of_the_curve():
    """W(Q*) against the Masing loop on the virgin curve integrated numerically (fine steps):
    the closed form and the curves it comes from agree; small loops go as 2Q*³/(9K₀μP)."""
    mu_p, k0 = 50.0, 1e7
    for q in (0.05, 0.5, 0.99):
        d_r = 1.5 * mu_p / k0 * (1 - (1 - q) ** (2 / 3))
        d = np.linspace(-d_r, d_r, 200001)
        lower = -q * mu_p + 2 * virgin((d + d_r) / 2, mu_p, k0)
        upper = q * mu_p - 2 * virgin((d_r - d) / 2, mu_p, k0)
        area = np.trapezoid(lower - upper, d)
        assert loop_energy(q * mu_p, mu_p, k0) == pytest.approx(area, rel=1e-6)
    small = 1e-3 * mu_p
    assert loop_energy(small, mu_p, k0) == pytest.approx(2 * small**3 / (9 * k0 * mu_p), rel=1e-2)


def test_a_loop_closed_goes_on_along_the_virgin_curve():
    """Masing's memory: after a loop ±Q*, loading past Q* continues the virgin curve (the
    branch factor is back at 1), to gross slip at μP with zero slope."""
    group = crossed_pair()
    w, P, k0 = pressed(group)
    mu_p = MU * P
    along = np.array([1.0, 0.0, 0.0])
    span = 1.5 * mu_p / k0
    d_r = 0.3 * span
    path = np.concatenate(
        [np.linspace(0, d_r, 51)[1:], np.linspace(d_r, -d_r, 101)[1:], np.linspace(-d_r, d_r, 101)]
    )
    _, branches = drive(group, w, path, along)
    assert branches[60] == 2.0  # on a reversal branch inside the loop
    beyond = np.linspace(d_r, 1.2 * span, 101)[1:]
    Q, branches = drive(group, w, beyond, along)
    assert np.all(branches == 1.0)
    np.testing.assert_allclose(Q, virgin(beyond, mu_p, k0), atol=1e-3 * mu_p)
    assert Q[-1] == pytest.approx(mu_p, rel=1e-12) and group.state.slipping[0]


def random_states(rng, n, kind):
    """n pairs with random normals, forces, coefficients, stiffnesses and histories; ``kind``
    picks where the step leaves them: on their branch, reversed, saturated, capped, open."""
    nrm = rng.standard_normal((n, 3))
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    plane = np.eye(3) - nrm[:, :, None] * nrm[:, None, :]

    def tangential(scale):
        return np.einsum("pij,pj->pi", plane, rng.standard_normal((n, 3))) * scale[:, None]

    p0 = rng.uniform(10, 200, n)
    mu = rng.uniform(0.2, 0.6, n)
    k0 = rng.uniform(1e6, 1e7, n)
    span = 1.5 * mu * p0 / k0
    anchor = (
        tangential(0.3 * mu * p0) if kind in ("reversal branch", "capped") else np.zeros((n, 3))
    )
    branch = np.where(np.any(anchor != 0, axis=1), 2.0, 1.0)
    t_old = anchor + tangential(0.2 * mu * p0 / np.sqrt(3))
    p = p0 * rng.uniform(0.8, 1.2, n)
    tau = t_old - anchor
    if kind in ("virgin", "reversal branch"):
        slip = tau / np.linalg.norm(tau, axis=1)[:, None] * (0.2 * span)[:, None]
        slip += tangential(0.05 * span)
    elif kind == "reversed":
        slip = -tau / np.linalg.norm(tau, axis=1)[:, None] * (0.3 * span)[:, None]
    elif kind == "saturated":
        slip = tau / np.linalg.norm(tau, axis=1)[:, None] * (3 * span)[:, None]
    elif kind == "capped":  # a reversal branch driven sideways past the cone
        slip = tangential(4 * span)
        p = p0 * 0.5
    else:  # open
        slip = tangential(0.2 * span)
        p = np.zeros(n)
    return t_old, slip, nrm, p, p0, mu, k0, anchor, branch


@pytest.mark.parametrize(
    "kind", ["virgin", "reversal branch", "reversed", "saturated", "capped", "open"]
)
def test_microslip_derivatives_match_finite_differences(kind):
    """dt/dΔg_T and dt/dp against central differences in every state a step can leave."""
    rng = np.random.default_rng(11)
    t_old, slip, nrm, p, p0, mu, k0, anchor, branch = random_states(rng, 40, kind)

    def at(s, pp):
        return microslip_return(t_old, s, nrm, pp, p0, mu, k0, anchor=anchor, branch=branch)[0]

    r = at(slip, p)
    span = 1.5 * mu * p0 / k0
    if kind in ("saturated", "capped"):
        assert np.all(r.slipping)
    else:
        assert not np.any(r.slipping)
    if kind == "capped":
        np.testing.assert_allclose(np.linalg.norm(r.traction, axis=1), mu * p, rtol=1e-12)
    if kind == "open":  # nothing, whatever the slip (dp/dq is zero there: no pressure term)
        assert np.all(r.traction == 0) and np.all(r.d_slip == 0)
        return
    h = 1e-7 * span.min()
    for k in range(3):
        e = np.zeros(3)
        e[k] = h
        fd = (at(slip + e, p).traction - at(slip - e, p).traction) / (2 * h)
        np.testing.assert_allclose(r.d_slip[:, :, k], fd, rtol=1e-5, atol=1e-5 * k0.max())
    hp = 1e-6
    fd = (at(slip, p + hp).traction - at(slip, p - hp).traction) / (2 * hp)
    np.testing.assert_allclose(r.d_pressure, fd, rtol=1e-5, atol=1e-7)


def test_the_law_history_goes_through_a_checkpoint():
    """``history_arrays`` carries the branch; restoring it into a new group gives the same next
    step as the group that never stopped."""
    group = crossed_pair()
    w, P, k0 = pressed(group)
    along = np.array([1.0, 0.0, 0.0])
    span = 1.5 * MU * P / k0
    drive(group, w, [0.4 * span, 0.1 * span], along)  # a reversal: branch 2, anchor set
    arrays = group.history_arrays()
    assert arrays["friction_branch"][0] == 2.0 and np.any(arrays["friction_anchor"][0] != 0)
    w_now = w.copy()
    w_now[1, :3] += 0.1 * span * along
    other = crossed_pair()
    other.restore_history(arrays, w_now)
    for g in (group, other):
        w2 = w_now.copy()
        w2[1, :3] -= 0.3 * span * along
        g.evaluate(w2, True)
    np.testing.assert_array_equal(other.state.traction, group.state.traction)


def test_reversal_choices_are_kept_from_the_first_iterate_on():
    """Within a step a pair's reversal is chosen afresh until ``SETTLE`` tangents have been
    evaluated, then kept, for residuals and tangents alike (an iterate going back and forth
    across the reversal meets no kink); a rolled-back step chooses again."""
    group = crossed_pair()
    w, P, k0 = pressed(group)
    along = np.array([1.0, 0.0, 0.0])
    span = 1.5 * MU * P / k0
    drive(group, w, [0.5 * span], along)  # loaded forward on the virgin curve
    t_old = group.state.traction[0] @ along
    mu_p = MU * P

    def traction(d, jacobian=True):
        w2 = w.copy()
        w2[1, :3] += (0.5 * span + d) * along
        group.evaluate(w2, jacobian)
        return group.state.traction[0] @ along, bool(group._law_next["reversed"][0])

    assert group.SETTLE == 2
    t, reversed_ = traction(0.01 * span, jacobian=False)  # a residual first: chosen afresh
    assert not reversed_ and t == pytest.approx(virgin(0.51 * span, mu_p, k0), rel=1e-9)
    for _ in range(group.SETTLE):  # back: reversed, on Masing's branch
        t, reversed_ = traction(-0.01 * span)
        assert reversed_ and t == pytest.approx(t_old - 2 * virgin(0.005 * span, mu_p, k0))
    for jacobian in (False, True):  # kept: forward on the reversal branch, stiff (K₀)
        t, reversed_ = traction(0.01 * span, jacobian)
        assert reversed_ and t == pytest.approx(t_old + 2 * virgin(0.005 * span, mu_p, k0))
    group.rollback()
    t, reversed_ = traction(0.01 * span)  # chosen afresh: the virgin curve goes on, softer
    assert not reversed_ and t == pytest.approx(virgin(0.51 * span, mu_p, k0), rel=1e-9)
