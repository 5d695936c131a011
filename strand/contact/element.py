"""The small-sliding contact element: pairs fixed at t = 0, their gaps and slips from the stencil.

Each ``ContactGroup`` holds the pairs of one kind (crossings or line pairs); the shared
``PairGroup`` applies the normal and friction laws (``strand.contact.group``). Per pair, the gap is
one of ``kinematics``'s normals, and the slip since the last converged step is Δg_T = S Δq, with
n and the tangent plane frozen at the start of the step. Two slip measures (``SLIP``):

* "surface": S = P_n[−I, r_a n×, I, r_b n×] on (u_a, θ_a, u_b, θ_b), the relative motion of the
  two surface points in contact. A wire may roll on its neighbour without slip.
* "centreline": the motion of the centre lines' closest points, Δg_T = Δξ₁ t₁ − Δξ₂ t₂ (the seed
  paper's g_T from the closest-point parameters ξ, as in Wriggers & Zavarise 1997): the change of
  the conditions (x_b − x_a)·t₁ = (x_b − x_a)·t₂ = 0, with x_b − x_a = d n, d = r_a + r_b and the
  tangents turned by δω = T(θ)δθ, gives (Δu_b − Δu_a)·tᵢ + d δωᵢ·(tᵢ × n) = rᵢ, and Δg_T is the
  vector of the tangent plane with Δg_T·tᵢ = rᵢ. A rigid motion of the pair gives no slip; a
  wire's spin (δω·t) does not enter, so rolling is slip. Line pairs have one condition; their
  slip is that of b's centre against the point of a's cross-section at d n,
  P_n(Δu_b − Δu_a + d n × δω_a).

``resolve_normal`` names the normal a group uses; ``strand.contact.pairs`` builds groups on any
beams (``strand.model.strand_contact`` those of a strand). Units: m, N, rad.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from .errors import ContactError
from .friction_laws import FrictionLaw
from .group import PairGroup, PairKinematics
from .kinematics import (
    NORMALS,
    gap_derivatives,
    rotation_matrix,
    skew,
    stencil_nodes,
    tangent_map,
)
from .normal_laws import NormalLaw

__all__ = ["SLIP", "ContactGroup", "check_slip", "resolve_normal"]

#: the slip measures: the surface points' relative motion, or the centre lines' closest points'
SLIP = ("surface", "centreline")

Array = npt.NDArray[np.float64]


def resolve_normal(normal: str, friction: bool) -> str:
    """The contact normal that ``normal`` names: one of ``kinematics.NORMALS``, or "auto":
    "director" with friction, "frozen" without (frictionless beams lying on others have
    near-zero-energy modes, rolling around them, that only the frozen normal's stiffness holds).

    Raises ``ContactError`` for any other name.
    """
    if normal == "auto":
        return "director" if friction else "frozen"
    if normal not in NORMALS:
        raise ContactError(
            f"contact normal {normal!r} is unknown; choose auto, {', '.join(NORMALS)}"
        )
    return normal


def check_slip(slip: str) -> str:
    """``slip`` if it names one of ``SLIP``; raises ``ContactError`` otherwise."""
    if slip not in SLIP:
        raise ContactError(f"contact slip {slip!r} is unknown; choose {' or '.join(SLIP)}")
    return slip


class ContactGroup(PairGroup):
    """Small-sliding pairs of one kind sharing a stencil layout; a ``PairTerms`` for
    ``NonlinearProblem``.

    Args:
        stencils: (P, k) local dof blocks, ordered as ``stencil_nodes(normal, line)``.
        initial_positions: (P, k, 3) positions of the stencil nodes at t = 0, m.
        line: line pairs (projected normal) rather than crossings.
        radius_a, radius_b: wire radii (P,), m; normal0: (P, 3) initial normals a → b.
        normal_law: the pairs' normal law; friction_law: their friction law (None: frictionless).
        normal: the normal ("frozen", "neighbour", "director").
        tangent0: (P, 2, 3) initial unit tangents at a and b (``director`` only).
        index: (P,) pair ids, for reporting.
        initial_gap: (P,) gap at t = 0, m (default 0: the pairs touch).
        slip: the slip measure, one of ``SLIP`` ("centreline" needs ``tangent0``).
        offset: line pairs, "surface" slip: (P,) where b faces the centre line of a, m along
            a's tangent from node a (default 0: at node a). The gap, the distance of x_b from
            the tangent line of a, does not depend on it; the slip takes the surface point of
            a's section there as rigidly carried by node a, Δu_a + Δθ_a × (s t_a + r_a n).
    """

    def __init__(
        self,
        stencils,
        initial_positions,
        line: bool,
        radius_a,
        radius_b,
        normal0,
        normal_law: NormalLaw,
        *,
        friction_law: FrictionLaw | None,
        normal: str,
        tangent0=None,
        index=None,
        initial_gap=None,
        slip: str = "surface",
        offset=None,
    ):
        check_slip(slip)
        if slip == "centreline" and tangent0 is None:
            raise ValueError("the centre-line slip needs the pairs' initial tangents")
        super().__init__(stencils, normal_law, friction_law, normal0, index)
        n_pairs, k = self.stencils.shape
        if k != len(stencil_nodes(normal, line)):
            raise ValueError(
                f"{normal} normal needs stencils of {len(stencil_nodes(normal, line))}"
            )
        self.X = np.asarray(initial_positions, dtype=float)
        #: stencil dofs that the residual and tangent hold: (u, θ) of a and b, and the positions of
        #: the neighbour nodes (their rotations never enter)
        self.dofs = np.concatenate(
            [np.arange(12), (6 * np.arange(2, k)[:, None] + np.arange(3)).ravel()]
        )
        self.line = line
        self.normal_kind = normal
        self.r_a = np.asarray(radius_a, dtype=float)
        self.r_b = np.asarray(radius_b, dtype=float)
        n0 = self._n_old
        self.data: dict = {"g0": np.zeros(n_pairs), "n0": n0.copy()}
        X = self.X
        if not line and normal in ("neighbour", "director"):
            if normal == "neighbour":
                ca, cb = X[:, 3] - X[:, 2], X[:, 5] - X[:, 4]
            else:
                ca, cb = tangent0[:, 0], tangent0[:, 1]
            self.data["sign"] = np.sign(np.einsum("pi,pi->p", np.cross(ca, cb), n0))
            if np.any(self.data["sign"] == 0):
                raise ValueError("a crossing pair has parallel tangents; use a line pair")
        if normal == "director":
            self.data["t0"] = np.asarray(tangent0, dtype=float)
        self.slip = slip
        self._tangent0 = None if tangent0 is None else np.asarray(tangent0, dtype=float)
        self.offset = None
        if offset is not None and np.any(offset):
            if not line or slip != "surface" or tangent0 is None:
                raise ValueError("an offset is for line pairs with the surface slip and tangents")
            self.offset = np.asarray(offset, dtype=float)
        # g0: the initial value less the initial gap, so that g = initial_gap at t = 0
        zero = np.zeros_like(X)
        value = gap_derivatives(normal, line, X, zero, self.data).gap
        gap0 = np.zeros(n_pairs) if initial_gap is None else np.asarray(initial_gap, float)
        self.data["g0"] = value - gap0
        self._q_old = np.zeros((n_pairs, 12))  # (u_a, θ_a, u_b, θ_b) at the last converged step
        self._S: Array | None = None  # slip operator of the current step

    def slip_operator(self) -> Array:
        """S (P, 3, 12): Δg_T = S Δ(u_a, θ_a, u_b, θ_b), with the normal frozen over the step."""
        if self._S is None:
            n = self._n_old
            if self.slip == "surface":
                P_n = np.eye(3) - n[:, :, None] * n[:, None, :]
                N = skew(n)
                lever_a = self.r_a[:, None, None] * N
                if self.offset is not None:  # the facing point lies s along a's tangent
                    R = rotation_matrix(self._q_old[:, 3:6])
                    t_a = np.einsum("pij,pj->pi", R, self._tangent0[:, 0])
                    lever_a = lever_a + self.offset[:, None, None] * (P_n @ skew(t_a))
                self._S = np.concatenate([-P_n, lever_a, P_n, self.r_b[:, None, None] * N], axis=2)
            else:
                theta_a, theta_b = self._q_old[:, 3:6], self._q_old[:, 9:12]
                t = np.stack(
                    [
                        np.einsum("pij,pj->pi", rotation_matrix(theta_a), self._tangent0[:, 0]),
                        np.einsum("pij,pj->pi", rotation_matrix(theta_b), self._tangent0[:, 1]),
                    ],
                    axis=1,
                )
                self._S = centreline_slip_operator(
                    n,
                    t,
                    self.r_a + self.r_b,
                    tangent_map(theta_a),
                    tangent_map(theta_b),
                    self.line,
                )
        return self._S

    def _kinematics(self, W: Array, jacobian: bool) -> PairKinematics:
        x = self.X + W[..., :3]
        gd = gap_derivatives(
            self.normal_kind,
            self.line,
            x,
            W[..., 3:],
            self.data,
            hessian_where=(lambda g: g <= 0.0) if jacobian else None,
        )
        return PairKinematics(
            gd.gap,
            gd.normal,
            gd.gradient[:, self.dofs],
            lambda K, scale: gd.add_hessian(K, scale, self.dofs),
            lambda: (self.slip_operator(), W[:, :2].reshape(-1, 12) - self._q_old),
        )

    def _commit_kinematics(self, W: Array) -> None:
        self._q_old = W[:, :2].reshape(-1, 12).copy()
        self._S = None


def centreline_slip_operator(n, t, d, T_a, T_b, line: bool) -> Array:
    """The centre-line slip operator S (P, 3, 12) on (u_a, θ_a, u_b, θ_b) (module docstring).

    Args:
        n: (P, 3) unit normals a → b; t: (P, 2, 3) tangents of a and b at the step's start.
        d: (P,) distance of the centre lines, m; T_a, T_b: (P, 3, 3) δω = T δθ of a and b.
        line: line pairs (one closest-point condition) rather than crossings.
    """
    n_pairs = len(n)
    P_n = np.eye(3) - n[:, :, None] * n[:, None, :]
    if line:
        lever = d[:, None, None] * skew(n) @ T_a  # d n × δω_a
        return np.concatenate([-P_n, lever, P_n, np.zeros((n_pairs, 3, 3))], axis=2)
    e = np.einsum("pij,pkj->pki", P_n, t)  # the tangents in the tangent plane
    e /= np.linalg.norm(e, axis=2)[..., None]
    # rows r_i = (Δu_b − Δu_a)·e_i + d (e_i × n)·T δθ_i
    R = np.zeros((n_pairs, 2, 12))
    R[:, :, 0:3], R[:, :, 6:9] = -e, e
    lever = d[:, None, None] * np.cross(e, n[:, None, :])  # (P, 2, 3)
    R[:, 0, 3:6] = np.einsum("pi,pij->pj", lever[:, 0], T_a)
    R[:, 1, 9:12] = np.einsum("pi,pij->pj", lever[:, 1], T_b)
    # Δg_T = x e_1 + y e_2 with Δg_T·e_i = r_i: (x, y) = G⁻¹ r, G the Gram matrix of e_1, e_2
    c = np.einsum("pi,pi->p", e[:, 0], e[:, 1])
    if np.any(np.abs(c) > 1 - 1e-8):
        raise ContactError("a crossing pair has parallel tangents; use a line pair")
    G_inv = np.stack([np.stack([np.ones_like(c), -c], -1), np.stack([-c, np.ones_like(c)], -1)], -2)
    G_inv /= (1 - c**2)[:, None, None]
    return np.einsum("pki,pkl,plm->pim", e, G_inv, R)
