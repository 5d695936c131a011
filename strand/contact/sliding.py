"""Large-sliding beam-to-beam contact: the baseline the small-sliding element is compared with.

Every contact point is re-projected at every Newton iteration: the closest points between the
current centrelines of its two beams, searched over a window of segments around the initial pair
(those within a sliding reach either side), so a pair moves from segment to segment as the beams
slide. Crossings take the closest points of two centrelines; line pairs (a strand's core | layer 1)
project node b onto beam a's centreline. The gap is their distance minus its initial value plus
the initial gap (g ≡ 0 at t = 0 for touching pairs), the normal their direction.

Centrelines are C¹ (``strand.contact.centreline``): on each segment the cubic Hermite curve through
the two nodes with the nodal tangents t = R(θ) t₀ (scaled by the initial segment length). The beams' own straight segments
would not do: every contact point starts on a node, where a polyline has a kink; the closest point
of two polylines then sits on the vertex, where the gap is not differentiable and both adjacent
segments claim the point lies on the other (measured: on Cardinal the pairs flip segments in the
first iterations and Newton diverges at 3 kN of tension). On Hermite curves the gap and its
gradient are continuous across nodes. Helices touch at nodes with the analytic tangents, so the
closest points start exactly there.

The same laws as the small-sliding element apply (the law objects of
``strand.contact.normal_laws`` and ``strand.contact.friction_laws``, through the shared
``PairGroup``), and the same two slip measures (``slip``):

* "surface": the relative motion of the two surface points currently in contact since the last
  converged step (translations and rotations interpolated linearly at the closest points, lever
  arms r n), in the plane normal to n frozen over the step;
* "centreline": the motion of the closest points' parameters, Δg_T = a'Δξ − b'Δη, linearised at
  the step's start (``strand.contact.sliding_slip``): blind to a wire's spin.

Tangent: the normal part is exact. The closest-point parameters solve a small Newton problem per
pair; one more Newton step in complex arithmetic carries their derivatives, so the complex step of
the hand-written gradient gives the Hessian including ∂ξ/∂q. The centre-line friction part is
exact too (its S is frozen over the step); the surface one ignores the motion of the contact point
within a step (good enough for Newton; its quadratic rate is lost while points slide).

The pattern reserves the whole window, so segment changes need no new non-zeros; a pair whose
closest point wants to leave its window raises an error naming it. ``strand.contact.windows``
builds the groups from node pairs and the beams' node chains. Units: m, N.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from .centreline import crossing_kernel, line_kernel
from .element import check_slip
from .friction_laws import FrictionLaw
from .group import PairGroup, PairKinematics
from .kinematics import skew
from .normal_laws import NormalLaw
from .sliding_slip import centreline_slip_operator

__all__ = ["SlidingGroup", "SlidingWindowError"]

Array = npt.NDArray[np.float64]
_EPS = 1e-30


class SlidingWindowError(RuntimeError):
    """A contact point slid beyond the segments reserved for it."""


class SlidingGroup(PairGroup):
    """Large-sliding pairs of one kind; a ``PairTerms`` for ``NonlinearProblem``.

    Args:
        stencils: (P, na + nb) local dof blocks: the window of wire a (na nodes, in order along
            the wire) then the window of wire b (nb nodes; nb = 1 for line pairs).
        initial_positions: (P, na + nb, 3), m.
        na: nodes of wire a per window; line: line pairs (node b against the core).
        start: (P, 2) the segment of each window holding the initial pair (a, b).
        normal_law, friction_law: the pairs' laws (friction None: frictionless); radius_a,
            radius_b: wire radii (lever arms of the surface points), m.
        start_parameters: (P, 2) the initial contact point's parameter on those segments
            (default 0: the segments' first nodes).
        tangents: (P, na + nb, 3) initial unit tangents of the centrelines at the window nodes
            (keyword; a line pair's node b needs none: any value).
        index: the pairs' numbers (for messages); wire_end: (P, 4) the window's first/last node of
            wire a, then of wire b, is the wire's end (a point may stop there).
        initial_gap: (P,) gap at t = 0, m (keyword; default 0: the pairs touch, and start closed).
        slip: the friction's slip measure, "surface" or "centreline" (keyword; module docstring).
    """

    #: a pair keeps its segment while its closest point stays within this fraction of a segment
    #: beyond the segment's ends (contact points start on nodes shared by two segments)
    HYSTERESIS = 0.05
    #: Newton iterations allowed to the closest-point problem, and its tolerance on ξ
    PROJECTION_ITERATIONS, PROJECTION_TOLERANCE = 25, 1e-13
    #: segments a contact point may walk per evaluation
    MAX_WALK = 8
    #: initial penetration (m) that keeps touching pairs closed despite round-off
    TOUCH = 1e-15

    def __init__(
        self,
        stencils,
        initial_positions,
        na: int,
        line: bool,
        start,
        normal_law: NormalLaw,
        *,
        friction_law: FrictionLaw | None,
        tangents,
        index=None,
        wire_end=None,
        radius_a=0.0,
        radius_b=0.0,
        start_parameters=None,
        initial_gap=None,
        slip: str = "surface",
    ):
        self.slip = check_slip(slip)
        n_pairs, k = np.shape(stencils)
        # the initial normal is known once the closest points are: set below
        super().__init__(stencils, normal_law, friction_law, np.zeros((n_pairs, 3)), index)
        self.X = np.asarray(initial_positions, dtype=float)
        self.na, self.nb, self.line = na, k - na, line
        self.r_a = np.broadcast_to(np.asarray(radius_a, float), (n_pairs,))
        self.r_b = np.broadcast_to(np.asarray(radius_b, float), (n_pairs,))
        self.wire_end = (
            np.zeros((n_pairs, 4), dtype=bool) if wire_end is None else np.asarray(wire_end)
        )
        self.T0 = np.asarray(tangents, dtype=float)
        self.segment_length = np.full((n_pairs, k), np.nan)  # initial length of window segments
        self.segment_length[:, : na - 1] = np.linalg.norm(np.diff(self.X[:, :na], axis=1), axis=2)
        if not line:
            self.segment_length[:, na:-1] = np.linalg.norm(np.diff(self.X[:, na:], axis=1), axis=2)
        self.segment = np.asarray(start, dtype=np.intp).copy()  # current (s_a, s_b)
        self.parameter = (
            np.zeros((n_pairs, 2))
            if start_parameters is None
            else np.asarray(start_parameters, float).copy()
        )
        self.g0 = np.zeros(n_pairs)  # so that the initial distances come out whole
        distance, _, n_initial, _ = self._kinematics_of(
            self.X, np.zeros_like(self.X), hessian=False
        )
        # g = initial_gap at t = 0; pairs touching at t = 0 start closed: a femtometre below their
        # initial distance, more than the round-off of the iterated projection (~1e-19 m), so
        # g = 0 reads as g ≤ 0
        gap0 = np.zeros(n_pairs) if initial_gap is None else np.asarray(initial_gap, float)
        self.g0 = distance - gap0 + np.where(gap0 == 0, self.TOUCH, 0.0)
        self._n_old = n_initial.copy()
        self.state.normal = n_initial.copy()
        self._w_old = np.zeros((n_pairs, k, 6))  # window unknowns at the last converged step
        self._committed = (self.segment.copy(), self.parameter.copy())
        self._S: Array | None = None  # the centre-line slip operator of the step
        self._commit_kinematics(self._w_old)

    # -- closest points ---------------------------------------------------------------------------
    def _active(self, x, rot, rows=None):
        """The active segments' nodes (window positions), unknowns y and kernel data."""
        rows = np.arange(len(self.stencils)) if rows is None else rows
        s_a, s_b = self.segment[rows, 0], self.segment[rows, 1]
        b_nodes = [self.na + s_b] if self.line else [self.na + s_b, self.na + s_b + 1]
        nodes = np.stack([s_a, s_a + 1, *b_nodes], axis=1)
        r = rows[:, None]
        xs, ts = x[r, nodes], rot[r, nodes]
        y = np.concatenate([xs, ts], axis=2).reshape(len(rows), -1)
        if self.line:
            y = y[:, :15]  # the core's two nodes (x, θ), then x_b
        length = np.stack(
            [self.segment_length[rows, s_a], self.segment_length[rows, b_nodes[0]]], 1
        )
        data = {"tangents": self.T0[r, nodes], "length": length}
        return nodes, y, data

    def _kernel(self, y, data, xi, eta, free, iterations, tol=0.0):
        kernel = line_kernel if self.line else crossing_kernel
        return kernel(y, data, xi, eta, free, iterations, tol)

    def _project(self, x, rot, rows):
        """Closest points of the pairs ``rows`` on their current segments (Newton to tolerance)."""
        _, y, data = self._active(x, rot, rows)
        xi, eta = self._kernel(
            y,
            data,
            self.parameter[rows, 0],
            self.parameter[rows, 1],
            True,
            self.PROJECTION_ITERATIONS,
            self.PROJECTION_TOLERANCE,
        )[3:]
        self.parameter[rows, 0], self.parameter[rows, 1] = xi, eta

    def _search(self, x, rot) -> None:
        """Walk every contact point to the segments holding its closest points: while a parameter
        lies more than ``HYSTERESIS`` beyond its segment, move to the neighbouring segment and
        start its projection from the overshoot carried over by length, up to the window's ends."""
        rows = np.arange(len(x))
        last = (self.na - 2, self.nb - 2)
        for _ in range(self.MAX_WALK):
            self._project(x, rot, rows)
            moved = np.zeros(len(rows), dtype=bool)
            for side in (0, 1) if not self.line else (0,):
                t = self.parameter[rows, side]
                s = self.segment[rows, side]
                step = np.where(t > 1 + self.HYSTERESIS, 1, 0) - np.where(
                    t < -self.HYSTERESIS, 1, 0
                )
                step = np.where((s + step < 0) | (s + step > last[side]), 0, step)
                # carry the overshoot over by length (segments may differ 1000-fold in length)
                offset = self.na * side
                ratio = (
                    self.segment_length[rows, offset + s]
                    / self.segment_length[rows, offset + np.clip(s + step, 0, last[side])]
                )
                carried = np.where(step > 0, (t - 1) * ratio, 1 + t * ratio)
                self.segment[rows, side] = s + step
                self.parameter[rows, side] = np.where(step != 0, np.clip(carried, 0, 1), t)
                moved |= step != 0
            rows = rows[moved]
            if len(rows) == 0:
                break

    def _kinematics_of(self, x: Array, rot: Array, hessian: bool):
        self._search(x, rot)
        nodes, y, data = self._active(x, rot)
        self._nodes = nodes
        xi, eta = self.parameter[:, 0], self.parameter[:, 1]
        # a closest point beyond the window's last segment is held at its end: at a wire's end
        # that is physics (the wire stops there). Elsewhere it is an error (reported at commit) if
        # the pair presses there or just beyond (within a segment, where the last segment's cubic
        # still extends the wire); open pairs whose closest points wander off are harmless
        tol = self.HYSTERESIS + 1e-9
        s_a, s_b = self.segment[:, 0], self.segment[:, 1]
        lo_a, hi_a = (s_a == 0) & (xi < -tol), (s_a == self.na - 2) & (xi > 1 + tol)
        held = lo_a | hi_a
        out = (lo_a & ~self.wire_end[:, 0]) | (hi_a & ~self.wire_end[:, 1])
        if not self.line:
            lo_b, hi_b = (s_b == 0) & (eta < -tol), (s_b == self.nb - 2) & (eta > 1 + tol)
            held |= lo_b | hi_b
            out |= (lo_b & ~self.wire_end[:, 2]) | (hi_b & ~self.wire_end[:, 3])
        beyond = np.zeros(len(x), dtype=bool)
        near = np.flatnonzero(out & (np.abs(xi - 0.5) <= 1.5) & (np.abs(eta - 0.5) <= 1.5))
        if len(near):
            sub = {key: v[near] for key, v in data.items()}
            dist = self._kernel(y[near], sub, xi[near], eta[near], False, 0)[0]
            beyond[near] = dist <= self.g0[near]
        xi, eta = np.where(held, np.clip(xi, 0, 1), xi), np.where(held, np.clip(eta, 0, 1), eta)
        self.parameter[:, 0], self.parameter[:, 1] = xi, eta  # next projection starts inside
        self._free = free = ~held
        dist, grad, n, xi, eta = self._kernel(y, data, xi, eta, free, 0)
        self._shape = np.column_stack(
            [1 - xi, xi] + ([np.ones_like(xi)] if self.line else [1 - eta, eta])
        )
        g = dist - self.g0
        self._outside = out & ((g <= 0) | beyond)
        H = None
        if hessian:
            sel = np.flatnonzero(g <= 0)
            m = y.shape[1]
            H = (sel, np.zeros((len(sel), m, m)))
            if len(sel):
                # one Newton step of the projection in complex arithmetic from the converged
                # parameters carries ∂(ξ, η)/∂y exactly: the complex step then differentiates the
                # gradient along the closest points
                yc = y[sel, None, :] + 1j * _EPS * np.eye(m)
                sub = {key: v[sel, None] for key, v in data.items()}
                gc = self._kernel(
                    yc, sub, xi[sel, None] + 0j, eta[sel, None] + 0j, free[sel, None], 1
                )[1]
                H = (sel, np.imag(gc) / _EPS)
        return g, grad, n, H

    # -- PairTerms ----------------------------------------------------------------------------------
    def _kinematics(self, W: Array, jacobian: bool) -> PairKinematics:
        n_pairs, k = self.stencils.shape
        x = self.X + W[..., :3]
        g, grad, n, H = self._kinematics_of(x, W[..., 3:], jacobian)
        # scatter the active nodes' unknowns (u, θ per node; u only for a line pair's node b) into
        # the window layout (6k: u, θ per node)
        cols = (6 * self._nodes[:, :, None] + np.arange(6)).reshape(n_pairs, -1)[:, : grad.shape[1]]
        rows = np.arange(n_pairs)[:, None]
        G = np.zeros((n_pairs, 6 * k))
        G[rows, cols] = grad

        def add_hessian(K, scale):
            sel, h = H
            if len(sel):
                c = cols[sel]
                K[sel[:, None, None], c[:, :, None], c[:, None, :]] += scale[sel, None, None] * h

        def slip():
            if self.slip == "centreline":
                return self.slip_operator(), (W - self._w_old).reshape(n_pairs, -1)
            # slip of the surface points in contact since the last converged step, as in the
            # small-sliding element: P_n[Δu_b − r_b Δθ_b×n − Δu_a − r_a Δθ_a×n], interpolated
            # with the current closest-point weights; n and the plane frozen over the step
            n0 = self._n_old
            P_n = np.eye(3) - n0[:, :, None] * n0[:, None, :]
            lever = skew(n0)  # −Δθ×(r n) = r (n×) Δθ
            side = np.r_[-1.0, -1.0, 1.0] if self.line else np.r_[-1.0, -1.0, 1.0, 1.0]
            radius = np.where(side < 0, self.r_a[:, None], self.r_b[:, None])  # (P, active)
            S = np.zeros((n_pairs, 3, k, 6))
            for j in range(self._nodes.shape[1]):
                node = self._nodes[:, j]
                weight = self._shape[:, j]
                S[rows[:, 0], :, node, 0:3] = (side[j] * weight)[:, None, None] * P_n
                S[rows[:, 0], :, node, 3:6] = (weight * radius[:, j])[:, None, None] * lever
            return S.reshape(n_pairs, 3, 6 * k), (W - self._w_old).reshape(n_pairs, -1)

        return PairKinematics(g, n, G, add_hessian, slip)

    def commit(self) -> None:
        if np.any(self._outside):
            bad = self.index[np.flatnonzero(self._outside)[:5]]
            raise SlidingWindowError(
                f"contact pairs {bad.tolist()} press at the end of the segments reserved for "
                "them: they slid further than the sliding reach; increase contact reach"
            )
        super().commit()

    def _kinematics_history(self) -> dict[str, Array]:
        return {"segment": self._committed[0], "parameter": self._committed[1]}

    def _restore_kinematics_history(self, arrays: dict[str, Array]) -> None:
        self.segment = np.array(arrays["segment"], dtype=self.segment.dtype)
        self.parameter = np.array(arrays["parameter"], dtype=float)

    def slip_operator(self) -> Array:
        """The centre-line slip operator of the step, S (P, 3, 6k) on the window's unknowns:
        Δg_T = S Δw since the last converged step (``strand.contact.sliding_slip``)."""
        if self._S is None:
            raise ValueError('the slip operator is that of slip = "centreline"')
        return self._S

    def _commit_kinematics(self, W: Array) -> None:
        self._w_old = W.copy()
        if self.slip == "centreline":
            self._S = self._centreline_operator(W)
        self._committed = (self.segment.copy(), self.parameter.copy())

    def _centreline_operator(self, W: Array) -> Array:
        """S (P, 3, 6k) of the centre-line slip at the converged window unknowns W: at its
        closest points, re-projected (a restored state has no evaluation yet)."""
        n_pairs, k = self.stencils.shape
        x, rot = self.X + W[..., :3], W[..., 3:]
        self._kinematics_of(x, rot, hessian=False)
        _, y, data = self._active(x, rot)
        S = centreline_slip_operator(
            line_kernel if self.line else crossing_kernel,
            y,
            data,
            self.parameter[:, 0],
            self.parameter[:, 1],
            self._free,
            self.line,
        )
        cols = (6 * self._nodes[:, :, None] + np.arange(6)).reshape(n_pairs, -1)[:, : y.shape[1]]
        out = np.zeros((n_pairs, 3, 6 * k))
        out[np.arange(n_pairs)[:, None], :, cols] = S.transpose(0, 2, 1)
        return out

    def _rollback_kinematics(self) -> None:
        self.segment, self.parameter = (a.copy() for a in self._committed)
