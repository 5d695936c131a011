"""Gap functions of the contact pairs, with exact first and second derivatives (numpy, all pairs).

A pair joins node a (inner wire) and node b (outer wire). Its gap is

    g = (x_b − x_a)·n − g₀,        g₀ = the same expression at t = 0, so g ≡ 0 initially,

(the radii r_a + r_b are constant and sit inside g₀). Three normals are available:

``frozen``
    the initial radial normal n₀: g is linear in the translations. Robust, but it gives the
    circumferential modes of the strand a spurious stiffness and its gaps drift in bending.
``neighbour``
    depends on translations only. Crossings: n = s (c_a × c_b)/‖c_a × c_b‖ with the chords
    c = x_{i+1} − x_{i−1} of each wire around the pair (stencil [a, b, a−, a+, b−, b+]).
    Line pairs (core | layer 1): n = P_c(x_b − x_a)/‖P_c(x_b − x_a)‖, the centre-to-centre
    direction orthogonal to the core chord c (stencil [a, b, a−, a+]); then g = ‖P_c d‖ − g₀.
``director``
    the seed paper's normal, from the nodal rotations: the tangents t = R(θ) t₀ replace the chords
    (stencil [a, b]); it couples the gap to the rotations.

Every normal function takes the stencil unknowns y (P, m), m = 3 per node for the translation-only
normals and (u_a, θ_a, u_b, θ_b) for ``director``, and returns ∂g/∂y written out by hand. The
hand-written gradients are complex-analytic (no abs, no conj: norms are sqrt(Σx²)), so the Hessian
follows exactly by the complex step, H[:, j] = Im ∇g(y + iεe_j)/ε, with no cancellation error.
Lengths in m.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = [
    "NORMALS",
    "GapDerivatives",
    "stencil_nodes",
    "gap_derivatives",
    "rotation_matrix",
    "skew",
    "tangent_map",
]

Array = npt.NDArray[np.float64]

NORMALS = ("frozen", "neighbour", "director")

#: complex step; any tiny value is exact since no difference is taken
_EPS = 1e-30
_SMALL_ANGLE2 = 0.09  # series below |θ| = 0.3 rad


def _dot(a, b):
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1] + a[..., 2] * b[..., 2]


def _norm(a):
    return np.sqrt(_dot(a, a))


def _series(x2, first: int):
    """Σ_k (−1)^k x^{2k}/(2k + first)!, by Horner, with as many terms as the largest x² needs for
    1e-17 (at most 9 terms: exact to round-off for x² < 0.09)."""
    biggest = float(np.max(np.abs(x2), initial=0.0))
    terms = 9
    while terms > 2 and biggest ** (terms - 1) / math.factorial(2 * terms - 2 + first) < 1e-17:
        terms -= 1
    out = np.zeros_like(x2)
    for k in range(terms - 1, -1, -1):
        out = out * (-x2) + 1.0 / math.factorial(2 * k + first)
    return out


def _rotation_coefficients(theta):
    """(sin x/x, (1 − cos x)/x², (x − sin x)/x³), x = ‖θ‖, complex-analytic and safe at 0."""
    x2 = _dot(theta, theta)
    small = np.real(x2) < _SMALL_ANGLE2
    x2_small = np.where(small, x2, 0.0)  # the series only where it is used (no overflow)
    coefficients = [_series(x2_small, k) for k in (1, 2, 3)]
    if not np.all(small):  # the closed forms, only where the series would be inexact
        xs2 = np.where(small, 1.0, x2)
        x = np.sqrt(xs2)
        exact = [np.sin(x) / x, (1 - np.cos(x)) / xs2, (x - np.sin(x)) / (xs2 * x)]
        coefficients = [np.where(small, s, e) for s, e in zip(coefficients, exact, strict=True)]
    return coefficients


def skew(v):
    """The matrix v× of the cross product with v (..., 3, 3)."""
    z = np.zeros_like(v[..., 0])
    return np.stack(
        [
            np.stack([z, -v[..., 2], v[..., 1]], -1),
            np.stack([v[..., 2], z, -v[..., 0]], -1),
            np.stack([-v[..., 1], v[..., 0], z], -1),
        ],
        -2,
    )


def rotation_matrix(theta):
    """R(θ) = I + a θ× + b θ×² for rotation vectors θ (..., 3), the beam's nodal rotation."""
    a, b, _ = _rotation_coefficients(theta)
    W = skew(theta)
    return np.eye(3) + a[..., None, None] * W + b[..., None, None] * (W @ W)


