"""Normal contact laws as objects, evaluated for all pairs of a group at once (numpy).

Physics only: functions of the gaps, returning the normal forces and their exact derivatives.
Units: m, N; stiffnesses in N/m (per pair).

A normal law gives the normal force p(g) ≥ 0 (compression positive, g the gap, δ = −g the
approach) and dp/dg; a pair counts as closed in the tangent for g ≤ 0 (pairs start at g = 0):

* ``PenaltyLaw``: p = K_N⟨−g⟩ (the seed paper's);
* ``LinePenaltyLaw``: the same per unit length of a line contact, K_N = k ℓ over each line pair's
  tributary length ℓ (given by ``contact_terms``);
* ``HertzPointLaw``: crossed cylinders, p = c δ^{3/2} (``strand.contact.hertz``);
* ``HertzLineLaw``: parallel-axis cylinders, the approach of the axes under a line load;
* ``SmoothOnset``: any of them made C¹ at first touch (shifted by ε of approach);
* ``CubicOnset``: any of them made C¹ at first touch by a cubic over the first ε of approach,
  exact beyond (the held attempts' law, ``strand.solver.stabilisation``).

The friction laws that go with them: ``strand.contact.friction_laws``.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np
import numpy.typing as npt

__all__ = [
    "NormalLaw",
    "PenaltyLaw",
    "LinePenaltyLaw",
    "HertzPointLaw",
    "HertzLineLaw",
    "SmoothOnset",
    "CubicOnset",
    "normal_force",
]

Array = npt.NDArray[np.float64]


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


@dataclass(frozen=True)
class CubicOnset(NormalLaw):
    """``law`` made C¹ at first touch by a cubic over the first ``width`` ε of approach δ = −g,
    and exact beyond: p = aδ² + bδ³ on 0 ≤ δ < ε, with p(ε) = p_law(ε), p'(ε) = p'_law(ε).

    Unlike ``SmoothOnset`` it moves no force of a pair pressed by more than ε; within ε the force
    is softer than the law's (for a law p ≈ kδ, by k δ (1 − δ/ε)² at most, 4kε/27 at δ = ε/3).
    The stiffness p' = δ(2a + 3bδ) stays positive over the cubic where a > 0, that is
    p(ε) > ε p'(ε)/3 (a penalty: 1; Hertz line contact: 0.8–0.95; Hertz point contact: 2/3);
    a law for which it is not is refused at its first evaluation. ``energy(g)``, ½ Δp²/k, is a
    measure of the force it leaves out (a chosen one: the work left out, ∫Δp dδ, is up to
    7.6 times larger for a penalty law), what a held attempt reports beside its springs'
    (``strand.solver.stabilisation``). Arrays are (P,), one per pair of ``law``.
    """

    law: NormalLaw
    width: float = 1e-6  # m

    #: (p(ε), p'(ε), a, b) per number of pairs (the law is immutable: computed once)
    _ends_cache: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self):
        if not self.width > 0:
            raise ValueError(f"CubicOnset: width {self.width} m, must be > 0")

    def _ends(self, n: int) -> tuple[Array, Array, Array, Array]:
        """p(ε), p'(ε) of the law and the cubic's a, b (n,)."""
        if n not in self._ends_cache:
            eps = self.width
            p_e, dp_e = self.law.force(np.full(n, -eps))
            k_e = -dp_e
            b = (k_e * eps - 2 * p_e) / eps**3
            a = (3 * p_e - k_e * eps) / eps**2
            if not np.all(a > 0):
                raise ValueError(
                    f"CubicOnset: the law stiffens too fast over {eps:g} m for a monotone "
                    "cubic (p(ε) ≤ ε p'(ε)/3); a narrower width, or SmoothOnset"
                )
            self._ends_cache[n] = (p_e, k_e, a, b)
        return self._ends_cache[n]

    def _with_law(self, g: Array) -> tuple[Array, Array, Array, Array]:
        """p, dp/dg and the law's own p_law, dp_law/dg at the gaps g (P,)."""
        d = -np.asarray(g, float)
        assert d.ndim == 1, "CubicOnset: gaps (P,), one per pair"
        p_law, dp_law = self.law.force(-d)
        _, _, a, b = self._ends(len(d))
        x = np.clip(d, 0.0, self.width)
        ramp = d < self.width
        p = np.where(ramp, x * x * (a + b * x), p_law)
        dp = np.where(ramp, -x * (2 * a + 3 * b * x), dp_law)
        return p, dp, p_law, dp_law

    def force(self, g: Array) -> tuple[Array, Array]:
        return self._with_law(g)[:2]

    def stiffness(self, p: Array) -> Array:
        p = np.maximum(np.asarray(p, float), 0.0)
        p_e, k_e, a, b = self._ends(len(p))
        # the cubic's δ for p < p(ε): bisection on the monotone cubic (vectorised)
        lo, hi = np.zeros_like(p), np.full_like(p, self.width)
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            below = mid * mid * (a + b * mid) < p
            lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
        x = 0.5 * (lo + hi)
        return np.where(p < p_e, x * (2 * a + 3 * b * x), self.law.stiffness(p))

    def energy(self, g: Array) -> Array:
        """½ Δp²/k per pair (J, ≥ 0): the energy the law's stiffness k = p'_law stores under the
        force Δp = p_law − p the cubic leaves out; zero beyond ε, where the force is the law's."""
        return self.force_and_energy(g)[2]

    def force_and_energy(self, g: Array) -> tuple[Array, Array, Array]:
        """``force(g)`` and ``energy(g)`` from one evaluation of the law (the Hertz line law
        inverts per pair): p, dp/dg and ½ Δp²/k (P,)."""
        p, dp, p_law, dp_law = self._with_law(g)
        k = np.where(dp_law < 0.0, -dp_law, np.inf)
        return p, dp, 0.5 * (p_law - p) ** 2 / k
