"""The centre-line slip of large-sliding pairs: the motion of their closest points' parameters.

The seed paper's slip measure (Wriggers & Zavarise 1997), which ``strand.contact.element`` gives
the small-sliding pairs, on the C¹ centrelines of large sliding (``strand.contact.centreline``).
A crossing's closest points a(ξ), b(η) solve F = (r·a'(ξ), r·b'(η)) = 0, r = b(η) − a(ξ). As the
beams move, the contact point moves along a by a'Δξ and along b by b'Δη (a' = ∂a/∂ξ), and the
slip is the relative motion of the two centre lines there,

    Δg_T = a'(ξ) Δξ − b'(η) Δη.

A wire's spin about its own axis leaves its centreline, hence ξ and η, unchanged: it makes no
slip, and a wire rolling on another slips by its centre's motion. A line pair (node b against
beam a) has one parameter: the slip is a'Δξ along a and, around a, the motion of b's centre
against a's cross-section at the closest point (a's nodal rotations interpolated linearly),

    Δg_T = a'Δξ + c [c·(Δx_b − Δa|_ξ + r × Δφ_a)],      c = n × a'/‖a'‖,

as the small-sliding element's line pairs, P_n(Δu_b − Δu_a + d n × δω_a), at a node.

As in small sliding, the slip of a step is linear in the step's increments, Δg_T = S Δq, with S
the derivative at the step's start (the last converged state), frozen over the step: the friction
tangent Sᵀ(∂t/∂Δg_T)S is then exact. ∂(ξ, η)/∂q = −J⁻¹ ∂F/∂q (J = ∂F/∂(ξ, η)) is carried exactly
by one Newton step of the projection in complex arithmetic from the converged parameters (as
``strand.contact.sliding``'s Hessian). On straight wires S is the small-sliding element's
operator; on curved ones J adds the centrelines' curvature, r·a'' and r·b''. A step's slip
differs from the actual change of the parameters by terms of second order in the step's slide
(the contact point's path curving within the step). Units: m.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from .centreline import _combine, _controls, _hermite, _side_gradient
from .kinematics import _EPS, _cross, _dot, _tangent_map_transpose

__all__ = ["parameter_derivatives", "centreline_slip_operator"]

Array = npt.NDArray[np.float64]


def parameter_derivatives(kernel, y, data, xi, eta, free) -> tuple[Array, Array]:
    """∂ξ/∂y and ∂η/∂y (P, m) of the closest points (ξ, η) that ``kernel`` (``crossing_kernel``
    or ``line_kernel``) converged to on the active segments' unknowns y (P, m); zero where not
    ``free`` (a point held at its window's end)."""
    m = y.shape[1]
    yc = y[:, None, :] + 1j * _EPS * np.eye(m)
    sub = {key: v[:, None] for key, v in data.items()}
    xi_c, eta_c = kernel(yc, sub, xi[:, None] + 0j, eta[:, None] + 0j, free[:, None], 1)[3:]
    return np.imag(xi_c) / _EPS, np.imag(eta_c) / _EPS


def centreline_slip_operator(kernel, y, data, xi, eta, free, line: bool) -> Array:
    """S (P, 3, m): the centre-line slip Δg_T = S Δy (module docstring) on the active segments'
    unknowns y (P, m) = (x, θ) of a₀, a₁ then b₀, b₁ (a line pair: x_b alone), at the converged
    closest points (ξ, η); in the plane normal to the current normal."""
    dxi, deta = parameter_derivatives(kernel, y, data, xi, eta, free)
    length = data["length"]
    ca, ta, coef_a = _controls(y[:, :12], data["tangents"][:, 0:2], length[:, 0])
    ha, dha, _ = _hermite(xi)
    a1 = _combine(dha, ca)
    if line:
        r = y[:, 12:15] - _combine(ha, ca)
        n = r / np.sqrt(_dot(r, r))[:, None]
        c = _cross(n, a1)
        c /= np.sqrt(_dot(c, c))[:, None]
        around = np.zeros_like(y)  # ∂/∂y of c·(Δx_b − Δa|_ξ + r × Δφ_a)
        around[:, :12] = _side_gradient(ha, length[:, 0], c, ta, coef_a, y[:, :12], -1.0)
        c_r = _cross(c, r)  # c·(r × δφ) = δφ·(c × r)
        for node, weight in ((0, 1 - xi), (1, xi)):
            theta = slice(6 * node + 3, 6 * node + 6)
            around[:, theta] += weight[:, None] * _tangent_map_transpose(
                y[:, theta], coef_a[node], c_r
            )
        around[:, 12:15] = c
        S = a1[:, :, None] * dxi[:, None, :] + c[:, :, None] * around[:, None, :]
    else:
        cb, _, _ = _controls(y[:, 12:], data["tangents"][:, 2:4], length[:, 1])
        hb, dhb, _ = _hermite(eta)
        r = _combine(hb, cb) - _combine(ha, ca)
        n = r / np.sqrt(_dot(r, r))[:, None]
        S = a1[:, :, None] * dxi[:, None, :] - _combine(dhb, cb)[:, :, None] * deta[:, None, :]
    P_n = np.eye(3) - n[:, :, None] * n[:, None, :]  # no-op at exact closest points
    return P_n @ S
