"""Large-sliding beam-to-beam contact: the baseline the small-sliding element is compared with.

Every contact point is re-projected at every Newton iteration: the closest points between the
current centreline polylines of its two wires, searched over a window of segments around the
initial pair (``reach`` segments either side), so a pair moves from segment to segment as the
wires slide. Crossings use segment-to-segment closest points; line pairs (core | layer 1) project
the layer-1 node onto the core's polyline. The gap is the distance of the closest points minus its
initial value (so g ≡ 0 at t = 0), the normal their direction. The same laws as the small-sliding
element apply (penalty, Coulomb radial return with K_T = μP₀/g_lim), and the same slip measure:
the relative motion of the two surface points currently in contact since the last converged step
(translations and rotations interpolated at the closest points, lever arms r n), in the plane
normal to n frozen over the step.

Tangent: the normal part is exact — the closest-point parameters come from the closed-form
projection, complex-analytic, so the complex step of the hand-written gradient gives the Hessian
including ∂ξ/∂q. The friction part ignores the motion of the contact point within a step
(good enough for Newton; its quadratic rate is lost while points slide).

The pattern reserves the whole window, so segment changes need no new
non-zeros; a pair whose closest point wants to leave its window raises an error naming it.
Units: m, N.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from ..geometry import LINE, StrandGeometry
from .element import ContactState, friction_terms, tangential_part
from .kinematics import _dot, skew
from .laws import normal_force

__all__ = ["SlidingGroup", "sliding_groups", "closest_parameters", "SlidingWindowError"]

Array = npt.NDArray[np.float64]
_EPS = 1e-30


class SlidingWindowError(RuntimeError):
    """A contact point slid beyond the segments reserved for it."""


def closest_parameters(p0, p1, q0, q1):
    """Parameters (ξ, η) of the closest points of the lines p0 + ξ(p1 − p0), q0 + η(q1 − q0).

    Closed form (complex-analytic). Nearly parallel lines are the caller's business.
    """
    u, v, w = p1 - p0, q1 - q0, p0 - q0
    a, b, c, d, e = _dot(u, u), _dot(u, v), _dot(v, v), _dot(u, w), _dot(v, w)
    den = a * c - b * b
    return (b * e - c * d) / den, (a * e - b * d) / den


def _clamped_segment_parameters(p0, p1, q0, q1):
    """Closest points of segments (real arrays, broadcast): clamped parameters and distance."""
    u, v, w = p1 - p0, q1 - q0, p0 - q0
    a, b, c, d, e = _dot(u, u), _dot(u, v), _dot(v, v), _dot(u, w), _dot(v, w)
    den = np.maximum(a * c - b * b, 1e-30 * a * c)
    xi = np.clip((b * e - c * d) / den, 0.0, 1.0)
    eta = np.clip((b * xi + e) / c, 0.0, 1.0)
    xi = np.clip((b * eta - d) / a, 0.0, 1.0)
    diff = p0 + xi[..., None] * u - q0 - eta[..., None] * v
    return xi, eta, np.sqrt(_dot(diff, diff))


def _point_segment_parameter(p, q0, q1):
    v = q1 - q0
    return _dot(p - q0, v) / _dot(v, v)


def _crossing_gradient(y, free, fixed):
    """g = |x_b(η) − x_a(ξ)| for y = (a0, a1, b0, b1) (..., 12): value, ∂g/∂y (envelope), n."""
    a0, a1, b0, b1 = (y[..., 3 * i : 3 * i + 3] for i in range(4))
    xi, eta = closest_parameters(a0, a1, b0, b1)
    xi = np.where(free, xi, fixed[..., 0])
    eta = np.where(free, eta, fixed[..., 1])
    d = b0 + eta[..., None] * (b1 - b0) - a0 - xi[..., None] * (a1 - a0)
    dist = np.sqrt(_dot(d, d))
    n = d / dist[..., None]
    grad = np.concatenate(
        [
            -(1 - xi)[..., None] * n,
            -xi[..., None] * n,
            (1 - eta)[..., None] * n,
            eta[..., None] * n,
        ],
        -1,
    )
    return dist, grad, n, xi, eta


def _line_gradient(y, free, fixed):
    """g = |x_b − x_a(ξ)| for y = (a0, a1, b) (..., 9), ξ the projection of b on the segment."""
    a0, a1, b = y[..., 0:3], y[..., 3:6], y[..., 6:9]
    xi = np.where(free, _point_segment_parameter(b, a0, a1), fixed[..., 0])
    d = b - a0 - xi[..., None] * (a1 - a0)
    dist = np.sqrt(_dot(d, d))
    n = d / dist[..., None]
    grad = np.concatenate([-(1 - xi)[..., None] * n, -xi[..., None] * n, n], -1)
    return dist, grad, n, xi, np.ones_like(xi)


class SlidingGroup:
    """Large-sliding pairs of one kind; a ``PairTerms`` for ``NewtonSolver``.

    Args:
        stencils: (P, na + nb) local dof blocks: the window of wire a (na nodes, in order along
            the wire) then the window of wire b (nb nodes; nb = 1 for line pairs).
        initial_positions: (P, na + nb, 3), m.
        na: nodes of wire a per window; line: line pairs (node b against the core).
        start: (P, 2) the segment of each window holding the initial pair (a, b).
        stiffness, mu: per pair; g_lim: m; radius_a, radius_b: wire radii (lever arms of the
            surface points), m.
    """

    def __init__(self, stencils, initial_positions, na: int, line: bool, start, stiffness, mu,
                 g_lim: float, index=None, wire_end=None, radius_a=0.0, radius_b=0.0):  # fmt: skip
        self.stencils = np.ascontiguousarray(stencils, dtype=np.int32)
        n_pairs, k = self.stencils.shape
        self.X = np.asarray(initial_positions, dtype=float)
        self.na, self.nb, self.line = na, k - na, line
        self.r_a = np.broadcast_to(np.asarray(radius_a, float), (n_pairs,))
        self.r_b = np.broadcast_to(np.asarray(radius_b, float), (n_pairs,))
        self.k_n = np.asarray(stiffness, float)
        self.mu = np.asarray(mu, float)
        self.g_lim = g_lim
        self.index = np.arange(n_pairs) if index is None else np.asarray(index)
        self.segment = np.asarray(start, dtype=np.intp).copy()  # current (s_a, s_b)
        #: (P, 4): the window's first/last node of wire a, then of wire b, is the wire's end
        self.wire_end = (
            np.zeros((n_pairs, 4), dtype=bool) if wire_end is None else np.asarray(wire_end)
        )
        self.g0 = np.zeros(n_pairs)  # so that the initial distances come out whole
        self.g0, _, n_initial, _ = self._kinematics(self.X, hessian=False)
        self._t_old = np.zeros((n_pairs, 3))
        self._p_old = np.zeros(n_pairs)
        self._n_old = n_initial.copy()
        self._w_old = np.zeros((n_pairs, k, 6))  # window unknowns at the last converged step
        self._committed_segment = self.segment.copy()
        self.state = ContactState(
            np.zeros(n_pairs), np.zeros(n_pairs), np.zeros((n_pairs, 3)), self._n_old.copy(),
            np.zeros(n_pairs, dtype=bool),
        )  # fmt: skip

    def __len__(self) -> int:
        return len(self.stencils)

    # -- closest points ---------------------------------------------------------------------------
    #: a pair keeps its segment while its closest point stays within this fraction of a segment
    #: beyond the segment's ends: contact points start on nodes shared by two segments, and a
    #: strict choice would flip between them from one iteration to the next
    HYSTERESIS = 0.05

    def _search(self, x: Array) -> None:
        """Choose, per pair, the segment (pair) of its windows closest to each other, keeping the
        current one while its closest point lies within ``HYSTERESIS`` of it."""
        na, rows = self.na, np.arange(len(x))
        A0, A1 = x[:, : na - 1], x[:, 1:na]
        s_a, s_b = self.segment[:, 0], self.segment[:, 1]
        if self.line:
            b = x[:, na]
            xi_now = _point_segment_parameter(b, A0[rows, s_a], A1[rows, s_a])
            keep = np.abs(xi_now - 0.5) <= 0.5 + self.HYSTERESIS
            xi = np.clip(_point_segment_parameter(b[:, None], A0, A1), 0.0, 1.0)
            diff = b[:, None] - A0 - xi[..., None] * (A1 - A0)
            best = np.argmin(_dot(diff, diff), axis=1)
            self.segment[:, 0] = np.where(keep, s_a, best)
            return
        B0, B1 = x[:, na:-1], x[:, na + 1 :]
        xi_now, eta_now = closest_parameters(
            A0[rows, s_a], A1[rows, s_a], B0[rows, s_b], B1[rows, s_b]
        )
        keep = (np.abs(xi_now - 0.5) <= 0.5 + self.HYSTERESIS) & (
            np.abs(eta_now - 0.5) <= 0.5 + self.HYSTERESIS
        )
        _, _, dist = _clamped_segment_parameters(
            A0[:, :, None], A1[:, :, None], B0[:, None], B1[:, None]
        )
        flat = np.argmin(dist.reshape(len(x), -1), axis=1)
        best = np.column_stack(np.unravel_index(flat, dist.shape[1:]))
        self.segment = np.where(keep[:, None], self.segment, best)

    def _kinematics(self, x: Array, hessian: bool):
        self._search(x)
        rows = np.arange(len(x))
        s_a, s_b = self.segment[:, 0], self.segment[:, 1]
        nodes = [s_a, s_a + 1] + (
            [self.na + s_b] if self.line else [self.na + s_b, self.na + s_b + 1]
        )
        self._nodes = np.stack(nodes, axis=1)  # window positions of the active nodes
        y = x[rows[:, None], self._nodes].reshape(len(x), -1)
        kernel = _line_gradient if self.line else _crossing_gradient
        # closest points move with q (exact derivatives) unless they would leave the window: then
        # they are held at its end (and the pair is reported at commit)
        probe = kernel(y, np.ones(len(x), bool), np.zeros((len(x), 2)))
        xi, eta = probe[3].real, probe[4].real
        tol = self.HYSTERESIS + 1e-9
        lo_a, hi_a = (s_a == 0) & (xi < -tol), (s_a == self.na - 2) & (xi > 1 + tol)
        held = lo_a | hi_a
        out = (lo_a & ~self.wire_end[:, 0]) | (hi_a & ~self.wire_end[:, 1])
        if not self.line:
            lo_b, hi_b = (s_b == 0) & (eta < -tol), (s_b == self.nb - 2) & (eta > 1 + tol)
            held |= lo_b | hi_b
            out |= (lo_b & ~self.wire_end[:, 2]) | (hi_b & ~self.wire_end[:, 3])
        free = ~held  # held at a window's end: at a wire's end that is physics, else an error
        fixed = np.column_stack([np.clip(xi, 0, 1), np.clip(eta, 0, 1)])
        self._outside = out
        dist, grad, n, xi, eta = kernel(y, free, fixed)
        self._shape = np.column_stack(
            [1 - xi, xi] + ([np.ones_like(xi)] if self.line else [1 - eta, eta])
        )
        g = dist - self.g0
        H = None
        if hessian:
            sel = np.flatnonzero(g <= 0)
            m = y.shape[1]
            H = (sel, np.zeros((len(sel), m, m)))
            if len(sel):
                yc = y[sel, None, :] + 1j * _EPS * np.eye(m)
                _, gc, *_ = kernel(yc, free[sel, None], fixed[sel, None])
                H = (sel, np.imag(gc) / _EPS)
        return g, grad, n, H

    # -- PairTerms ----------------------------------------------------------------------------------
    def evaluate(self, w: Array, jacobian: bool = True):
        n_pairs, k = self.stencils.shape
        W = w[self.stencils]  # (P, k, 6)
        x = self.X + W[..., :3]
        g, grad, n, H = self._kinematics(x, jacobian)
        p, dp_dg = normal_force(g, self.k_n)
        # scatter the active nodes' translations into the window layout (6k: u, θ per node)
        cols = (6 * self._nodes[:, :, None] + np.arange(3)).reshape(n_pairs, -1)
        rows = np.arange(n_pairs)[:, None]
        G = np.zeros((n_pairs, 6 * k))
        G[rows, cols] = grad
        f = -p[:, None] * G
        K = None
        if jacobian:
            K = G[:, :, None] * G[:, None, :]
            K *= -dp_dg[:, None, None]
            sel, h = H
            if len(sel):
                c = cols[sel]
                K[sel[:, None, None], c[:, :, None], c[:, None, :]] -= p[sel, None, None] * h
        traction = np.zeros((n_pairs, 3))
        slipping = np.zeros(n_pairs, dtype=bool)
        if np.any(self.mu > 0):
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
            S = S.reshape(n_pairs, 3, 6 * k)
            f_t, K_t, traction, slipping = friction_terms(
                S, (W - self._w_old).reshape(n_pairs, -1), p, dp_dg[:, None] * G, self.mu,
                self._p_old, self._t_old, n0, self.g_lim, jacobian,
            )  # fmt: skip
            f += f_t
            if jacobian:
                K += K_t
        self.state = ContactState(g, p, traction, n, slipping)
        self._last_w = W
        return f, K

    def commit(self) -> None:
        if np.any(self._outside):
            bad = self.index[np.flatnonzero(self._outside)[:5]]
            raise SlidingWindowError(
                f"contact pairs {bad.tolist()} slid to the end of the segments reserved for them; "
                "increase the sliding reach"
            )
        n = self.state.normal
        self._t_old = tangential_part(self.state.traction, n)
        self._n_old = n.copy()
        self._p_old = self.state.force.copy()
        self._w_old = self._last_w.copy()
        self._committed_segment = self.segment.copy()

    def rollback(self) -> None:
        self.segment = self._committed_segment.copy()

    @property
    def committed_force(self) -> Array:
        return self._p_old


def sliding_groups(
    geometry: StrandGeometry,
    input_to_block: npt.NDArray[np.int32],
    k_point: float,
    k_line: float,
    g_lim: float,
    friction: bool = True,
    reach: int = 1,
) -> list[SlidingGroup]:
    """Large-sliding versions of the geometry's pairs, with windows of ``reach`` segments either
    side of each initial contact node."""
    pairs = geometry.pairs
    offsets, wire = geometry.wire_offsets, geometry.point_wire
    groups = []
    for kind in (0, LINE):
        sel = np.flatnonzero(pairs.kind == kind)
        if len(sel) == 0:
            continue
        line = kind == LINE

        def window(nodes, width):
            lo, hi = offsets[wire[nodes]], offsets[wire[nodes] + 1] - 1
            first = np.clip(nodes - reach, lo, hi - width + 1)
            ends = np.column_stack([first == lo, first + width - 1 == hi])
            return first[:, None] + np.arange(width), nodes - first, ends

        na = 2 * reach + 2
        a_nodes, a_pos, a_ends = window(pairs.a[sel], na)
        start_a = np.clip(a_pos - (a_pos == na - 1), 0, na - 2)  # segment starting at a
        if line:
            b_nodes, start_b = pairs.b[sel][:, None], np.zeros(len(sel), dtype=np.intp)
            b_ends = np.ones((len(sel), 2), dtype=bool)
        else:
            b_nodes, b_pos, b_ends = window(pairs.b[sel], na)
            start_b = np.clip(b_pos - (b_pos == na - 1), 0, na - 2)
        nodes = np.concatenate([a_nodes, b_nodes], axis=1)
        stiffness = k_line * pairs.tributary[sel] if line else np.full(len(sel), k_point)
        mu = pairs.friction[sel] if friction else np.zeros(len(sel))
        groups.append(
            SlidingGroup(input_to_block[nodes], geometry.points[nodes], na, line,
                         np.column_stack([start_a, start_b]), stiffness, mu, g_lim, index=sel,
                         wire_end=np.column_stack([a_ends, b_ends]),
                         radius_a=pairs.radius_a[sel], radius_b=pairs.radius_b[sel])
        )  # fmt: skip
    return groups
