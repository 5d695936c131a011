"""Contact laws as objects, evaluated for all pairs of a group at once (numpy).

Physics only: functions of gaps, slips and histories, returning forces and their exact derivatives.
Units: m, N; stiffnesses in N/m (per pair).

Normal laws give the normal force p(g) ≥ 0 (compression positive, g the gap, δ = −g the approach)
and dp/dg; a pair counts as closed in the tangent for g ≤ 0 (pairs start at g = 0):

* ``PenaltyLaw``: p = K_N⟨−g⟩ (the seed paper's);
* ``LinePenaltyLaw``: the same per unit length of a line contact, K_N = k ℓ over each line pair's
  tributary length ℓ (given by ``contact_terms``);
* ``HertzPointLaw``: crossed cylinders, p = c δ^{3/2} (``strand.contact.hertz``);
* ``HertzLineLaw``: parallel-axis cylinders, the approach of the axes under a line load.

Friction laws are Coulomb with an elastic stick branch and a radial return onto the cone. The stick
stiffness K_T is evaluated with the normal force P₀ at the start of the step and frozen over the
step (so that Newton stays quadratic); the trial traction t_tr = P_n t_old + K_T Δg_T (P_n = I − n⊗n
re-projects the stored traction onto the current tangent plane) is kept when ‖t_tr‖ ≤ μp (stick),
else scaled back to μp t_tr/‖t_tr‖ (slip). The laws differ in K_T only:

* ``ElasticSlip``: K_T = μP₀/g_lim, friction reaches μP after a slip g_lim (the seed paper's);
* ``Mindlin``: K_T = k_T/k_N × dp/dδ(P₀), Mindlin's initial tangential stiffness of the Hertz
  contact (``strand.contact.hertz.mindlin_ratio``).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np
import numpy.typing as npt

from .hertz import compliance, mindlin_ratio, point_coefficient

__all__ = [
    "NormalLaw",
    "PenaltyLaw",
    "LinePenaltyLaw",
    "HertzPointLaw",
    "HertzLineLaw",
    "SmoothOnset",
    "FrictionLaw",
    "ElasticSlip",
    "Mindlin",
    "CoulombResult",
    "FrictionTerms",
    "coulomb_return",
    "normal_force",
    "tangential_stiffness",
    "hertz_mindlin",
]

Array = npt.NDArray[np.float64]


# -- normal laws ------------------------------------------------------------------------------------
class NormalLaw(ABC):
    """Normal force of the pairs of one group as a function of their gaps."""

    @abstractmethod
    def force(self, g: Array) -> tuple[Array, Array]:
        """p (P,) in N and dp/dg (P,) in N/m; closed pairs are g ≤ 0."""

    @abstractmethod
    def stiffness(self, p: Array) -> Array:
        """dp/dδ (P,) in N/m at the normal force p (P,) in N."""


def normal_force(g: Array, k_n: Array | float) -> tuple[Array, Array]:
    """p = K_N⟨−g⟩ and dp/dg = −K_N for closed pairs (g ≤ 0), 0 for open ones."""
    closed = g <= 0.0
    k = np.broadcast_to(k_n, g.shape)
    return np.where(closed, -k * g, 0.0), np.where(closed, -k, 0.0)


@dataclass(frozen=True)
class PenaltyLaw(NormalLaw):
    """p = K_N⟨−g⟩ with K_N (N/m, per pair or one for all)."""

    k: Array | float

    def force(self, g: Array) -> tuple[Array, Array]:
        return normal_force(g, self.k)

    def stiffness(self, p: Array) -> Array:
        return np.broadcast_to(np.asarray(self.k, float), np.shape(p)).copy()


@dataclass(frozen=True)
class LinePenaltyLaw(NormalLaw):
    """A penalty per unit length of a line contact: p = k ℓ ⟨−g⟩ for a line pair standing for a
    tributary length ℓ (m) of the contact line, k in N/m² (one for all pairs or per pair).

    ``contact_terms`` gives it its pairs' tributary lengths (``for_pairs``); the result is
    ``PenaltyLaw(k * pairs.tributary)``, without the multiplication written by hand.
    """

    k_per_length: Array | float
    tributary: Array | None = None

    def for_pairs(self, tributary: Array) -> LinePenaltyLaw:
        """This law on pairs of tributary lengths ``tributary`` (P,), m, all positive."""
        tributary = np.asarray(tributary, dtype=float)
        if not np.all(tributary > 0):
            raise ValueError(
                "LinePenaltyLaw is a penalty per unit length of line contacts: its pairs need "
                "positive tributary lengths (line pairs; crossings take PenaltyLaw, N/m)"
            )
        return replace(self, tributary=tributary)

    @property
    def k(self) -> Array:
        """K_N = k ℓ (P,), N/m."""
        if self.tributary is None:
            raise ValueError(
                "LinePenaltyLaw has no tributary lengths yet: give it to contact_terms with the "
                "line pairs (or call for_pairs(pairs.tributary))"
            )
        return np.asarray(self.k_per_length, float) * self.tributary

    def force(self, g: Array) -> tuple[Array, Array]:
        return normal_force(g, self.k)

    def stiffness(self, p: Array) -> Array:
        return np.broadcast_to(self.k, np.shape(p)).copy()


class _ApproachLaw(NormalLaw):
    """A law p = f(δ) that is stiffening from f(0) = f'(0) = 0, started at an approach δ_r.

    p = f(δ + δ_r) − f(δ_r) keeps p(0) = 0 but gives closed pairs a first tangent f'(δ_r) > 0
    (Hertz contacts have none at first touch, and all pairs start touching). δ_r = 10 nm changes
    the force by under 0.5 % at approaches above 3 µm (Cardinal's contacts: 3–9 µm).
    """

    START = 1e-8  # m

    @abstractmethod
    def _force(self, d: Array) -> tuple[Array, Array]:
        """f(δ) and f'(δ) for δ > 0."""

    @abstractmethod
    def _approach(self, p: Array) -> Array:
        """δ with f(δ) = p (p ≥ f(δ_r))."""

    @cached_property
    def offset(self) -> Array:
        """f(δ_r) (P,), N: what the start takes off the force."""
        return self._force(np.full(len(self), self.START))[0]

    def force(self, g: Array) -> tuple[Array, Array]:
        closed = g <= 0.0
        f, df = self._force(np.where(closed, -g, 0.0) + self.START)
        return np.where(closed, f - self.offset, 0.0), np.where(closed, -df, 0.0)

    def stiffness(self, p: Array) -> Array:
        d = self._approach(np.maximum(p, 0.0) + self.offset)
        return self._force(d)[1]

    @abstractmethod
    def __len__(self) -> int: ...


@dataclass(frozen=True)
class HertzPointLaw(_ApproachLaw):
    """Hertz point contact p = c δ^{3/2} (c per pair, N/m^{3/2}; see ``hertz.point_coefficient``)."""

    c: Array

    def __len__(self) -> int:
        return len(self.c)

    def _force(self, d):
        return self.c * d**1.5, 1.5 * self.c * np.sqrt(d)

    def _approach(self, p):
        return (p / self.c) ** (2.0 / 3.0)


@dataclass(frozen=True)
class HertzLineLaw(_ApproachLaw):
    """Two cylinders in contact along their (parallel) axes, per pair of tributary length ℓ.

    The approach of the axes under a line load q = p/ℓ (Johnson 1985, eq. 5.39) is
    δ(q) = (q/π)[C₁(2 ln(4R₁/b) − 1) + C₂(2 ln(4R₂/b) − 1)], with C_i = (1 − ν_i²)/E_i, the contact
    half-width b = (4qR/(πE*))^{1/2}, 1/R = 1/R₁ + 1/R₂ and 1/E* = C₁ + C₂. It is inverted for q by
    Newton on ln q. Arrays (P,): radii in m, C in 1/Pa, length ℓ in m.
    """

    r1: Array
    r2: Array
    c1: Array
    c2: Array
    length: Array

    def __len__(self) -> int:
        return len(self.length)

    def _logs(self, q):
        """ln(4R_i/b) for i = 1, 2."""
        r = self.r1 * self.r2 / (self.r1 + self.r2)
        half_log_b = 0.5 * np.log(4 * q * r * (self.c1 + self.c2) / np.pi)
        return np.log(4 * self.r1) - half_log_b, np.log(4 * self.r2) - half_log_b

    def _line(self, q):
        """δ(q) and dδ/dq."""
        l1, l2 = self._logs(q)
        d = q / np.pi * (self.c1 * (2 * l1 - 1) + self.c2 * (2 * l2 - 1))
        dd = (2 * self.c1 * (l1 - 1) + 2 * self.c2 * (l2 - 1)) / np.pi
        return d, dd

    def _force(self, d):
        q = self._approach_inverse(d)
        return q * self.length, self.length / self._line(q)[1]

    def _approach(self, p):
        return self._line(p / self.length)[0]

    def _approach_inverse(self, d):
        # Newton on x = ln q: δ is close to linear in q (its log varies slowly), so start there
        x = np.log(d * np.pi / (2 * (self.c1 + self.c2) * 6.0))
        for _ in range(50):
            q = np.exp(x)
            value, slope = self._line(q)
            step = (value - d) / (q * slope)
            x = np.clip(x - step, -60.0, 60.0)  # absurd iterates stay finite (q ≤ 1e26 N/m)
            if np.max(np.abs(step)) < 1e-14:
                break
        return np.exp(x)


@dataclass(frozen=True)
class SmoothOnset(NormalLaw):
    """``law`` made C¹ at first touch, for pairs that start touching without load.

    A law whose tangent jumps from 0 (open) to k₀ = dp/dg at g = 0⁻ makes Newton chatter where
    many pairs sit within nanometres of touching (the wires of a packed layer). Over the first
    ``width`` ε of approach δ = −g the force rises as p = k₀δ²/(2ε); beyond, the law is shifted,
    p = p_law(δ − ε) + k₀ε/2, matching value and slope at δ = ε. With ε = 10 nm the force moves
    by k₀ε/2 at most (under 0.1 N for the wires of a strand), far below every physical scale.
    """

    law: NormalLaw
    width: float = 1e-8  # m

    #: k₀ per number of pairs (the law is immutable: computed once, not at every evaluation)
    _k0_cache: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def _k0(self, like: Array) -> Array:
        """k₀ per pair: the law's tangent just closed."""
        shape = np.shape(like)
        if shape not in self._k0_cache:
            self._k0_cache[shape] = -self.law.force(np.zeros(shape))[1]
        return self._k0_cache[shape]

    def force(self, g: Array) -> tuple[Array, Array]:
        d = -np.asarray(g, float)
        eps, k0 = self.width, self._k0(d)
        p_law, dp_law = self.law.force(np.minimum(-(d - eps), 0.0))
        ramp = d < eps
        p = np.where(ramp, k0 * np.maximum(d, 0.0) ** 2 / (2 * eps), p_law + k0 * eps / 2)
        dp = np.where(ramp, -k0 * np.maximum(d, 0.0) / eps, dp_law)
        return p, dp

    def stiffness(self, p: Array) -> Array:
        p = np.maximum(np.asarray(p, float), 0.0)
        eps, k0 = self.width, self._k0(p)
        ramp = p < k0 * eps / 2
        return np.where(
            ramp,
            np.sqrt(2 * k0 * p / eps),
            self.law.stiffness(np.maximum(p - k0 * eps / 2, 0.0)),
        )


# -- friction laws ----------------------------------------------------------------------------------
@dataclass
class CoulombResult:
    """Frictional traction t (P, 3) and its derivatives: dt/dΔg_T (P, 3, 3) and dt/dp (P, 3)."""

    traction: Array
    d_slip: Array
    d_pressure: Array
    slipping: npt.NDArray[np.bool_]


def tangential_stiffness(mu: Array, p_start: Array, g_lim: float) -> Array:
    """K_T = μ P₀/g_lim (N/m), from the normal force P₀ at the start of the step."""
    return mu * p_start / g_lim


def coulomb_return(
    t_old: Array, slip: Array, normal: Array, p: Array, mu: Array, k_t: Array
) -> CoulombResult:
    """Radial return for all pairs.

    Args:
        t_old: traction at the last converged step (P, 3), N.
        slip: tangential slip increment since that step, Δg_T (P, 3), m (in the tangent plane).
        normal: current unit normals (P, 3).
        p: current normal force (P,), N.
        mu: friction coefficients (P,); k_t: slip stiffnesses (P,), N/m.
    """
    P_n = np.eye(3) - normal[:, :, None] * normal[:, None, :]
    trial = np.einsum("pij,pj->pi", P_n, t_old) + k_t[:, None] * slip
    size = np.linalg.norm(trial, axis=1)
    cap = mu * p
    slipping = size > cap
    safe = np.where(size > 0, size, 1.0)
    nu = trial / safe[:, None]
    eye = np.broadcast_to(np.eye(3), (len(p), 3, 3))
    # stick: t = trial
    d_slip = k_t[:, None, None] * eye
    d_pressure = np.zeros_like(trial)
    traction = trial.copy()
    # slip: t = μ p ν, dt/dtrial = μp/|trial| (I − ν⊗ν)
    s = slipping
    if np.any(s):
        proj = eye[s] - nu[s, :, None] * nu[s, None, :]
        d_slip[s] = (cap[s] * k_t[s] / safe[s])[:, None, None] * proj
        d_pressure[s] = mu[s, None] * nu[s]
        traction[s] = cap[s, None] * nu[s]
    return CoulombResult(traction, d_slip, d_pressure, slipping)


@dataclass
class FrictionTerms:
    """What a friction law adds at an evaluation: residual (P, m) and tangent (P, m, M) (None
    without the Jacobian), traction t (P, 3), N, slipping flags, the slip Δg_T (P, 3), m, of the
    surface points since the last converged step, and the stick stiffness K_T (P,), N/m."""

    residual: Array
    tangent: Array | None
    traction: Array
    slipping: npt.NDArray[np.bool_]
    slip: Array
    stiffness: Array


@dataclass(frozen=True)
class FrictionLaw(ABC):
    """Coulomb friction (coefficients ``mu`` (P,)) with an elastic stick branch."""

    mu: Array

    @property
    def active(self) -> bool:
        return bool(np.any(np.asarray(self.mu) > 0))

    @abstractmethod
    def stiffness(self, p_start: Array, normal: NormalLaw) -> Array:
        """K_T (P,) in N/m from the normal forces at the start of the step."""

    def terms(
        self, S, dq, p, dp_dq, p_old, t_old, n_old, *, normal: NormalLaw, jacobian: bool
    ) -> FrictionTerms:
        """Friction of all pairs on a slip operator S (P, 3, m): Δg_T = S Δq.

        Returns the residual Sᵀt (P, m), the tangent Sᵀ(∂t/∂Δg_T)S + Sᵀ(∂t/∂p)⊗∂p/∂q (P, m, M)
        over all M dofs of the pair's layout (``dp_dq`` (P, M); None without ``jacobian``), the
        traction, the slipping flags (pairs at the cap with a positive normal force), the slip
        Δg_T and the stick stiffness K_T of the step.
        """
        mu = np.broadcast_to(np.asarray(self.mu, float), p.shape)
        slip = np.einsum("pij,pj->pi", S, dq)
        k_t = self.stiffness(p_old, normal)
        ret = coulomb_return(t_old, slip, n_old, p, mu, k_t)
        f = np.einsum("pij,pi->pj", S, ret.traction)
        K = None
        if jacobian:
            St = S.transpose(0, 2, 1)
            K = np.einsum("pj,pk->pjk", np.einsum("pij,pi->pj", S, ret.d_pressure), dp_dq)
            K[:, :, : S.shape[2]] += St @ ret.d_slip @ S
        return FrictionTerms(f, K, ret.traction, ret.slipping & (p > 0), slip, k_t)


@dataclass(frozen=True)
class ElasticSlip(FrictionLaw):
    """K_T = μP₀/g_lim: friction reaches μP after an elastic slip ``g_lim`` (m)."""

    g_lim: float = 5e-6

    def stiffness(self, p_start, normal):
        return tangential_stiffness(np.asarray(self.mu, float), p_start, self.g_lim)


@dataclass(frozen=True)
class Mindlin(FrictionLaw):
    """K_T = ``ratio`` × dp/dδ(P₀): Mindlin's initial tangential stiffness of a Hertz contact,
    ``ratio`` = k_T/k_N per pair (``hertz.mindlin_ratio``)."""

    ratio: Array | float

    def stiffness(self, p_start, normal):
        return self.ratio * normal.stiffness(p_start) * (p_start > 0)


def hertz_mindlin(
    line: bool, radius_a, radius_b, crossing_angle, tributary, *, E_a, nu_a, E_b, nu_b, mu=None
) -> tuple[NormalLaw, FrictionLaw | None]:
    """The laws of elastic wires in contact, from their radii (m) and moduli (Pa) alone.

    Crossings: ``HertzPointLaw`` of cylinders crossing at ``crossing_angle`` (rad); line pairs:
    ``HertzLineLaw`` over their ``tributary`` lengths (m). Friction: ``Mindlin`` with Coulomb
    coefficients ``mu`` (None: frictionless). Values are per pair (P,) or one for all.
    """
    r_a = np.asarray(radius_a, float)
    P = len(r_a)
    E_a, nu_a, E_b, nu_b, r_b, angle, length = (
        np.broadcast_to(np.asarray(v, float), (P,))
        for v in (E_a, nu_a, E_b, nu_b, radius_b, crossing_angle, tributary)
    )
    if line:
        law: NormalLaw = HertzLineLaw(
            r_a, r_b, compliance(E_a, nu_a), compliance(E_b, nu_b), length
        )
    else:
        law = HertzPointLaw(point_coefficient(r_a, r_b, angle, E_a, nu_a, E_b, nu_b))
    if mu is None:
        return law, None
    return law, Mindlin(
        np.broadcast_to(np.asarray(mu, float), (P,)).copy(), mindlin_ratio(E_a, nu_a, E_b, nu_b)
    )
