"""Small-sliding contact of a node against a point of a segment: beams lying side by side.

Two parallel beams meshed independently have no node facing a node. A ``SegmentGroup`` pairs node
a of one beam with the point b = (1 − ξ) b₀ + ξ b₁ of the other's segment (b₀, b₁) that faced it at
t = 0; ξ is fixed (small sliding). With the normal n frozen at its initial value (the beams lie side
by side: their normal barely turns under small rotations of the pair), the gap is linear,

    g = n·(x_b − x_a) − g₀ = n·(u_b − u_a) + g_init,      x_b = (1 − ξ) x_b₀ + ξ x_b₁,

g₀ set so that g equals the given initial gap g_init at t = 0, and the slip since the last converged step
is the relative motion of the two surface points (as in ``element.ContactGroup``),

    Δg_T = P_n [Δu_b − Δu_a + n × (r_a Δθ_a + r_b Δθ_b)],   θ_b = (1 − ξ) θ_b₀ + ξ θ_b₁,

so that a rigid rotation of the pair neither opens it nor makes it slip (to first order). The
normal and friction laws are any of ``laws`` (e.g. ``HertzLineLaw`` over each pair's tributary
length, ``Mindlin``). The stencil is [a, b₀, b₁]; residual and tangent hold all 18 dofs.
Units: m, N, rad.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from .group import PairGroup, PairKinematics
from .kinematics import skew
from .laws import FrictionLaw, NormalLaw

__all__ = ["SegmentGroup"]

Array = npt.NDArray[np.float64]


class SegmentGroup(PairGroup):
    """Node-to-segment pairs with a frozen normal; a ``PairTerms`` for the Newton solver.

    Args:
        stencils: (P, 3) local dof blocks [a, b₀, b₁].
        weights: (P,) ξ ∈ [0, 1], the point of segment (b₀, b₁) facing a.
        radius_a, radius_b: (P,) beam radii, m.
        normal0: (P, 3) normals from a towards b (normalised here).
        normal_law, friction_law: the pairs' laws (friction None: frictionless).
        initial_gap: (P,) gap at t = 0, m (default 0: touching).
        index: (P,) pair ids, for reporting.
    """

    def __init__(
        self,
        stencils,
        weights,
        radius_a,
        radius_b,
        normal0,
        normal_law: NormalLaw,
        friction_law: FrictionLaw | None,
        initial_gap=None,
        index=None,
    ):
        n0 = np.asarray(normal0, dtype=float)
        n0 = n0 / np.linalg.norm(n0, axis=1)[:, None]
        super().__init__(stencils, normal_law, friction_law, n0, index)
        n_pairs = len(self.stencils)
        if self.stencils.shape[1] != 3:
            raise ValueError("segment pairs need stencils [a, b0, b1]")
        xi = np.asarray(weights, dtype=float).reshape(n_pairs)
        if np.any((xi < 0) | (xi > 1)):
            raise ValueError("segment weights must lie in [0, 1]")
        self.n0 = n0
        #: (P, 3): the weights of a, b₀, b₁ in x_b − x_a
        self.c = np.column_stack([-np.ones(n_pairs), 1 - xi, xi])
        self.r_a = np.asarray(radius_a, dtype=float).reshape(n_pairs)
        self.r_b = np.asarray(radius_b, dtype=float).reshape(n_pairs)
        #: the gap at t = 0: g = n·(u_b − u_a) + initial gap, the geometry's n·(X_b − X_a) − g₀
        self.initial_gap = (
            np.zeros(n_pairs) if initial_gap is None else np.asarray(initial_gap, float)
        )
        # ∂g/∂q: c_k n on the translations of node k, nothing on the rotations
        G = np.zeros((n_pairs, 3, 6))
        G[:, :, :3] = self.c[:, :, None] * n0[:, None, :]
        self._gradient = G.reshape(n_pairs, 18)
        # the slip operator (P, 3, 18) with the frozen normal
        P_n = np.eye(3) - n0[:, :, None] * n0[:, None, :]
        N = skew(n0)
        lever = np.column_stack([self.r_a, (1 - xi) * self.r_b, xi * self.r_b])
        S = np.zeros((n_pairs, 3, 3, 6))
        S[:, :, :, :3] = self.c[:, None, :, None] * P_n[:, :, None, :]
        S[:, :, :, 3:] = lever[:, None, :, None] * N[:, :, None, :]
        self._S = S.reshape(n_pairs, 3, 18)
        self._q_old = np.zeros((n_pairs, 18))

    def _kinematics(self, W: Array, jacobian: bool) -> PairKinematics:
        gap = np.einsum("pk,pki,pi->p", self.c, W[..., :3], self.n0) + self.initial_gap
        q = W.reshape(len(W), 18)
        return PairKinematics(
            gap,
            self.n0,
            self._gradient,
            lambda K, scale: None,  # g is linear in the unknowns
            lambda: (self._S, q - self._q_old),
        )

    def _commit_kinematics(self, W: Array) -> None:
        self._q_old = W.reshape(len(W), 18).copy()
