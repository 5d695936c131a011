"""Large-sliding beam-to-beam contact: the baseline the small-sliding element is compared with.

Every contact point is re-projected at every Newton iteration: the closest points between the
current centrelines of its two wires, searched over a window of segments around the initial pair
(``reach`` segments either side), so a pair moves from segment to segment as the wires slide.
Crossings take the closest points of two centrelines; line pairs (core | layer 1) project the
layer-1 node onto the core's centreline. The gap is their distance minus its initial value (so
g ≡ 0 at t = 0), the normal their direction.

Centrelines are C¹: on each segment the cubic Hermite curve through the two nodes with the nodal
tangents t = R(θ) t₀ (scaled by the initial segment length). The beams' own straight segments
would not do: every contact point starts on a node, where a polyline has a kink; the closest point
of two polylines then sits on the vertex, where the gap is not differentiable and both adjacent
segments claim the point lies on the other (measured: on Cardinal the pairs flip segments in the
first iterations and Newton diverges at 3 kN of tension). On Hermite curves the gap and its
gradient are continuous across nodes. Helices touch at nodes with the analytic tangents, so the
closest points start exactly there.

The same laws as the small-sliding element apply (the law objects of ``strand.contact.laws``,
through the shared ``PairGroup``), and the same slip measure: the relative motion of the two surface points
currently in contact since the last converged step (translations and rotations interpolated
linearly at the closest points, lever arms r n), in the plane normal to n frozen over the step.

Tangent: the normal part is exact. The closest-point parameters solve a small Newton problem per
pair; one more Newton step in complex arithmetic carries their derivatives, so the complex step of
the hand-written gradient gives the Hessian including ∂ξ/∂q. The friction part ignores the motion
of the contact point within a step (good enough for Newton; its quadratic rate is lost while
points slide).

The pattern reserves the whole window, so segment changes need no new non-zeros; a pair whose
closest point wants to leave its window raises an error naming it. Units: m, N.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from ..geometry import LINE, StrandGeometry
from .element import ContactSettings
from .group import PairGroup, PairKinematics
from .kinematics import _cross, _dot, _rotate, _rotation_coefficients, _tangent_map_transpose, skew
from .laws import FrictionLaw, NormalLaw
from .strand_pairs import pair_laws

__all__ = [
    "SlidingGroup",
    "sliding_groups",
    "sliding_windows",
    "hermite_point",
    "SlidingWindowError",
]

Array = npt.NDArray[np.float64]
_EPS = 1e-30


class SlidingWindowError(RuntimeError):
    """A contact point slid beyond the segments reserved for it."""


# -- Hermite centrelines -----------------------------------------------------------------------
def _hermite(xi):
    """Cubic Hermite basis (…, 4) at ξ and its first two derivatives: weights of (x₀, L t₀, x₁, L t₁)."""
    xi2 = xi * xi
    xi3 = xi2 * xi
    h = np.stack([2 * xi3 - 3 * xi2 + 1, xi3 - 2 * xi2 + xi, 3 * xi2 - 2 * xi3, xi3 - xi2], -1)
    dh = np.stack([6 * xi2 - 6 * xi, 3 * xi2 - 4 * xi + 1, 6 * xi - 6 * xi2, 3 * xi2 - 2 * xi], -1)
    d2h = np.stack([12 * xi - 6, 6 * xi - 4, 6 - 12 * xi, 6 * xi - 2], -1)
    return h, dh, d2h


def hermite_point(control, xi, derivatives: int = 0):
    """Point (and derivatives) of the Hermite segment with control (…, 4, 3) = (x₀, L t₀, x₁, L t₁)."""
    out = [_combine(b, control) for b in _hermite(xi)[: derivatives + 1]]
    return out if derivatives else out[0]


def _combine(weights, control):
    """Σ_k w_k c_k for weights (…, 4) and control (…, 4, 3), unrolled (a strided reduce is slow)."""
    return (
        weights[..., 0, None] * control[..., 0, :]
        + weights[..., 1, None] * control[..., 1, :]
        + weights[..., 2, None] * control[..., 2, :]
        + weights[..., 3, None] * control[..., 3, :]
    )


def _controls(y, tangents, length):
    """Control points of one segment from y (…, 12) = (x₀, θ₀, x₁, θ₁); also the rotated unit
    tangents and the rotation coefficients (for the gradient)."""
    coef = [_rotation_coefficients(y[..., 3:6]), _rotation_coefficients(y[..., 9:12])]
    t = [_rotate(y[..., 3:6], coef[0], tangents[..., 0, :]),
         _rotate(y[..., 9:12], coef[1], tangents[..., 1, :])]  # fmt: skip
    L = length[..., None]
    control = np.stack([y[..., 0:3], L * t[0], y[..., 6:9], L * t[1]], -2)
    return control, t, coef


def _closest_on_curves(ca, cb, xi, eta, free, iterations: int, tol: float):
    """Newton on r·a'(ξ) = 0, r·b'(η) = 0 with r = b(η) − a(ξ); only where ``free``; stops early
    once no parameter moves by more than ``tol``."""
    for _ in range(iterations):
        a, a1, a2 = hermite_point(ca, xi, 2)
        b, b1, b2 = hermite_point(cb, eta, 2)
        r = b - a
        f1, f2 = _dot(r, a1), _dot(r, b1)
        j11, j12 = _dot(r, a2) - _dot(a1, a1), _dot(a1, b1)
        j22 = _dot(r, b2) + _dot(b1, b1)
        det = j11 * j22 + j12 * j12  # j21 = −j12
        d_xi = np.where(free, (j22 * f1 - j12 * f2) / det, 0.0)
        d_eta = np.where(free, (j11 * f2 + j12 * f1) / det, 0.0)
        xi, eta = xi - d_xi, eta - d_eta
        if np.max(np.abs(d_xi) + np.abs(d_eta), initial=0.0) <= tol:
            break
    return xi, eta


def _closest_on_curve(ca, b, xi, free, iterations: int, tol: float):
    """Newton on (b − a(ξ))·a'(ξ) = 0; only where ``free``; stops early as above."""
    for _ in range(iterations):
        a, a1, a2 = hermite_point(ca, xi, 2)
        r = b - a
        d_xi = np.where(free, _dot(r, a1) / (_dot(r, a2) - _dot(a1, a1)), 0.0)
        xi = xi - d_xi
        if np.max(np.abs(d_xi), initial=0.0) <= tol:
            break
    return xi


