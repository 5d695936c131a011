"""C¹ centrelines of beams and the closest points between them: the kernels of large sliding.

On each segment a beam's centreline is the cubic Hermite curve through its two nodes with the
nodal tangents t = R(θ) t₀ (scaled by the initial segment length L), so the gap and its gradient
are continuous across nodes (a polyline has a kink at every node, where the closest point of two
polylines is not differentiable). The kernels take the unknowns y = (x, θ) of the active
segments' nodes and return the distance of the closest points (crossings: two curves; line
pairs: a point against a curve), its gradient ∂/∂y, the normal and the curve parameters; they
also run in complex arithmetic (the complex step of ``strand.contact.sliding``). Units: m.
"""

from __future__ import annotations

import numpy as np

from .kinematics import _cross, _dot, _rotate, _rotation_coefficients, _tangent_map_transpose

__all__ = ["hermite_point", "crossing_kernel", "line_kernel"]


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
    t = [
        _rotate(y[..., 3:6], coef[0], tangents[..., 0, :]),
        _rotate(y[..., 9:12], coef[1], tangents[..., 1, :]),
    ]
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
            sign
            * h[..., 2 * node + 1, None]
            * L
            * _tangent_map_transpose(y[..., 6 * node + 3 : 6 * node + 6], coef[node], v)
        )
    return np.concatenate(parts, -1)


def crossing_kernel(y, data, xi, eta, free, iterations, tol=0.0):
    """g + g₀ = ‖b(η) − a(ξ)‖ for y (…, 24) = (x, θ) of a₀, a₁, b₀, b₁ at the closest points.

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


def line_kernel(y, data, xi, eta, free, iterations, tol=0.0):
    """g + g₀ = ‖x_b − a(ξ)‖ for y (…, 15) = (x, θ) of a₀, a₁ and x_b, ξ the projection of x_b."""
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
