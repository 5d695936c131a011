"""Finite rotations in UFL: the exponential map of the rotation vector.

A rotation is described by its rotation vector ``theta`` (axis times angle, rad). This module gives

* ``rotation_matrix(theta)``: Λ = exp(θ×) (Rodrigues' formula),
* ``curvature_matrix(theta)``: T(θ) such that the spin of a variation is δω = T(θ) δθ (spatial) and the
  material curvature of a rod is K = T(θ)ᵀ θ'.

The coefficients sin x/x, (1 − cos x)/x², (x − sin x)/x³ are 0/0 at θ = 0, where every computation
starts; below ``SMALL_ANGLE`` they are replaced by their Taylor series in x² = θ·θ, so that values and
all derivatives used by Newton are exact to round-off. The parametrisation is singular at ‖θ‖ = 2π
only (T is then rank-deficient), far beyond what a cable sees.
"""

from __future__ import annotations

import ufl

#: a quaternion as (scalar part, vector part)
Quaternion = tuple[ufl.core.expr.Expr, ufl.core.expr.Expr]

SMALL_ANGLE = 1e-2  # rad; the series below is accurate to ~1e-17 there

__all__ = [
    "skew",
    "axial",
    "rotation_matrix",
    "curvature_matrix",
    "rotation_coefficients",
    "quaternion",
    "quaternion_product",
    "quaternion_conjugate",
    "quaternion_matrix",
    "quaternion_log",
]


def skew(v: ufl.core.expr.Expr) -> ufl.core.expr.Expr:
    """The matrix v× such that (v×) a = v × a."""
    return ufl.as_matrix([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


def axial(A: ufl.core.expr.Expr) -> ufl.core.expr.Expr:
    """The axial vector of the skew part of A (inverse of ``skew`` on skew matrices)."""
    return ufl.as_vector([A[2, 1] - A[1, 2], A[0, 2] - A[2, 0], A[1, 0] - A[0, 1]]) / 2


def rotation_coefficients(theta: ufl.core.expr.Expr):
    """(a, b, c) = (sin x/x, (1 − cos x)/x², (x − sin x)/x³) with x = ‖θ‖, safe at θ = 0."""
    x2 = ufl.dot(theta, theta)
    x = ufl.sqrt(x2)
    small = ufl.lt(x2, SMALL_ANGLE**2)
    a = ufl.conditional(small, 1 - x2 / 6 + x2**2 / 120 - x2**3 / 5040, ufl.sin(x) / x)
    b = ufl.conditional(small, 0.5 - x2 / 24 + x2**2 / 720 - x2**3 / 40320, (1 - ufl.cos(x)) / x2)
    c = ufl.conditional(
        small, 1 / 6 - x2 / 120 + x2**2 / 5040 - x2**3 / 362880, (x - ufl.sin(x)) / (x2 * x)
    )
    return a, b, c


def rotation_matrix(theta: ufl.core.expr.Expr) -> ufl.core.expr.Expr:
    """Λ = exp(θ×) = I + a θ× + b θ×² (Rodrigues)."""
    a, b, _ = rotation_coefficients(theta)
    W = skew(theta)
    return ufl.Identity(3) + a * W + b * W * W


def curvature_matrix(theta: ufl.core.expr.Expr) -> ufl.core.expr.Expr:
    """T(θ) = I + b θ× + c θ×², the tangent map of the exponential: δω = T(θ) δθ."""
    _, b, c = rotation_coefficients(theta)
    W = skew(theta)
    return ufl.Identity(3) + b * W + c * W * W


# -- unit quaternions (q0, q) -------------------------------------------------------------------
# Used for objective strains: the geodesic midpoint of two rotations is normalize(q_a + q_b) and the
# relative rotation is conj(q_a) q_b, so no rotation-vector interpolation enters the strains.


def quaternion(theta: ufl.core.expr.Expr):
    """Unit quaternion (scalar, vector) of the rotation vector θ: (cos(x/2), sin(x/2) θ/x)."""
    x2 = ufl.dot(theta, theta)
    x = ufl.sqrt(x2)
    small = ufl.lt(x2, SMALL_ANGLE**2)
    q0 = ufl.conditional(small, 1 - x2 / 8 + x2**2 / 384 - x2**3 / 46080, ufl.cos(x / 2))
    s = ufl.conditional(small, 0.5 - x2 / 48 + x2**2 / 3840 - x2**3 / 645120, ufl.sin(x / 2) / x)
    return q0, s * theta


def quaternion_product(p: Quaternion, q: Quaternion) -> Quaternion:
    """Hamilton product p q of quaternions given as (scalar, vector)."""
    p0, pv = p
    q0, qv = q
    return p0 * q0 - ufl.dot(pv, qv), p0 * qv + q0 * pv + ufl.cross(pv, qv)


def quaternion_conjugate(q: Quaternion) -> Quaternion:
    return q[0], -q[1]


def quaternion_matrix(q: Quaternion) -> ufl.core.expr.Expr:
    """Rotation matrix of a quaternion q (normalised here, so q may be any non-zero multiple)."""
    q0, v = q
    n2 = q0**2 + ufl.dot(v, v)
    return ((q0**2 - ufl.dot(v, v)) * ufl.Identity(3) + 2 * ufl.outer(v, v) + 2 * q0 * skew(v)) / n2


def quaternion_log(q: Quaternion) -> ufl.core.expr.Expr:
    """Rotation vector of a unit quaternion with q0 > 0 (rotation angle below π)."""
    q0, v = q
    v2 = ufl.dot(v, v)
    r2 = v2 / q0**2
    small = ufl.lt(r2, SMALL_ANGLE**2)
    # atan(|v|/q0)/|v|, and its series in r² = |v|²/q0²
    f = ufl.conditional(
        small,
        (1 - r2 / 3 + r2**2 / 5 - r2**3 / 7 + r2**4 / 9) / q0,
        ufl.atan2(ufl.sqrt(v2), q0) / ufl.sqrt(v2),
    )
    return 2 * f * v
