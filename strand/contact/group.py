"""The base of every contact group: evaluate → normal law → friction → commit, for all pairs at once.

A group holds pairs that share a stencil layout and implements the solver's ``PairTerms`` protocol:
given the nodal unknowns w, ``evaluate`` returns every pair's residual (P, m) and tangent (P, m, M).
Subclasses say how a pair's gap and slip follow from its stencil (``PairKinematics``: the
small-sliding ``ContactGroup``, the large-sliding ``SlidingGroup``); the base applies the laws:

* normal part: p = law(g), residual −p ∂g/∂q, tangent −(dp/dg) ∂g⊗∂g − p ∂²g/∂q²;
* friction: slip Δg_T = S Δq since the last converged step (n and the tangent plane frozen at its
  start), the traction t from the friction law's radial return; residual Sᵀt, tangent
  Sᵀ(∂t/∂Δg_T)S + Sᵀ(∂t/∂p)⊗(∂p/∂q) — unsymmetric in slip.

``state`` (the last evaluation) and ``history`` are the same objects for a group's whole life,
their arrays updated in place: a reference taken before a load ramp follows it.

History (traction, normal, normal force, and what the subclass keeps) is committed after converged
steps only, with the friction history of each pair (``FrictionHistory``): the relative tangential
displacement of its surface points summed over the steps, the part of it that is Coulomb sliding
(Δg_s = Δg_T − Δt/K_T, the slip less the change of the elastic stick), and the energy friction
dissipated, Σ t·Δg_s. Units: m, N, rad, J.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from .friction_laws import FrictionLaw
from .normal_laws import CubicOnset, NormalLaw, SmoothOnset

__all__ = ["ContactState", "FrictionHistory", "PairKinematics", "PairGroup", "tangential_part"]

Array = npt.NDArray[np.float64]

#: the prefix of the friction law's own history arrays in ``history_arrays``
LAW = "friction_"


@dataclass
class ContactState:
    """Per-pair results of the last evaluation: gap g (m), normal force p (N), traction t (N),
    current normal n, whether the pair slips. A group keeps one state and updates its arrays in
    place at every evaluation (``fill``)."""

    gap: Array
    force: Array
    traction: Array
    normal: Array
    slipping: npt.NDArray[np.bool_]

    def fill(self, gap, force, traction, normal, slipping) -> None:
        """Put new values into these arrays, in place: a reference to the state, or to one of
        its arrays, kept before a load ramp reads the values of the last evaluation."""
        self.gap[...] = gap
        self.force[...] = force
        self.traction[...] = traction
        self.normal[...] = normal
        self.slipping[...] = slipping


@dataclass
class FrictionHistory:
    """Per pair, summed over the converged steps since t = 0: ``slip`` (P, 3), the relative
    tangential displacement of the two surface points (m); ``sliding`` (P, 3), its Coulomb part
    (m; zero while the pair sticks); ``work`` (P,), the energy dissipated by friction (J)."""

    slip: Array
    sliding: Array
    work: Array

    @classmethod
    def zeros(cls, n_pairs: int) -> FrictionHistory:
        return cls(np.zeros((n_pairs, 3)), np.zeros((n_pairs, 3)), np.zeros(n_pairs))

    def copy(self) -> FrictionHistory:
        return FrictionHistory(self.slip.copy(), self.sliding.copy(), self.work.copy())


def friction_increment(
    slip: Array, k_t: Array, traction: Array, t_old: Array, n_old: Array
) -> tuple[Array, Array]:
    """Coulomb sliding Δg_s (P, 3) and dissipated energy t·Δg_s (P,) of a converged step with
    slip Δg_T, stick stiffness K_T and traction t, from the traction t_old at the step's start
    (normal n_old): Δg_s = Δg_T − (t − P_n t_old)/K_T; zero where K_T = 0 (not in contact at
    the step's start, so nothing to slide against)."""
    closed = k_t > 0
    elastic = (traction - tangential_part(t_old, n_old)) / np.where(closed, k_t, 1.0)[:, None]
    sliding = np.where(closed[:, None], slip - elastic, 0.0)
    return sliding, np.einsum("pi,pi->p", traction, sliding)


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

    A friction law with discrete choices in a step (``FrictionLaw.CHOICES``: Mindlin–Deresiewicz's
    reversals) makes them afresh until ``SETTLE`` tangents of a step have been evaluated, then
    keeps those of the last one until the step is committed or rolled back, so that Newton meets
    no kink where a pair barely moves (as semismooth Newton methods freeze their active set).
    On 0.3 m of Cardinal (tension, first leg) 0.5 % of the pairs' steps end on a choice that
    their converged slip contradicts; letting a later tangent change it, once a step, took 22 %
    more Newton iterations there (design notes, 2026-11-29).
    """

    #: tangent evaluations of a step after which the law's choices are kept (2: those of the
    #: first Newton iterate, which has moved every pair the way the step takes it)
    SETTLE = 2

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
        self._friction: tuple[Array, Array] | None = None  # (Δg_T, K_T) of the last evaluation
        #: the friction law's own history (``FrictionLaw.initial_history``), committed per step
        self._law_history = friction_law.initial_history(n_pairs) if friction_law else {}
        self._law_next: dict[str, Array] = {}  # ... as the last evaluation leaves it
        self._new_step()
        #: per-pair stabilisation springs (N/m; None: off, ``stabilise``), the energy they held
        #: at the last evaluation (J), and the gaps they hold to (m: those of the last commit,
        #: or of the first evaluation, at the initial unknowns, before any)
        self._stabilisation: Array | None = None
        self._held_law: CubicOnset | None = None  # the normal law while held (``stabilise``)
        self.stabilisation_energy = 0.0
        self._g_old: Array | None = None
        self.history = FrictionHistory.zeros(n_pairs)
        self.state = ContactState(
            np.zeros(n_pairs),
            np.zeros(n_pairs),
            np.zeros((n_pairs, 3)),
            n0.copy(),
            np.zeros(n_pairs, dtype=bool),
        )

    def __len__(self) -> int:
        return len(self.stencils)

    def _new_step(self) -> None:
        """Forget the choices of the step that ended (``_choose``)."""
        self._tangents = 0  # tangent evaluations of this step
        self._choices: dict[str, Array] = {}

    def stabilise(self, stiffness: Array | float | None, onset: float | None = None) -> bool:
        """Hold every pair's relative motion since the step's start, its slip Δg_T and its
        change of gap Δg_N, open pairs' as well, with a spring of ``stiffness`` (N/m, per pair
        or one for all; None: off): residual Sᵀ k Δg_T + k Δg_N ∂g/∂q, tangent k SᵀS +
        k ∂g/∂q ⊗ ∂g/∂q (the gap's curvature times k Δg_N, a few mN, is left out). ``onset``
        (m): while held, a normal law with a C¹ onset (``SmoothOnset``) rises over this wider
        one, the law itself beyond (``CubicOnset``). A stabilisation of a step that would not
        converge (``strand.solver.stabilisation``), not a law: the springs are not committed,
        but a step converged under them commits the forces it converged to (the onset's as
        well). Returns whether the wider onset is on (False for a law without an onset)."""
        self._held_law = None
        if stiffness is None:
            self._stabilisation = None
            return False
        if onset is not None and isinstance(self.normal_law, SmoothOnset):
            self._held_law = CubicOnset(self.normal_law, onset)
        k = np.broadcast_to(np.asarray(stiffness, float), (len(self),)).copy()
        if np.any(k < 0):
            raise ValueError("stabilise: the stiffness must be >= 0")
        self._stabilisation = k
        return self._held_law is not None

    @property
    def friction(self) -> bool:
        return self.friction_law is not None and self.friction_law.active

    def _choose(self, S: Array, dq: Array, jacobian: bool) -> dict[str, Array]:
        """The law's choices (``FrictionLaw.CHOICES``) to evaluate with, given the slip
        Δg_T = S Δq: made afresh until ``SETTLE`` tangents of the step have been evaluated,
        then those of the last of them."""
        law = self.friction_law
        if not law.CHOICES:
            return {}
        if self._tangents >= self.SETTLE:
            return self._choices
        slip = np.einsum("pij,pj->pi", S, dq)
        chosen = law.choose(slip, self._t_old, self._n_old, self._p_old, self._law_history)
        if jacobian:
            self._tangents += 1
            self._choices = chosen
        return chosen

    def _kinematics(self, W: Array, jacobian: bool) -> PairKinematics:
        raise NotImplementedError

    def evaluate(self, w: Array, jacobian: bool = True):
        W = w[self.stencils]  # (P, k, 6)
        kin = self._kinematics(W, jacobian)
        normal_law = self.normal_law if self._held_law is None else self._held_law
        if self._held_law is None:
            p, dp_dg = normal_law.force(kin.gap)
            left_out = 0.0
        else:  # the force the wider onset leaves out, as an energy, from the same evaluation
            p, dp_dg, onset_energy = self._held_law.force_and_energy(kin.gap)
            left_out = float(onset_energy.sum())
        G = kin.gradient
        if self._g_old is None:  # the first evaluation: the initial unknowns' gaps
            self._g_old = kin.gap.copy()
        f = -p[:, None] * G
        K = None
        if jacobian:
            K = G[:, :, None] * G[:, None, :]
            K *= -dp_dg[:, None, None]
            kin.add_hessian(K, -p)
        traction = np.zeros((len(p), 3))
        slipping = np.zeros(len(p), dtype=bool)
        if self.friction or self._stabilisation is not None:
            S, dq = kin.slip()
        if self._stabilisation is not None:
            self._add_stabilisation(S, dq, kin.gap, G, f, K, left_out)
        if self.friction:
            choices = self._choose(S, dq, jacobian)
            ft = self.friction_law.terms(
                S,
                dq,
                p,
                dp_dg[:, None] * G,
                self._p_old,
                self._t_old,
                self._n_old,
                normal=normal_law,
                jacobian=jacobian,
                history=self._law_history | choices,
            )
            m = S.shape[2]
            f[:, :m] += ft.residual
            if jacobian:
                K[:, :m, :] += ft.tangent
            traction, slipping = ft.traction, ft.slipping
            self._friction = (ft.slip, ft.stiffness)
            self._law_next = ft.history
        self.state.fill(kin.gap, p, traction, kin.normal, slipping)
        self._last = W
        return f, K

    def _add_stabilisation(
        self,
        S: Array,
        dq: Array,
        gap: Array,
        G: Array,
        f: Array,
        K: Array | None,
        left_out: float = 0.0,
    ) -> None:
        """Add the springs of ``stabilise`` on the slip S dq and the change of gap since the
        step's start (gap gradient G) to the residual f and tangent K, in place; their energy
        plus ``left_out`` (J: the wider onset's, ``CubicOnset.energy``) is the group's
        ``stabilisation_energy``."""
        k = self._stabilisation
        assert k is not None and self._g_old is not None  # only while the springs are on
        dg = gap - self._g_old
        slip = np.einsum("pij,pj->pi", S, dq)
        m = S.shape[2]
        f[:, :m] += np.einsum("pij,pi->pj", S, k[:, None] * slip)
        f += (k * dg)[:, None] * G
        if K is not None:
            K[:, :m, :m] += k[:, None, None] * (S.transpose(0, 2, 1) @ S)
            K += k[:, None, None] * (G[:, :, None] * G[:, None, :])
        energy = 0.5 * (np.einsum("p,pi,pi->", k, slip, slip) + np.dot(k, dg * dg))
        self.stabilisation_energy = float(energy) + left_out

    def commit(self) -> None:
        """Accept the last evaluated state (the converged one) as the history."""
        if self._last is None:
            return
        n = self.state.normal
        if self._friction is not None:
            slip, k_t = self._friction
            sliding, work = friction_increment(
                slip, k_t, self.state.traction, self._t_old, self._n_old
            )
            h = self.history  # in place, as the state
            h.slip += slip
            h.sliding += sliding
            h.work += work
            self._friction = None  # counted once
            choices = self.friction_law.CHOICES
            self._law_history = {k: v for k, v in self._law_next.items() if k not in choices}
        self._new_step()
        self._t_old = tangential_part(self.state.traction, n)  # onto the new tangent plane
        self._n_old = n.copy()
        self._p_old = self.state.force.copy()
        self._g_old = self.state.gap.copy()
        self._commit_kinematics(self._last)

    def rollback(self) -> None:
        """Forget the current step (history is only changed by ``commit``)."""
        self._last = None
        self._friction = None
        self._law_next = {}
        self._new_step()
        self._rollback_kinematics()

    # -- checkpoints -------------------------------------------------------------------------------
    #: the per-pair arrays of ``history_arrays``, in order
    HISTORY = (
        "t_old",
        "n_old",
        "p_old",
        "slip",
        "sliding",
        "work",
        "gap",
        "force",
        "traction",
        "normal",
        "slipping",
    )

    def history_arrays(self) -> dict[str, Array]:
        """Everything the next step starts from, per pair (first axis: the group's pairs): the
        committed traction, normal and normal force, the friction history, the last state, and
        what the kinematics keep beyond the unknowns (``_kinematics_history``)."""
        s, h = self.state, self.history
        values = (
            self._t_old,
            self._n_old,
            self._p_old,
            h.slip,
            h.sliding,
            h.work,
            s.gap,
            s.force,
            s.traction,
            s.normal,
            s.slipping,
        )
        out = {k: np.array(v, copy=True) for k, v in zip(self.HISTORY, values, strict=True)}
        out |= {LAW + k: np.array(v, copy=True) for k, v in self._law_history.items()}
        return out | {k: np.array(v, copy=True) for k, v in self._kinematics_history().items()}

    def restore_history(self, arrays: dict[str, Array], w: Array) -> None:
        """Return to a committed state: ``arrays`` as ``history_arrays`` gave them, ``w`` the
        nodal unknowns (n_blocks, 6) of that state."""
        a = {k: np.array(v, copy=True) for k, v in arrays.items()}
        self._t_old, self._n_old, self._p_old = a["t_old"], a["n_old"], a["p_old"]
        h = self.history
        h.slip[...], h.sliding[...], h.work[...] = a["slip"], a["sliding"], a["work"]
        self.state.fill(a["gap"], a["force"], a["traction"], a["normal"], a["slipping"])
        self._g_old = np.array(a["gap"], copy=True)
        for k in self._law_history:
            self._law_history[k] = a[LAW + k]
        self._restore_kinematics_history(a)
        self._last, self._friction, self._law_next = None, None, {}
        self._new_step()
        self._commit_kinematics(w[self.stencils])

    def _kinematics_history(self) -> dict[str, Array]:
        """Per-pair arrays the kinematics keep that the unknowns do not give back."""
        return {}

    def _restore_kinematics_history(self, arrays: dict[str, Array]) -> None:
        """Set what ``_kinematics_history`` returned."""

    def _commit_kinematics(self, W: Array) -> None:
        """Keep what the kinematics need from the converged stencil unknowns W."""

    def _rollback_kinematics(self) -> None:
        """Return the kinematics to the last committed step."""

    @property
    def committed_force(self) -> Array:
        """Normal forces (N) at the last committed step."""
        return self._p_old