def _side_gradient(h, length, n, t, coef, y, sign):
    """∂(sign·n·x(ξ))/∂(x₀, θ₀, x₁, θ₁) at fixed ξ: (…, 12)."""
    L = length[..., None]
    parts = []
    for node in (0, 1):
        parts.append(sign * h[..., 2 * node, None] * n)
        v = _cross(t[node], n)  # δ(L t) = L (T δθ) × t  ⇒  n·δ(L t) = L δθ·Tᵀ(t × n)
        parts.append(
            sign * h[..., 2 * node + 1, None] * L
            * _tangent_map_transpose(y[..., 6 * node + 3 : 6 * node + 6], coef[node], v)
        )  # fmt: skip
    return np.concatenate(parts, -1)


def _crossing_kernel(y, data, xi, eta, free, iterations, tol=0.0):
    """g + g₀ = |b(η) − a(ξ)| for y (…, 24) = (x, θ) of a₀, a₁, b₀, b₁ at the closest points.

    Returns the distance, ∂/∂y (envelope: exact where the parameters are the closest points),
    the normal and (ξ, η)."""
    ca, ta, coef_a = _controls(y[..., :12], data["tangents"][..., 0:2, :], data["length"][..., 0])
    cb, tb, coef_b = _controls(y[..., 12:], data["tangents"][..., 2:4, :], data["length"][..., 1])
    xi, eta = _closest_on_curves(ca, cb, xi, eta, free, iterations, tol)
    ha, hb = _hermite(xi)[0], _hermite(eta)[0]
    r = _combine(hb, cb) - _combine(ha, ca)
    dist = np.sqrt(_dot(r, r))
    n = r / dist[..., None]
    grad = np.concatenate(
        [
            _side_gradient(ha, data["length"][..., 0], n, ta, coef_a, y[..., :12], -1.0),
            _side_gradient(hb, data["length"][..., 1], n, tb, coef_b, y[..., 12:], 1.0),
        ],
        -1,
    )
    return dist, grad, n, xi, eta