def tangent_map(theta):
    """T(θ) = I + b θ× + c θ×² (..., 3, 3): the spatial rotation increment δω = T(θ) δθ of an
    increment δθ of the rotation vector θ."""
    _, b, c = _rotation_coefficients(theta)
    W = skew(theta)
    return np.eye(3) + b[..., None, None] * W + c[..., None, None] * (W @ W)


def _cross(u, v):
    """u × v over the last axis (cheaper than np.cross for many small vectors)."""
    u0, u1, u2 = u[..., 0], u[..., 1], u[..., 2]
    v0, v1, v2 = v[..., 0], v[..., 1], v[..., 2]
    out = np.empty(np.broadcast_shapes(u.shape, v.shape), dtype=np.result_type(u, v))
    out[..., 0] = u1 * v2 - u2 * v1
    out[..., 1] = u2 * v0 - u0 * v2
    out[..., 2] = u0 * v1 - u1 * v0
    return out


def _rotate(theta, coefficients, v):
    """R(θ) v = v + a θ×v + b θ×(θ×v), without forming R (..., 3)."""
    a, b, _ = coefficients
    tv = _cross(theta, v)
    return v + a[..., None] * tv + b[..., None] * _cross(theta, tv)


def _tangent_map_transpose(theta, coefficients, v):
    """T(θ)ᵀ v = v − b θ×v + c θ×(θ×v) (T = I + b θ× + c θ×², θ×ᵀ = −θ×)."""
    _, b, c = coefficients
    tv = _cross(theta, v)
    return v - b[..., None] * tv + c[..., None] * _cross(theta, tv)


def _cross_normal_gradient(d, ca, cb, s):
    """g = d·n with n = s(ca × cb)/|ca × cb|: returns n and ∂g/∂d, ∂g/∂ca, ∂g/∂cb."""
    m = s[..., None] * _cross(ca, cb)
    mm = _norm(m)
    n = m / mm[..., None]
    w = (d - _dot(d, n)[..., None] * n) / mm[..., None]  # ∂g/∂m
    g_ca = s[..., None] * _cross(cb, w)
    g_cb = s[..., None] * _cross(w, ca)
    return n, n, g_ca, g_cb


def _projected_normal_gradient(d, c):
    """g = ‖P_c d‖ with P_c = I − c⊗c/c·c: returns n = P_c d/‖P_c d‖, ∂g/∂d and ∂g/∂c."""
    cc = _dot(c, c)
    dc = _dot(d, c)
    e = d - (dc / cc)[..., None] * c
    n = e / _norm(e)[..., None]
    return n, n, -(dc / cc)[..., None] * n


# -- the three normals: value g + g0 and gradient in reduced variables z = A y ------------------
# The stencil unknowns y (3-vectors: positions per node for translation-only normals, or
# (x_a, θ_a, x_b, θ_b) for ``director``) enter each gap only through a few differences z = A y
# (d = x_b − x_a, chords c = x_{i+1} − x_{i−1}, rotations θ). Kernels work on z: fewer complex
# steps, and ∇_y g = Aᵀ∇_z g, ∇²_y g = Aᵀ ∇²_z g A exactly.


def _frozen(z, data):
    n = np.broadcast_to(data["n0"], z.shape)
    return _dot(z, n), n, n


def _neighbour_point(z, data):
    d, ca, cb = z[..., 0:3], z[..., 3:6], z[..., 6:9]
    n, gd, g_ca, g_cb = _cross_normal_gradient(d, ca, cb, data["sign"])
    return _dot(d, n), np.concatenate([gd, g_ca, g_cb], -1), n


def _neighbour_line(z, data):
    d, c = z[..., 0:3], z[..., 3:6]
    n, gd, gc = _projected_normal_gradient(d, c)
    return _dot(d, n), np.concatenate([gd, gc], -1), n


