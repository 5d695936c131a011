"""Friction laws as objects, evaluated for all pairs of a group at once (numpy).

Physics only: functions of slips, normal forces and histories, returning tractions and their
exact derivatives. Units: m, N; stiffnesses in N/m (per pair).

The laws are Coulomb with an elastic stick branch and a radial return onto the cone. The stick
stiffness K_T is evaluated with the normal force P₀ at the start of the step and frozen over the
step (so that Newton stays quadratic); the trial traction t_tr = P_n t_old + K_T Δg_T (P_n = I − n⊗n
re-projects the stored traction onto the current tangent plane) is kept when ‖t_tr‖ ≤ μp (stick),
else scaled back to μp t_tr/‖t_tr‖ (slip). The laws differ in K_T only:

* ``ElasticSlip``: K_T = μP₀/g_lim, friction reaches μP after a slip g_lim (the seed paper's);
* ``Mindlin``: K_T = k_T/k_N × dp/dδ(P₀), Mindlin's initial tangential stiffness of the Hertz
  contact (``strand.contact.hertz.mindlin_ratio``), from the normal law
  (``strand.contact.normal_laws``).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
import numpy.typing as npt

from .normal_laws import NormalLaw

__all__ = [
    "FrictionLaw",
    "ElasticSlip",
    "Mindlin",
    "CoulombResult",
    "FrictionTerms",
    "coulomb_return",
    "tangential_stiffness",
]

Array = npt.NDArray[np.float64]


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
    surface points since the last converged step, the stick stiffness K_T (P,), N/m, and the
    law's own history (``FrictionLaw.initial_history``) as it stands if this evaluation is
    committed."""

    residual: Array
    tangent: Array | None
    traction: Array
    slipping: npt.NDArray[np.bool_]
    slip: Array
    stiffness: Array
    history: dict[str, Array] = field(default_factory=dict)


@dataclass(frozen=True)
class FrictionLaw(ABC):
    """Coulomb friction (coefficients ``mu`` (P,)) with an elastic stick branch."""

    mu: Array

    #: names of the discrete choices of a step that ``terms`` reports in its history and takes
    #: back in ``history`` to keep them (``PairGroup.SETTLE``); none for a Coulomb law
    CHOICES: ClassVar[tuple[str, ...]] = ()

    @property
    def active(self) -> bool:
        return bool(np.any(np.asarray(self.mu) > 0))

    @abstractmethod
    def stiffness(self, p_start: Array, normal: NormalLaw) -> Array:
        """K_T (P,) in N/m from the normal forces at the start of the step."""

    def choose(
        self, slip: Array, t_old: Array, n_old: Array, p_old: Array, history: dict[str, Array]
    ) -> dict[str, Array]:
        """The step's ``CHOICES`` (each (P,)) for the slip Δg_T (P, 3) since the last converged
        step (traction t_old, normal n_old, normal force p_old, the law's ``history``); none
        here."""
        return {}

    def initial_history(self, n_pairs: int) -> dict[str, Array]:
        """Per-pair arrays the law keeps between steps beyond the traction, normal and normal
        force that every law keeps (none here); a group commits them with the converged step."""
        return {}

    def terms(
        self,
        S: Array,
        dq: Array,
        p: Array,
        dp_dq: Array | None,
        p_old: Array,
        t_old: Array,
        n_old: Array,
        *,
        normal: NormalLaw,
        jacobian: bool,
        history: dict[str, Array] | None = None,
    ) -> FrictionTerms:
        """Friction of all pairs on a slip operator S (P, 3, m): Δg_T = S Δq.

        Returns the residual Sᵀt (P, m), the tangent Sᵀ(∂t/∂Δg_T)S + Sᵀ(∂t/∂p)⊗∂p/∂q (P, m, M)
        over all M dofs of the pair's layout (``dp_dq`` (P, M); None without ``jacobian``), the
        traction, the slipping flags (pairs at the cap with a positive normal force), the slip
        Δg_T and the stick stiffness K_T of the step. ``history``: the law's committed history
        (``initial_history``; none for a Coulomb law with a linear stick).
        """
        mu = np.broadcast_to(np.asarray(self.mu, float), p.shape)
        slip = np.einsum("pij,pj->pi", S, dq)
        k_t = self.stiffness(p_old, normal)
        ret, after = self._return(t_old, slip, n_old, p, p_old, mu, k_t, history)
        f = np.einsum("pij,pi->pj", S, ret.traction)
        K = None
        if jacobian:
            assert dp_dq is not None  # given with the jacobian
            St = S.transpose(0, 2, 1)
            K = np.einsum("pj,pk->pjk", np.einsum("pij,pi->pj", S, ret.d_pressure), dp_dq)
            K[:, :, : S.shape[2]] += St @ ret.d_slip @ S
        return FrictionTerms(f, K, ret.traction, ret.slipping & (p > 0), slip, k_t, after)

    def _return(self, t_old, slip, n_old, p, p_old, mu, k_t, history):
        """The traction map of the step (``CoulombResult``) and the law's history after it: a
        linear stick K_T and the radial return onto μp (``coulomb_return``)."""
        return coulomb_return(t_old, slip, n_old, p, mu, k_t), {}


@dataclass(frozen=True)
class ElasticSlip(FrictionLaw):
    """K_T = μP₀/g_lim: friction reaches μP after an elastic slip ``g_lim`` (m)."""

    g_lim: float = 5e-6

    def stiffness(self, p_start: Array, normal: NormalLaw) -> Array:
        return tangential_stiffness(np.asarray(self.mu, float), p_start, self.g_lim)


@dataclass(frozen=True)
class Mindlin(FrictionLaw):
    """K_T = ``ratio`` × dp/dδ(P₀): Mindlin's initial tangential stiffness of a Hertz contact,
    ``ratio`` = k_T/k_N per pair (``hertz.mindlin_ratio``)."""

    ratio: Array | float

    def stiffness(self, p_start: Array, normal: NormalLaw) -> Array:
        return self.ratio * normal.stiffness(p_start) * (p_start > 0)
