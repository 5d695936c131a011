"""Small-sliding contact of a node against a point of a segment: beams lying side by side.

Two parallel beams meshed independently have no node facing a node. A ``SegmentGroup`` pairs node
a of one beam with the point b = (1 − ξ) b₀ + ξ b₁ of the other's segment (b₀, b₁) that faced it at
t = 0; ξ is fixed (small sliding). With d = x_b − x_a, two normals are available:

``neighbour`` (the default)
    the centre-to-centre direction across the neighbour's chord c = x_b₁ − x_b₀,
    n = P_c d/‖P_c d‖ with P_c = I − c⊗c/c·c, and the gap g = ‖P_c d‖ − g₀. A rigid motion of
    the pair, of any size, neither opens nor closes it.
``frozen``
    the initial normal n₀ and the linear gap g = n₀·(u_b − u_a) + g_init. A rigid rotation ω of
    the pair closes it by (r_a + r_b)(1 − cos ω⊥) ≈ (r_a + r_b)ω⊥²/2 (ω⊥: the rotation about
    axes across n₀): 1.5 µm at 0.03 rad for wires of 3.3 mm, of the order of their contact
    approach, and 0.1 mm at the 0.25 rad that the ends of the uniform bending test turn by.

g₀ is set so that g equals the given initial gap g_init at t = 0. The slip since the last
converged step is the relative motion of the two surface points (as in ``element.ContactGroup``),
with the normal n of the step's start,

    Δg_T = P_n [Δu_b − Δu_a + n × (r_a Δθ_a + r_b Δθ_b)],   θ_b = (1 − ξ) θ_b₀ + ξ θ_b₁,

so that a small rigid rotation of the pair does not make it slip (to first order). The normal
and friction laws are any of ``laws`` (e.g. ``HertzLineLaw`` over each pair's tributary length,
``Mindlin``). The stencil is [a, b₀, b₁]; residual and tangent hold all 18 dofs. Units: m, N, rad.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from .friction_laws import FrictionLaw
from .group import PairGroup, PairKinematics
from .kinematics import _projected_normal_gradient, skew
from .normal_laws import NormalLaw

__all__ = ["SEGMENT_NORMALS", "SegmentGroup"]

Array = npt.NDArray[np.float64]

#: the normals of a ``SegmentGroup`` (module docstring)
SEGMENT_NORMALS = ("neighbour", "frozen")


def _projected_gap(d: Array, c: Array) -> tuple[Array, Array, Array]:
    """‖P_c d‖ (P,), n (P, 3) and its gradient in z = (d, c) (P, 6); complex-analytic."""
    n, g_d, g_c = _projected_normal_gradient(d, c)
    value = np.einsum("pi,pi->p", d, n)
    return value, n, np.concatenate([g_d, g_c], axis=1)


def _projected_gap_hessian(d: Array, c: Array) -> Array:
    """∂²g/∂z² (P, 6, 6) of g = ‖P_c d‖ in z = (d, c), in closed form.

    With ℓ = ‖c‖, e = c/ℓ, α = d·c/ℓ², v = P_c d = d − αc, g = ‖v‖, n = v/g and R = I − e⊗e − n⊗n
    (the projection across both e and n), from ∂g/∂d = n, ∂g/∂c = −αn and ∂n/∂v = (I − n⊗n)/g:

        ∂²g/∂d² = R/g,   ∂²g/∂d∂c = −(α/g) R − e⊗n/ℓ,
        ∂²g/∂c² = (α²/g) R + (α/ℓ)(n⊗e + e⊗n) − (g/ℓ²) n⊗n.
    """
    length = np.sqrt(np.einsum("pi,pi->p", c, c))
    e = c / length[:, None]
    alpha = np.einsum("pi,pi->p", d, e) / length
    v = d - (alpha * length)[:, None] * e
    g = np.sqrt(np.einsum("pi,pi->p", v, v))
    n = v / g[:, None]
    ee = e[:, :, None] * e[:, None, :]
    nn = n[:, :, None] * n[:, None, :]
    en = e[:, :, None] * n[:, None, :]
    R_g = (np.eye(3) - ee - nn) / g[:, None, None]
    a, a_l = alpha[:, None, None], (alpha / length)[:, None, None]
    H = np.empty((len(d), 6, 6))
    H[:, :3, :3] = R_g
    H[:, :3, 3:] = -a * R_g - en / length[:, None, None]
    H[:, 3:, :3] = H[:, :3, 3:].transpose(0, 2, 1)
    H[:, 3:, 3:] = a**2 * R_g + a_l * (en + en.transpose(0, 2, 1))
    H[:, 3:, 3:] -= (g / length**2)[:, None, None] * nn
    return H


def _z_map(xi: Array) -> Array:
    """(P, 6, 9): z = (d, c) from the translations (x_a, x_b₀, x_b₁) of each pair,
    d = (1 − ξ) x_b₀ + ξ x_b₁ − x_a and c = x_b₁ − x_b₀."""
    eye = np.eye(3)
    A = np.zeros((len(xi), 6, 9))
    A[:, :3, 0:3] = -eye
    A[:, :3, 3:6] = (1 - xi)[:, None, None] * eye
    A[:, :3, 6:9] = xi[:, None, None] * eye
    A[:, 3:, 3:6] = -eye
    A[:, 3:, 6:9] = eye
    return A


class SegmentGroup(PairGroup):
    """Node-to-segment pairs; a ``PairTerms`` for the Newton solver.

    Args:
        stencils: (P, 3) local dof blocks [a, b₀, b₁].
        weights: (P,) ξ ∈ [0, 1], the point of segment (b₀, b₁) facing a.
        radius_a, radius_b: (P,) beam radii, m.
        normal0: (P, 3) normals from a towards b (normalised here).
        normal_law, friction_law: the pairs' laws (friction None: frictionless).
        initial_gap: (P,) gap at t = 0, m (default 0: touching).
        index: (P,) pair ids, for reporting.
        normal: one of ``SEGMENT_NORMALS`` (module docstring).
        initial_positions: (P, 3, 3) positions of a, b₀, b₁ at t = 0, m (``neighbour`` only).
    """

    def __init__(
        self,
        stencils,
        weights,
        radius_a,
        radius_b,
        normal0,
        normal_law: NormalLaw,
        *,
        friction_law: FrictionLaw | None,
        initial_gap=None,
        index=None,
        normal: str = "neighbour",
        initial_positions=None,
    ):
        if normal not in SEGMENT_NORMALS:
            raise ValueError(
                f"segment pairs: unknown normal {normal!r}; choose {' or '.join(SEGMENT_NORMALS)}"
            )
        if normal == "neighbour" and initial_positions is None:
            raise ValueError("the neighbour normal needs the pairs' initial positions")
        n0 = np.asarray(normal0, dtype=float)
        n0 = n0 / np.linalg.norm(n0, axis=1)[:, None]
        super().__init__(stencils, normal_law, friction_law, n0, index)
        n_pairs = len(self.stencils)
        if self.stencils.shape[1] != 3:
            raise ValueError("segment pairs need stencils [a, b0, b1]")
        xi = np.asarray(weights, dtype=float).reshape(n_pairs)
        if np.any((xi < 0) | (xi > 1)):
            raise ValueError("segment weights must lie in [0, 1]")
        self.normal_kind = normal
        self.n0 = n0
        #: (P, 3): the weights of a, b₀, b₁ in x_b − x_a
        self.c = np.column_stack([-np.ones(n_pairs), 1 - xi, xi])
        self.r_a = np.asarray(radius_a, dtype=float).reshape(n_pairs)
        self.r_b = np.asarray(radius_b, dtype=float).reshape(n_pairs)
        #: the gap at t = 0
        self.initial_gap = (
            np.zeros(n_pairs) if initial_gap is None else np.asarray(initial_gap, float)
        )
        self._lever = np.column_stack([self.r_a, (1 - xi) * self.r_b, xi * self.r_b])
        if normal == "neighbour":
            self.X = np.asarray(initial_positions, dtype=float).reshape(n_pairs, 3, 3)
            self._A = _z_map(xi)
            value = _projected_gap(*self._z(self.X))[0]
            #: ‖P_c d‖ at t = 0 less the initial gap: g = ‖P_c d‖ − g₀
            self.g0 = value - self.initial_gap
        else:
            # ∂g/∂q: c_k n₀ on the translations of node k, nothing on the rotations
            G = np.zeros((n_pairs, 3, 6))
            G[:, :, :3] = self.c[:, :, None] * n0[:, None, :]
            self._gradient = G.reshape(n_pairs, 18)
        self._S: Array | None = None  # slip operator of the current step
        self._q_old = np.zeros((n_pairs, 18))

    def _z(self, x: Array) -> tuple[Array, Array]:
        """d and c (P, 3) from the positions x (P, 3, 3) of a, b₀, b₁."""
        z = np.einsum("pij,pj->pi", self._A, x.reshape(len(x), 9))
        return z[:, :3], z[:, 3:]

    def slip_operator(self) -> Array:
        """S (P, 3, 18): Δg_T = S Δq, with the normal of the step's start."""
        if self._S is None:
            n = self._n_old
            P_n = np.eye(3) - n[:, :, None] * n[:, None, :]
            S = np.zeros((len(n), 3, 3, 6))
            S[:, :, :, :3] = self.c[:, None, :, None] * P_n[:, :, None, :]
            S[:, :, :, 3:] = self._lever[:, None, :, None] * skew(n)[:, :, None, :]
            self._S = S.reshape(len(n), 3, 18)
        return self._S

    def _kinematics(self, W: Array, jacobian: bool) -> PairKinematics:
        q = W.reshape(len(W), 18)
        slip = lambda: (self.slip_operator(), q - self._q_old)  # noqa: E731
        if self.normal_kind == "frozen":
            gap = np.einsum("pk,pki,pi->p", self.c, W[..., :3], self.n0) + self.initial_gap
            return PairKinematics(gap, self.n0, self._gradient, lambda K, scale: None, slip)
        x = self.X + W[..., :3]
        d, c = self._z(x)
        value, n, grad_z = _projected_gap(d, c)
        A, translations = self._A, np.r_[0:3, 6:9, 12:15]
        gradient = np.zeros((len(W), 18))
        gradient[:, translations] = np.einsum("pzy,pz->py", A, grad_z)

        def add_hessian(K: Array, scale: Array) -> None:
            # Aᵀ (∂²g/∂z²) A on the translations, for the pairs that carry a force (scale ≠ 0):
            # the open ones add nothing
            s = np.flatnonzero(scale)
            A_s = A[s]
            H_y = A_s.transpose(0, 2, 1) @ (_projected_gap_hessian(d[s], c[s]) @ A_s)
            K[np.ix_(s, translations, translations)] += scale[s, None, None] * H_y

        return PairKinematics(value - self.g0, n, gradient, add_hessian, slip)

    def _commit_kinematics(self, W: Array) -> None:
        self._q_old = W.reshape(len(W), 18).copy()
        self._S = None