def _director_point(z, data):
    d, ta, tb = z[..., 0:3], z[..., 3:6], z[..., 6:9]
    t0 = data["t0"]
    coef_a, coef_b = _rotation_coefficients(ta), _rotation_coefficients(tb)
    ca = _rotate(ta, coef_a, t0[..., 0, :])
    cb = _rotate(tb, coef_b, t0[..., 1, :])
    n, gd, g_ca, g_cb = _cross_normal_gradient(d, ca, cb, data["sign"])
    # δc = δω × c with δω = T(θ)δθ  ⇒  ∂g/∂θ = Tᵀ (c × ∂g/∂c)
    g_ta = _tangent_map_transpose(ta, coef_a, _cross(ca, g_ca))
    g_tb = _tangent_map_transpose(tb, coef_b, _cross(cb, g_cb))
    return _dot(d, n), np.concatenate([gd, g_ta, g_tb], -1), n


def _director_line(z, data):
    d, ta = z[..., 0:3], z[..., 3:6]
    coef = _rotation_coefficients(ta)
    c = _rotate(ta, coef, data["t0"][..., 0, :])
    n, gd, gc = _projected_normal_gradient(d, c)
    g_ta = _tangent_map_transpose(ta, coef, _cross(c, gc))
    return _dot(d, n), np.concatenate([gd, g_ta], -1), n


def _difference_map(rows: list[tuple[int, int]], n_blocks: int) -> npt.NDArray[np.float64]:
    """A (3·len(rows), 3·n_blocks): row block r is y[plus] − y[minus] (minus < 0: y[plus])."""
    A = np.zeros((3 * len(rows), 3 * n_blocks))
    eye = np.eye(3)
    for r, (plus, minus) in enumerate(rows):
        A[3 * r : 3 * r + 3, 3 * plus : 3 * plus + 3] += eye
        if minus >= 0:
            A[3 * r : 3 * r + 3, 3 * minus : 3 * minus + 3] -= eye
    return A


_Kernel = Callable[[np.ndarray, dict], tuple[np.ndarray, np.ndarray, np.ndarray]]


def _entry(kernel: _Kernel, A: npt.NDArray[np.float64]):
    """(kernel, A, zmap, zsign): every unknown y_i enters one z_j = zmap[i] with the sign
    zsign[i] (A has one ±1 per column, or none: sign 0), so A-products become gathers."""
    assert np.all((A != 0).sum(axis=0) <= 1)
    return kernel, A, np.abs(A).argmax(axis=0), A.max(axis=0) + A.min(axis=0)


#: (normal, line pair?) -> (kernel on z, the map A from y to z, and its gather form)
_KERNELS: dict[tuple[str, bool], tuple] = {
    # y = (x_a, x_b)
    ("frozen", False): _entry(_frozen, _difference_map([(1, 0)], 2)),
    ("frozen", True): _entry(_frozen, _difference_map([(1, 0)], 2)),
    # y = (x_a, x_b, x_a−, x_a+, x_b−, x_b+): z = (d, c_a, c_b)
    ("neighbour", False): _entry(_neighbour_point, _difference_map([(1, 0), (3, 2), (5, 4)], 6)),
    # y = (x_a, x_b, x_a−, x_a+): z = (d, c)
    ("neighbour", True): _entry(_neighbour_line, _difference_map([(1, 0), (3, 2)], 4)),
    # y = (x_a, θ_a, x_b, θ_b): z = (d, θ_a, θ_b) or (d, θ_a)
    ("director", False): _entry(_director_point, _difference_map([(2, 0), (1, -1), (3, -1)], 4)),
    ("director", True): _entry(_director_line, _difference_map([(2, 0), (1, -1)], 4)),
}


def stencil_nodes(normal: str, line: bool) -> tuple[str, ...]:
    """The nodes a pair's stencil holds, in order: a, b, then the neighbours its normal uses."""
    if normal == "neighbour":
        return ("a", "b", "a-", "a+") if line else ("a", "b", "a-", "a+", "b-", "b+")
    if normal in ("frozen", "director"):
        return ("a", "b")
    raise ValueError(f"unknown contact normal {normal!r}; choose one of {', '.join(NORMALS)}")


def _unknown_dofs(normal: str, k: int) -> npt.NDArray[np.intp]:
    """Positions of the kernel unknowns y within the stencil's 6k dofs."""
    if normal == "director":
        return np.arange(12)
    return (6 * np.arange(k)[:, None] + np.arange(3)).ravel()