def _line_kernel(y, data, xi, eta, free, iterations, tol=0.0):
    """g + g₀ = |x_b − a(ξ)| for y (…, 15) = (x, θ) of a₀, a₁ and x_b, ξ the projection of x_b."""
    ca, ta, coef_a = _controls(y[..., :12], data["tangents"][..., 0:2, :], data["length"][..., 0])
    b = y[..., 12:15]
    xi = _closest_on_curve(ca, b, xi, free, iterations, tol)
    ha = _hermite(xi)[0]
    r = b - _combine(ha, ca)
    dist = np.sqrt(_dot(r, r))
    n = r / dist[..., None]
    grad = np.concatenate(
        [_side_gradient(ha, data["length"][..., 0], n, ta, coef_a, y[..., :12], -1.0), n], -1
    )
    return dist, grad, n, xi, eta


class SlidingGroup(PairGroup):
    """Large-sliding pairs of one kind; a ``PairTerms`` for ``NewtonSolver``.

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

    def __init__(self, stencils, initial_positions, na: int, line: bool, start,
                 normal_law: NormalLaw, friction_law: FrictionLaw | None, index=None,
                 wire_end=None, radius_a=0.0, radius_b=0.0, start_parameters=None, *,
                 tangents):  # fmt: skip
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
            np.zeros((n_pairs, 2)) if start_parameters is None
            else np.asarray(start_parameters, float).copy()
        )  # fmt: skip
        self.g0 = np.zeros(n_pairs)  # so that the initial distances come out whole
        distance, _, n_initial, _ = self._kinematics_of(
            self.X, np.zeros_like(self.X), hessian=False
        )
        # pairs touching at t = 0 start closed: a femtometre below their initial distance, more
        # than the round-off of the iterated projection (~1e-19 m), so g = 0 reads as g ≤ 0
        self.g0 = distance + self.TOUCH
        self._n_old = n_initial.copy()
        self.state.normal = n_initial.copy()
        self._w_old = np.zeros((n_pairs, k, 6))  # window unknowns at the last converged step
        self._committed = (self.segment.copy(), self.parameter.copy())

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
        kernel = _line_kernel if self.line else _crossing_kernel
        return kernel(y, data, xi, eta, free, iterations, tol)

    def _project(self, x, rot, rows):
        """Closest points of the pairs ``rows`` on their current segments (Newton to tolerance)."""
        _, y, data = self._active(x, rot, rows)
        xi, eta = self._kernel(
            y, data, self.parameter[rows, 0], self.parameter[rows, 1], True,
            self.PROJECTION_ITERATIONS, self.PROJECTION_TOLERANCE,
        )[3:]  # fmt: skip
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
        free = ~held
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

    def _commit_kinematics(self, W: Array) -> None:
        self._w_old = W.copy()
        self._committed = (self.segment.copy(), self.parameter.copy())

    def _rollback_kinematics(self) -> None:
        self.segment, self.parameter = (a.copy() for a in self._committed)


def _windows(geometry: StrandGeometry, nodes: npt.NDArray[np.intp], reach: float):
    """Per node: the first and last node of the shortest stretch of its wire that reaches
    ``reach`` (m of initial arc length) either side of it, or the wire's end."""
    offsets, wire = geometry.wire_offsets, geometry.point_wire
    step = np.linalg.norm(np.diff(geometry.points, axis=0), axis=1)
    step[offsets[1:-1] - 1] = 0.0  # no length between the last node of a wire and the next
    arc = np.concatenate([[0.0], np.cumsum(step)])
    # one increasing key over all wires: wire w's arc length shifted past every earlier wire's
    key = arc + wire * (arc[-1] + 2 * reach + 1.0)
    lo, hi = offsets[wire[nodes]], offsets[wire[nodes] + 1] - 1
    first = np.maximum(np.searchsorted(key, key[nodes] - reach, side="right") - 1, lo)
    last = np.minimum(np.searchsorted(key, key[nodes] + reach, side="left"), hi)
    return first, last, np.column_stack([first == lo, last == hi])


