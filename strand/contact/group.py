"""The base of every contact group: evaluate → normal law → friction → commit, for all pairs at once.

A group holds pairs that share a stencil layout and implements the solver's ``PairTerms`` protocol:
given the nodal unknowns w, ``evaluate`` returns every pair's residual (P, m) and tangent (P, m, M).
Subclasses say how a pair's gap and slip follow from its stencil (``PairKinematics``: the
small-sliding ``ContactGroup``, the large-sliding ``SlidingGroup``); the base applies the laws:

* normal part: p = law(g), residual −p ∂g/∂q, tangent −(dp/dg) ∂g⊗∂g − p ∂²g/∂q²;
* friction: slip Δg_T = S Δq since the last converged step (n and the tangent plane frozen at its
  start), the traction t from the friction law's radial return; residual Sᵀt, tangent
  Sᵀ(∂t/∂Δg_T)S + Sᵀ(∂t/∂p)⊗(∂p/∂q) — unsymmetric in slip.

History (traction, normal, normal force, and what the subclass keeps) is committed after converged
steps only. Units: m, N, rad.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from .laws import FrictionLaw, NormalLaw

__all__ = ["ContactState", "PairKinematics", "PairGroup", "tangential_part"]

Array = npt.NDArray[np.float64]


@dataclass
class ContactState:
    """Per-pair results of the last evaluation: gap g (m), normal force p (N), traction t (N),
    current normal n, whether the pair slips."""

    gap: Array
    force: Array
    traction: Array
    normal: Array
    slipping: npt.NDArray[np.bool_]


@dataclass
class PairKinematics:
    """What a group's geometry gives the laws: gaps g (P,), current normals (P, 3), ∂g/∂q (P, M)
    over the group's layout, ``add_hessian(K, scale)`` (K += scale ∂²g/∂q², in place) and
    ``slip()`` → (S (P, 3, m), Δq (P, m)): the slip operator on the first m dofs of the layout and
    the increment of those dofs since the last converged step."""

    gap: Array
    normal: Array
    gradient: Array
    add_hessian: Callable[[Array, Array], None]
    slip: Callable[[], tuple[Array, Array]]


def tangential_part(t, n):
    """The traction t (P, 3) projected on the plane normal to n: the history carried to a step."""
    return t - np.einsum("pi,pi->p", t, n)[:, None] * n


class PairGroup:
    """Contact pairs of one layout under a normal law and a friction law (None: frictionless).

    Subclasses implement ``_kinematics(W, jacobian)`` (W = w[stencils], (P, k, 6)) and may extend
    ``_commit_kinematics``/``_rollback_kinematics`` for the state they keep.
    """

    def __init__(
        self,
        stencils,
        normal_law: NormalLaw,
        friction_law: FrictionLaw | None,
        normal0,
        index=None,
    ):
        self.stencils = np.ascontiguousarray(stencils, dtype=np.int32)
        n_pairs = len(self.stencils)
        self.normal_law = normal_law
        self.friction_law = friction_law
        self.index = np.arange(n_pairs) if index is None else np.asarray(index)
        n0 = np.asarray(normal0, dtype=float)
        self._t_old = np.zeros((n_pairs, 3))
        self._n_old = n0.copy()
        self._p_old = np.zeros(n_pairs)
        self._last: Array | None = None  # W of the last evaluation
        self.state = ContactState(
            np.zeros(n_pairs), np.zeros(n_pairs), np.zeros((n_pairs, 3)), n0.copy(),
            np.zeros(n_pairs, dtype=bool),
        )  # fmt: skip

    def __len__(self) -> int:
        return len(self.stencils)

    @property
    def friction(self) -> bool:
        return self.friction_law is not None and self.friction_law.active

    def _kinematics(self, W: Array, jacobian: bool) -> PairKinematics:
        raise NotImplementedError

    def evaluate(self, w: Array, jacobian: bool = True):
        W = w[self.stencils]  # (P, k, 6)
        kin = self._kinematics(W, jacobian)
        p, dp_dg = self.normal_law.force(kin.gap)
        G = kin.gradient
        f = -p[:, None] * G
        K = None
        if jacobian:
            K = G[:, :, None] * G[:, None, :]
            K *= -dp_dg[:, None, None]
            kin.add_hessian(K, -p)
        traction = np.zeros((len(p), 3))
        slipping = np.zeros(len(p), dtype=bool)
        if self.friction:
            S, dq = kin.slip()
            f_t, K_t, traction, slipping = self.friction_law.terms(
                S, dq, p, dp_dg[:, None] * G, self._p_old, self._t_old, self._n_old,
                self.normal_law, jacobian,
            )  # fmt: skip
            m = S.shape[2]
            f[:, :m] += f_t
            if jacobian:
                K[:, :m, :] += K_t
        self.state = ContactState(kin.gap, p, traction, kin.normal, slipping)
        self._last = W
        return f, K

    def commit(self) -> None:
        """Accept the last evaluated state (the converged one) as the history."""
        if self._last is None:
            return
        n = self.state.normal
        self._t_old = tangential_part(self.state.traction, n)  # onto the new tangent plane
        self._n_old = n.copy()
        self._p_old = self.state.force.copy()
        self._commit_kinematics(self._last)

    def rollback(self) -> None:
        """Forget the current step (history is only changed by ``commit``)."""
        self._last = None
        self._rollback_kinematics()

    def _commit_kinematics(self, W: Array) -> None:
        """Keep what the kinematics need from the converged stencil unknowns W."""

    def _rollback_kinematics(self) -> None:
        """Return the kinematics to the last committed step."""

    @property
    def committed_force(self) -> Array:
        """Normal forces (N) at the last committed step."""
        return self._p_old
