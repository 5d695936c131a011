"""Gap functions of the contact pairs, with exact first and second derivatives (numpy, all pairs).

A pair joins node a (inner wire) and node b (outer wire). Its gap is

    g = (x_b − x_a)·n − g₀,        g₀ = the same expression at t = 0, so g ≡ 0 initially,

(the radii r_a + r_b are constant and sit inside g₀). Three normals are available:

``frozen``
    the initial radial normal n₀: g is linear in the translations. Robust, but it gives the
    circumferential modes of the strand a spurious stiffness and its gaps drift in bending.
``neighbour``
    depends on translations only. Crossings: n = s (c_a × c_b)/|c_a × c_b| with the chords
    c = x_{i+1} − x_{i−1} of each wire around the pair (stencil [a, b, a−, a+, b−, b+]).
    Line pairs (core | layer 1): n = P_c(x_b − x_a)/|P_c(x_b − x_a)|, the centre-to-centre
    direction orthogonal to the core chord c (stencil [a, b, a−, a+]); then g = |P_c d| − g₀.
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
    "tangent_map",
]

Array = npt.NDArray[np.float64]

NORMALS = ("frozen", "neighbour", "director")

#: complex step; any tiny value is exact since no difference is taken
_EPS = 1e-30
_SMALL_ANGLE2 = 1e-4


def _dot(a, b):
    return np.sum(a * b, axis=-1)


def _norm(a):
    return np.sqrt(_dot(a, a))


def _rotation_coefficients(theta):
    """(sin x/x, (1 − cos x)/x², (x − sin x)/x³), x = |θ|, complex-analytic and safe at 0."""
    x2 = _dot(theta, theta)
    small = np.real(x2) < _SMALL_ANGLE2
    xs2 = np.where(small, 1.0, x2)
    x = np.sqrt(xs2)
    a = np.where(small, 1 - x2 / 6 + x2**2 / 120 - x2**3 / 5040, np.sin(x) / x)
    b = np.where(small, 0.5 - x2 / 24 + x2**2 / 720 - x2**3 / 40320, (1 - np.cos(x)) / xs2)
    c = np.where(
        small, 1 / 6 - x2 / 120 + x2**2 / 5040 - x2**3 / 362880, (x - np.sin(x)) / (xs2 * x)
    )
    return a, b, c


def _skew(v):
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
    W = _skew(theta)
    return np.eye(3) + a[..., None, None] * W + b[..., None, None] * (W @ W)


def tangent_map(theta):
    """T(θ) = I + b θ× + c θ×²: the spatial spin of an increment, δω = T(θ) δθ."""
    _, b, c = _rotation_coefficients(theta)
    W = _skew(theta)
    return np.eye(3) + b[..., None, None] * W + c[..., None, None] * (W @ W)


def _cross_normal_gradient(d, ca, cb, s):
    """g = d·n with n = s(ca × cb)/|ca × cb|: returns n and ∂g/∂d, ∂g/∂ca, ∂g/∂cb."""
    m = s[..., None] * np.cross(ca, cb)
    mm = _norm(m)
    n = m / mm[..., None]
    w = (d - _dot(d, n)[..., None] * n) / mm[..., None]  # ∂g/∂m
    g_ca = s[..., None] * np.cross(cb, w)
    g_cb = s[..., None] * np.cross(w, ca)
    return n, n, g_ca, g_cb


def _projected_normal_gradient(d, c):
    """g = |P_c d| with P_c = I − c⊗c/c·c: returns n = P_c d/|P_c d|, ∂g/∂d and ∂g/∂c."""
    cc = _dot(c, c)
    dc = _dot(d, c)
    e = d - (dc / cc)[..., None] * c
    n = e / _norm(e)[..., None]
    return n, n, -(dc / cc)[..., None] * n


# -- the three normals: value g + g0 and gradient in the stencil unknowns y ----------------------
# y is split into 3-vectors: translation-only normals use current positions x per stencil node;
# ``director`` uses (x_a, θ_a, x_b, θ_b) and the initial tangents t0 (P, 2, 3).


def _frozen(y, data):
    xa, xb = y[..., 0:3], y[..., 3:6]
    n = np.broadcast_to(data["n0"], xa.shape)
    return _dot(xb - xa, n), np.concatenate([-n, n], -1), n


def _neighbour_point(y, data):
    xa, xb, am, ap, bm, bp = (y[..., 3 * i : 3 * i + 3] for i in range(6))
    d = xb - xa
    n, gd, g_ca, g_cb = _cross_normal_gradient(d, ap - am, bp - bm, data["sign"])
    return _dot(d, n), np.concatenate([-gd, gd, -g_ca, g_ca, -g_cb, g_cb], -1), n


def _neighbour_line(y, data):
    xa, xb, am, ap = (y[..., 3 * i : 3 * i + 3] for i in range(4))
    d = xb - xa
    n, gd, gc = _projected_normal_gradient(d, ap - am)
    return _dot(d, n), np.concatenate([-gd, gd, -gc, gc], -1), n


def _director_point(y, data):
    xa, ta, xb, tb = (y[..., 3 * i : 3 * i + 3] for i in range(4))
    t0 = data["t0"]
    ca = np.einsum("...ij,...j->...i", rotation_matrix(ta), t0[..., 0, :])
    cb = np.einsum("...ij,...j->...i", rotation_matrix(tb), t0[..., 1, :])
    d = xb - xa
    n, gd, g_ca, g_cb = _cross_normal_gradient(d, ca, cb, data["sign"])
    # δc = δω × c with δω = T(θ)δθ  ⇒  ∂g/∂θ = Tᵀ (c × ∂g/∂c)
    g_ta = np.einsum("...ji,...j->...i", tangent_map(ta), np.cross(ca, g_ca))
    g_tb = np.einsum("...ji,...j->...i", tangent_map(tb), np.cross(cb, g_cb))
    return _dot(d, n), np.concatenate([-gd, g_ta, gd, g_tb], -1), n


def _director_line(y, data):
    xa, ta, xb = y[..., 0:3], y[..., 3:6], y[..., 6:9]
    c = np.einsum("...ij,...j->...i", rotation_matrix(ta), data["t0"][..., 0, :])
    d = xb - xa
    n, gd, gc = _projected_normal_gradient(d, c)
    g_ta = np.einsum("...ji,...j->...i", tangent_map(ta), np.cross(c, gc))
    return _dot(d, n), np.concatenate([-gd, g_ta, gd, np.zeros_like(gd)], -1), n


_Kernel = Callable[[np.ndarray, dict], tuple[np.ndarray, np.ndarray, np.ndarray]]

#: (normal, line pair?) -> (kernel, stencil node roles, stencil dofs used by y)
_KERNELS: dict[tuple[str, bool], _Kernel] = {
    ("frozen", False): _frozen,
    ("frozen", True): _frozen,
    ("neighbour", False): _neighbour_point,
    ("neighbour", True): _neighbour_line,
    ("director", False): _director_point,
    ("director", True): _director_line,
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
            K[np.ix_(s, pos, pos)] += scale[s, None, None] * self.hessian

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
    kernel = _KERNELS[(normal, line)]
    n_pairs, k, _ = positions.shape
    if normal == "director":
        y = np.concatenate(
            [positions[:, 0], rotations[:, 0], positions[:, 1], rotations[:, 1]], axis=1
        )
    else:
        y = positions.reshape(n_pairs, 3 * k)
    value, grad_y, n = kernel(y, data)
    idx = _unknown_dofs(normal, k)
    gradient = np.zeros((n_pairs, 6 * k))
    gradient[:, idx] = grad_y
    gap = value - data["g0"]
    sel = np.zeros(0, dtype=np.intp)
    if hessian_where is not None and normal != "frozen":
        sel = np.flatnonzero(hessian_where(gap))
    m = y.shape[1]
    h = np.zeros((len(sel), m, m))
    if len(sel):
        yc = y[sel, None, :] + 1j * _EPS * np.eye(m)  # (S, m perturbations, m)
        sub = {key: (v[sel, None] if np.ndim(v) else v) for key, v in data.items() if key != "n0"}
        _, gc, _ = kernel(yc, sub)
        h = np.imag(gc).transpose(0, 2, 1) / _EPS  # h[s, i, j] = ∂²g/∂y_i∂y_j
    return GapDerivatives(gap, n, gradient, sel, idx, h)
