"""Contact laws: penalty, stick, slip, unload/reload through the return map, exact derivatives;
Hertz and Mindlin against their closed forms."""

import numpy as np
import pytest

from strand.contact.friction_laws import Mindlin, coulomb_return, tangential_stiffness
from strand.contact.hertz import compliance, crossed_cylinders, mindlin_ratio, point_coefficient
from strand.contact.normal_laws import (
    CubicOnset,
    HertzLineLaw,
    HertzPointLaw,
    PenaltyLaw,
    normal_force,
)

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


# -- contact mechanics (Hertz, Mindlin) ---------------------------------------------------------
R, E_AL, NU_AL = 1.688e-3, 69e9, 0.33  # a Cardinal aluminium wire


def test_crossed_cylinders_at_right_angles_are_a_sphere_on_a_flat():
    """R₁ = R₂ = R at 90°: Hertz's sphere, P = (4/3) E* R^{1/2} δ^{3/2}, exactly."""
    e_star = 1 / (2 * compliance(E_AL, NU_AL))
    assert crossed_cylinders(R, R, np.pi / 2) == pytest.approx((R, R), rel=1e-12)
    c = point_coefficient(R, R, np.pi / 2, E_AL, NU_AL, E_AL, NU_AL)
    assert c == pytest.approx(4 / 3 * e_star * np.sqrt(R), rel=1e-12)


@pytest.mark.parametrize("deg", [18.0, 25.0, 40.0, 60.0])
def test_hamrock_brewe_fit_against_the_exact_elliptical_hertz_solution(deg):
    """At the crossing angles of stranded wires (18–25° for Cardinal) the fitted P(δ) is within
    5 % of Hertz's elliptical solution (Johnson 1985 §3.5: ū = (L − Mx² − Ny²)/E*, with
    L = p₀bK(e), M = p₀b(K − E)/(e²a²), N = p₀b((a/b)²E − K)/(e²a²), P = 2πabp₀/3)."""
    special = pytest.importorskip("scipy.special")
    optimize = pytest.importorskip("scipy.optimize")
    K, E = special.ellipk, special.ellipe  # of m = e²
    beta = np.radians(deg)
    rx, ry = crossed_cylinders(R, R, beta)
    A, B = 1 / (2 * rx), 1 / (2 * ry)
    m = optimize.brentq(lambda m: (E(m) / (1 - m) - K(m)) / (K(m) - E(m)) - B / A, 1e-9, 1 - 1e-12)
    e_star = 1 / (2 * compliance(E_AL, NU_AL))
    delta = 5e-6
    a2 = delta * (K(m) - E(m)) / (A * m * K(m))
    a, b = np.sqrt(a2), np.sqrt(a2 * (1 - m))
    p0 = A * e_star * m * a2 / (b * (K(m) - E(m)))
    exact = 2 * np.pi * a * b * p0 / 3 / delta**1.5
    assert point_coefficient(R, R, beta, E_AL, NU_AL, E_AL, NU_AL) == pytest.approx(exact, rel=0.05)


@pytest.mark.parametrize("kind", ["point", "line"])
def test_hertz_laws_derivatives_and_stiffness_at_force(kind):
    """dp/dg matches differences of p; ``stiffness(p)`` is dp/dδ at the approach giving p; open
    pairs carry nothing; the start offset keeps p(0) = 0 with a positive first tangent."""
    n = 5
    c = compliance(np.full(n, E_AL), NU_AL)
    law = (
        HertzPointLaw(np.full(n, point_coefficient(R, R, np.radians(20), E_AL, NU_AL, E_AL, NU_AL)))
        if kind == "point"
        else HertzLineLaw(np.full(n, 1.688e-3), np.full(n, 1.688e-3), c, c, np.full(n, 4e-3))
    )
    g = -np.array([0.0, 1e-7, 1e-6, 5e-6, 2e-5])
    p, dp = law.force(g)
    assert p[0] == 0.0 and dp[0] < 0.0 and np.all(np.diff(p) > 0)
    h = 1e-11
    fd = (law.force(g + h)[0] - law.force(g - h)[0]) / (2 * h)
    np.testing.assert_allclose(dp[1:], fd[1:], rtol=1e-5)  # g = 0 is the kink
    np.testing.assert_allclose(law.stiffness(p), -dp, rtol=1e-9)
    assert np.all(law.force(np.full(n, 1e-6))[0] == 0.0)