def sliding_windows(geometry: StrandGeometry, reach: float):
    """The node windows of the large-sliding pairs: per group of equal window sizes, the pairs
    ``sel``, the window of each, (P, na + nb) input nodes (wire a's first, from its first node),
    and ``na``. Each pair's window holds the segments of its wires within ``reach`` (m) of its
    initial nodes; a line pair's node b (a point against the core) is its own window."""
    pairs = geometry.pairs
    a_first, a_last, a_ends = _windows(geometry, pairs.a, reach)
    b_first, b_last, b_ends = _windows(geometry, pairs.b, reach)
    is_line = pairs.kind == LINE
    b_first, b_last = np.where(is_line, pairs.b, b_first), np.where(is_line, pairs.b, b_last)
    b_ends[is_line] = True
    sizes = np.column_stack([a_last - a_first + 1, b_last - b_first + 1])
    out = []
    for kind in (0, LINE):
        of_kind = pairs.kind == kind
        for na, nb in np.unique(sizes[of_kind], axis=0):
            sel = np.flatnonzero(of_kind & (sizes[:, 0] == na) & (sizes[:, 1] == nb))
            nodes = np.concatenate(
                [a_first[sel, None] + np.arange(na), b_first[sel, None] + np.arange(nb)], axis=1
            )
            ends = np.column_stack([a_ends[sel], b_ends[sel]])
            out.append((sel, nodes, int(na), ends))
    return out


def sliding_groups(
    geometry: StrandGeometry,
    input_to_block: npt.NDArray[np.int32],
    settings: ContactSettings,
    n_owned: int | None = None,
) -> list[SlidingGroup]:
    """Large-sliding versions of the geometry's pairs (windows: ``sliding_windows``), with the
    laws of ``settings``; pairs with windows of equal sizes share a group. With ``n_owned`` (a
    distributed mesh: the number of dof blocks this rank owns), only the pairs whose window
    starts on an owned node (``partition.owned_rows``)."""
    from ..partition import owned_rows

    pairs = geometry.pairs
    tangents = geometry.tangents()
    groups = []
    for sel, nodes, na, ends in sliding_windows(geometry, settings.reach):
        if n_owned is not None:
            rows = owned_rows(input_to_block[nodes], n_owned, "contact pairs")
            sel, nodes, ends = sel[rows], nodes[rows], ends[rows]
        if not len(sel):
            continue
        line = bool(pairs.kind[sel[0]] == LINE)
        # the closest points start at the pair's nodes: ξ = 0 on the segment they begin
        # (1 on the last segment when the node ends the window)
        a_pos, b_pos = pairs.a[sel] - nodes[:, 0], pairs.b[sel] - nodes[:, na]
        nb = nodes.shape[1] - na
        start_a = np.minimum(a_pos, na - 2)
        start_b = np.zeros(len(sel), dtype=np.intp) if line else np.minimum(b_pos, nb - 2)
        start_parameters = np.column_stack([a_pos - start_a, b_pos - start_b]).astype(float)
        pair_tangents = np.stack([tangents[pairs.a[sel]], tangents[pairs.b[sel]]], axis=1)
        normal_law, friction_law = pair_laws(geometry, sel, settings, pair_tangents)
        groups.append(
            SlidingGroup(input_to_block[nodes], geometry.points[nodes], na, line,
                         np.column_stack([start_a, start_b]), normal_law, friction_law,
                         index=sel, wire_end=ends,
                         radius_a=pairs.radius_a[sel], radius_b=pairs.radius_b[sel],
                         start_parameters=start_parameters, tangents=tangents[nodes])
        )  # fmt: skip
    return groups
