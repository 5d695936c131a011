"""Contact laws: penalty, stick, slip, unload/reload through the return map, exact derivatives."""

import numpy as np
import pytest

from strand.contact.laws import coulomb_return, normal_force, tangential_stiffness

K_N, MU, G_LIM = 5e7, 0.5, 5e-6


def test_penalty_force_and_tangent():
    g = np.array([-2e-6, 0.0, 3e-6])
    p, dp = normal_force(g, K_N)
    assert p.tolist() == [K_N * 2e-6, 0.0, 0.0]
    assert dp.tolist() == [-K_N, -K_N, 0.0]  # closed at g = 0


def one_pair(t_old, slip, p=100.0, n=(0.0, 0.0, 1.0)):
    n = np.array([n], float)
    k_t = tangential_stiffness(np.array([MU]), np.array([p]), G_LIM)
    return coulomb_return(
        np.array([t_old], float), np.array([slip], float), n, np.array([p]), np.array([MU]), k_t
    )


def test_stick_below_cap_then_slip_at_cap():
    P = 100.0
    k_t = MU * P / G_LIM
    # a tangential load below μP sticks with slip |t|/K_T
    r = one_pair([0, 0, 0], [0.4 * MU * P / k_t, 0, 0], P)
    assert not r.slipping[0]
    assert r.traction[0, 0] == pytest.approx(0.4 * MU * P)
    # beyond the cap: slip at μP, along the trial direction
    r = one_pair([0, 0, 0], [3 * G_LIM, 4 * G_LIM, 0], P)
    assert r.slipping[0]
    np.testing.assert_allclose(r.traction[0], MU * P * np.array([0.6, 0.8, 0.0]))


def test_unload_and_reload_through_the_return_map():
    """Slip forward to the cap, then reverse: elastic unloading by K_T, then slip at −μP."""
    P = 100.0
    k_t = MU * P / G_LIM
    t = one_pair([0, 0, 0], [2 * G_LIM, 0, 0], P).traction[0]  # slipped: t = μP
    assert t[0] == pytest.approx(MU * P)
    back = one_pair(t, [-0.5 * G_LIM, 0, 0], P)  # unloading is elastic
    assert not back.slipping[0]
    assert back.traction[0, 0] == pytest.approx(MU * P - k_t * 0.5 * G_LIM)
    rev = one_pair(back.traction[0], [-3 * G_LIM, 0, 0], P)  # reversed slip
    assert rev.slipping[0] and rev.traction[0, 0] == pytest.approx(-MU * P)


def test_stored_traction_is_reprojected_on_the_current_plane():
    r = one_pair([10.0, 0, 5.0], [0, 0, 0], 1e3)
    np.testing.assert_allclose(r.traction[0], [10.0, 0, 0])


@pytest.mark.parametrize("state", ["stick", "slip"])
def test_derivatives_match_finite_differences(state):
    rng = np.random.default_rng(3)
    P = 40
    n = rng.standard_normal((P, 3))
    n /= np.linalg.norm(n, axis=1)[:, None]
    proj = np.eye(3) - n[:, :, None] * n[:, None, :]
    p = rng.uniform(10, 200, P)
    mu = rng.uniform(0.2, 0.6, P)
    k_t = tangential_stiffness(mu, p, G_LIM)
    t_old = (
        np.einsum("pij,pj->pi", proj, rng.standard_normal((P, 3))) * 0.2 * mu[:, None] * p[:, None]
    )
    scale = 0.1 if state == "stick" else 10.0
    slip = np.einsum("pij,pj->pi", proj, rng.standard_normal((P, 3))) * scale * G_LIM
    r = coulomb_return(t_old, slip, n, p, mu, k_t)
    assert np.all(r.slipping == (state == "slip"))
    h = 1e-6 * G_LIM
    for k in range(3):
        e = np.zeros(3)
        e[k] = h
        fd = (
            coulomb_return(t_old, slip + e, n, p, mu, k_t).traction
            - coulomb_return(t_old, slip - e, n, p, mu, k_t).traction
        ) / (2 * h)
        np.testing.assert_allclose(r.d_slip[:, :, k], fd, rtol=1e-6, atol=1e-6 * k_t.max())
    hp = 1e-6
    fd = (
        coulomb_return(t_old, slip, n, p + hp, mu, k_t).traction
        - coulomb_return(t_old, slip, n, p - hp, mu, k_t).traction
    ) / (2 * hp)
    np.testing.assert_allclose(r.d_pressure, fd, rtol=1e-6, atol=1e-9)