@dataclass
class GapDerivatives:
    """Gaps g (P,) in m, current normals n (P, 3) and ∂g/∂q (P, 6k).

    q are the stencil's dofs (u, θ per node, in stencil order). The Hessian is kept compact: for
    the pairs ``hessian_pairs`` (S,), ∂²g/∂q_i∂q_j = ``hessian[s, a, b]`` with i, j =
    ``hessian_dofs[a], hessian_dofs[b]`` (all other second derivatives vanish).
    """

    gap: Array
    normal: Array
    gradient: Array
    hessian_pairs: npt.NDArray[np.intp]
    hessian_dofs: npt.NDArray[np.intp]
    hessian: Array

    def add_hessian(
        self, K: Array, scale: Array, layout: npt.NDArray[np.intp] | None = None
    ) -> None:
        """K[p] += scale[p] ∂²g/∂q² for every pair (in place); ``scale`` (P,).

        ``layout`` (sorted, m) names the stencil dofs that K's m rows hold (default: all 6k).
        """
        if len(self.hessian_pairs):
            s = self.hessian_pairs
            pos = (
                self.hessian_dofs if layout is None else np.searchsorted(layout, self.hessian_dofs)
            )
            contribution = scale[s, None, None] * self.hessian
            if len(pos) == K.shape[1]:  # the Hessian fills the whole block: no inner gather
                if len(s) == len(K):
                    K += contribution
                else:
                    K[s] += contribution
            else:
                K[np.ix_(s, pos, pos)] += contribution

    def full_hessian(self) -> Array:
        """∂²g/∂q² as a dense (P, 6k, 6k) array (for tests)."""
        K = np.zeros((*self.gradient.shape, self.gradient.shape[1]))
        self.add_hessian(K, np.ones(len(self.gap)))
        return K


def gap_derivatives(
    normal: str,
    line: bool,
    positions: Array,
    rotations: Array,
    data: dict,
    hessian_where: Callable[[Array], npt.NDArray[np.bool_]] | None = None,
) -> GapDerivatives:
    """Gaps and derivatives of all pairs of one kind.

    Args:
        normal: "frozen", "neighbour" or "director".
        line: the pairs are core | layer-1 line pairs (projected normal) rather than crossings.
        positions: current positions of the stencil nodes (P, k, 3), m.
        rotations: nodal rotation vectors of the stencil nodes (P, k, 3).
        data: per-pair constants: "g0" (P,), "n0" (P, 3) for ``frozen``, "sign" (P,) for crossing
            normals, "t0" (P, 2, 3) initial unit tangents at a and b for ``director``.
        hessian_where: selects, from the gaps, the pairs whose Hessian is needed (the closed
            ones: it enters the tangent multiplied by the normal force); None computes none.
    """
    kernel, A, zmap, zsign = _KERNELS[(normal, line)]
    n_pairs, k, _ = positions.shape
    if normal == "director":
        y = np.concatenate(
            [positions[:, 0], rotations[:, 0], positions[:, 1], rotations[:, 1]], axis=1
        )
    else:
        y = positions.reshape(n_pairs, 3 * k)
    z = y @ A.T
    value, grad_z, n = kernel(z, data)
    idx = _unknown_dofs(normal, k)
    gradient = np.zeros((n_pairs, 6 * k))
    gradient[:, idx] = grad_z[:, zmap] * zsign
    gap = value - data["g0"]
    sel = np.zeros(0, dtype=np.intp)
    if hessian_where is not None and normal != "frozen":
        sel = np.flatnonzero(hessian_where(gap))
    m = y.shape[1]
    h = np.zeros((len(sel), m, m))
    if len(sel):
        mz = z.shape[1]
        zc = z[sel, None, :] + 1j * _EPS * np.eye(mz)  # (S, mz perturbations, mz)
        sub = {key: (v[sel, None] if np.ndim(v) else v) for key, v in data.items() if key != "n0"}
        _, gc, _ = kernel(zc, sub)
        h_z = np.imag(gc) / _EPS  # h_z[s, j, i] = ∂²g/∂z_j∂z_i (symmetric)
        h = h_z[:, zmap][:, :, zmap] * np.outer(zsign, zsign)  # ∂²g/∂y² = Aᵀ h_z A
    return GapDerivatives(gap, n, gradient, sel, idx, h)