def test_hertz_line_law_matches_the_two_cylinder_formula():
    """The inverted line law returns the load whose approach (Johnson eq. 5.39) is the given one."""
    c = compliance(E_AL, NU_AL)
    law = HertzLineLaw(*(np.array([v]) for v in (1.688e-3, 1.688e-3, c, c, 1.0)))
    q = 2e4  # N/m
    b = np.sqrt(4 * q * (1.688e-3 / 2) / (np.pi / (2 * c)))
    delta = q / np.pi * 2 * c * (2 * np.log(4 * 1.688e-3 / b) - 1)
    assert law.force(np.array([-delta + law.START]))[0][0] + law.offset[0] == pytest.approx(
        q, rel=1e-9
    )


@pytest.mark.parametrize("kind", ["penalty", "line"])
def test_cubic_onset_is_c1_exact_beyond_its_width_and_stores_its_energy(kind):
    """The cubic rejoins the law at ε with its value and slope, leaves it alone beyond, is softer
    within and monotone; dp/dg matches differences; ``stiffness(p)`` inverts it; its energy is
    ½Δp²/k of the force it leaves out, Δp = kδ(1 − δ/ε)² against a penalty law k."""
    n, eps = 6, 1e-6
    c = compliance(np.full(n, E_AL), NU_AL)
    law = (
        PenaltyLaw(K_N)
        if kind == "penalty"
        else HertzLineLaw(np.full(n, 1.688e-3), np.full(n, 1.688e-3), c, c, np.full(n, 4e-3))
    )
    onset = CubicOnset(law, eps)
    g = -np.array([0.0, 1e-7, eps / 3, 0.9 * eps, 1.5 * eps, 5e-6])
    p, dp = onset.force(g)
    p_law, dp_law = law.force(g)
    np.testing.assert_array_equal(p[4:], p_law[4:])  # exact beyond ε
    assert p[0] == 0.0 and np.all(np.diff(p) > 0) and np.all(p[1:4] < p_law[1:4])
    at = np.full(n, -eps)
    np.testing.assert_allclose(onset.force(at * (1 - 1e-12))[0], law.force(at)[0], rtol=1e-9)
    np.testing.assert_allclose(onset.force(at * (1 - 1e-12))[1], law.force(at)[1], rtol=1e-6)
    h = 1e-12
    fd = (onset.force(g + h)[0] - onset.force(g - h)[0]) / (2 * h)
    np.testing.assert_allclose(dp[1:], fd[1:], rtol=1e-5)
    np.testing.assert_allclose(onset.stiffness(p)[1:], -dp[1:], rtol=1e-8)
    energy = onset.energy(g)
    assert energy[0] == 0.0 and np.all(energy[1:4] > 0.0) and np.all(energy[4:] == 0.0)
    if kind == "penalty":
        d = -g[1:4]
        np.testing.assert_allclose(energy[1:4], (K_N * d * (1 - d / eps) ** 2) ** 2 / (2 * K_N))
    with pytest.raises(ValueError, match="stiffens too fast"):
        CubicOnset(_Quartic(), eps).force(g)


class _Quartic:
    """p = c δ⁴: p(ε) = ε p'(ε)/4, past what a monotone cubic onset can join (ε p'(ε)/3)."""

    def force(self, g):
        d = np.maximum(-g, 0.0)
        return 1e26 * d**4, -4e26 * d**3


def test_mindlin_stick_stiffness():
    """Like materials: k_T/k_N = 2(1 − ν)/(2 − ν); K_T = that × dp/dδ at the start force, so a
    crossing reaches μP after μP/K_T ≈ (2/3)·(3μP/(16G*a)) (Mindlin's gross-slip distance)."""
    assert mindlin_ratio(E_AL, NU_AL, E_AL, NU_AL) == pytest.approx(2 * (1 - NU_AL) / (2 - NU_AL))
    law = HertzPointLaw(np.array([point_coefficient(R, R, np.pi / 2, E_AL, NU_AL, E_AL, NU_AL)]))
    friction = Mindlin(np.array([MU]), mindlin_ratio(E_AL, NU_AL, E_AL, NU_AL))
    P = np.array([50.0])
    e_star = 1 / (2 * compliance(E_AL, NU_AL))
    g_star = E_AL / (2 * (1 + NU_AL)) / (2 * (2 - NU_AL))
    a = (3 * P * R / (4 * e_star)) ** (1 / 3)
    k_t = friction.stiffness(P, law)
    assert k_t[0] == pytest.approx(8 * g_star * a[0], rel=1e-3)  # the start offset: 1e-3
    gross = 3 * MU * P / (16 * g_star * a)
    assert (MU * P / k_t)[0] == pytest.approx(2 / 3 * gross[0], rel=1e-3)
    assert friction.stiffness(np.array([0.0]), law)[0] == 0.0
