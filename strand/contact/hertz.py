"""Contact mechanics of touching wires (Hertz, Mindlin), for contact compliances from first principles.

Physics only (numpy, arrays over pairs). Units: m, N, Pa, rad. Johnson, *Contact Mechanics* (1985),
§4.2 (Hertz, elliptical contact), §5.6 (line contact), §7.2 (Mindlin).

Crossed cylinders of radii R₁, R₂ whose axes cross at β touch over an ellipse. The gap between them
is Ax² + By² with A + B = ½(1/R₁ + 1/R₂) and B − A = ½(1/R₁² + 1/R₂² + 2cos2β/(R₁R₂))^{1/2}. The
Hertz load–approach relation P = c δ^{3/2} uses the Hamrock–Brewe (1983) fits of the elliptic
integrals, with R_x = 1/(2A) ≥ R_y = 1/(2B), α_r = R_x/R_y, 1/R = 1/R_x + 1/R_y:

    k = α_r^{2/π},  ℰ = 1 + (π/2 − 1)/α_r,  ℱ = π/2 + (π/2 − 1) ln α_r,
    δ = ℱ [9/(2ℰR) (P/(π k E′))²]^{1/3},  E′ = 2E*,  1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂,

so c = π k E′ (2ℰR/9)^{1/2} / ℱ^{3/2} (exact for a sphere on a flat; a few % otherwise). The
contact ellipse has the semi-axes a = (6k²ℰPR/(πE′))^{1/3} along the direction of R_x and
b = (6ℰPR/(πkE′))^{1/3} across it, and the peak pressure p₀ = 3P/(2πab). Mindlin's
initial tangential stiffness of a contact area of radius a is k_T = 8a/[(2 − ν₁)/G₁ + (2 − ν₂)/G₂]
against the normal k_N = dP/dδ = 2aE*: their ratio depends on the materials alone.

``hertz_mindlin`` builds the law objects of elastic wires from these (``HertzPointLaw``,
``HertzLineLaw`` of ``strand.contact.normal_laws``, ``Mindlin`` of
``strand.contact.friction_laws``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from .friction_laws import FrictionLaw, Mindlin
from .microslip import MindlinDeresiewicz
from .normal_laws import HertzLineLaw, HertzPointLaw, NormalLaw

__all__ = [
    "crossed_cylinders",
    "point_coefficient",
    "compliance",
    "mindlin_ratio",
    "contact_ellipse",
    "line_contact",
    "hertz_mindlin",
]

Array = npt.NDArray[np.float64]


def compliance(E, nu) -> Array:
    """C = (1 − ν²)/E (1/Pa), one body's share of 1/E*."""
    return (1 - np.asarray(nu, float) ** 2) / np.asarray(E, float)


def crossed_cylinders(r1, r2, beta) -> tuple[Array, Array]:
    """Principal relative radii (R_x, R_y), R_x ≥ R_y, of cylinders r1, r2 (m) crossing at beta (rad)."""
    r1, r2, beta = (np.asarray(v, float) for v in (r1, r2, beta))
    s = 0.5 * (1 / r1 + 1 / r2)
    d = 0.5 * np.sqrt(1 / r1**2 + 1 / r2**2 + 2 * np.cos(2 * beta) / (r1 * r2))
    a, b = (s - d) / 2, (s + d) / 2
    return 1 / (2 * a), 1 / (2 * b)


@dataclass(frozen=True)
class _EllipticalContact:
    """Hamrock–Brewe quantities of crossed cylinders: ellipticity k, elliptic integrals ℰ, ℱ,
    curvature sum radius R (m) and E′ = 2E* (Pa)."""

    k: Array
    ell_e: Array
    ell_f: Array
    r: Array
    e_prime: Array


def _elliptical(r1, r2, beta, E1, nu1, E2, nu2) -> _EllipticalContact:
    rx, ry = crossed_cylinders(r1, r2, beta)
    alpha = rx / ry
    return _EllipticalContact(
        alpha ** (2 / np.pi),
        1 + (np.pi / 2 - 1) / alpha,
        np.pi / 2 + (np.pi / 2 - 1) * np.log(alpha),
        1 / (1 / rx + 1 / ry),
        2 / (compliance(E1, nu1) + compliance(E2, nu2)),
    )


def point_coefficient(r1, r2, beta, E1, nu1, E2, nu2) -> Array:
    """c (N/m^{3/2}) of P = c δ^{3/2} for crossed cylinders (Hertz, Hamrock–Brewe fits)."""
    h = _elliptical(r1, r2, beta, E1, nu1, E2, nu2)
    return np.pi * h.k * h.e_prime * np.sqrt(2 * h.ell_e * h.r / 9) / h.ell_f**1.5


def mindlin_ratio(E1, nu1, E2, nu2) -> Array:
    """k_T/k_N = 4[(1 − ν₁²)/E₁ + (1 − ν₂²)/E₂]/[(2 − ν₁)/G₁ + (2 − ν₂)/G₂], G = E/(2(1 + ν)).

    2(1 − ν)/(2 − ν) for like materials (0.82 at ν = 0.3)."""
    E1, nu1, E2, nu2 = (np.asarray(v, float) for v in (E1, nu1, E2, nu2))
    g1, g2 = E1 / (2 * (1 + nu1)), E2 / (2 * (1 + nu2))
    return 4 * (compliance(E1, nu1) + compliance(E2, nu2)) / ((2 - nu1) / g1 + (2 - nu2) / g2)


def contact_ellipse(r1, r2, beta, E1, nu1, E2, nu2, *, force) -> tuple[Array, Array, Array]:
    """Hertz contact of crossed cylinders under a normal ``force`` P (N): the semi-axes a ≥ b (m)
    and the peak pressure p₀ = 3P/(2πab) (Pa) (Hamrock–Brewe fits; exact for a sphere on a
    flat). Zero where P ≤ 0."""
    h = _elliptical(r1, r2, beta, E1, nu1, E2, nu2)
    P = np.maximum(np.asarray(force, float), 0.0)
    base = 6 * h.ell_e * P * h.r / (np.pi * h.e_prime)
    a, b = np.cbrt(base * h.k**2), np.cbrt(base / h.k)
    p0 = np.divide(3 * P, 2 * np.pi * a * b, out=np.zeros_like(P), where=P > 0)
    return a, b, p0


def line_contact(r1, r2, E1, nu1, E2, nu2, line_load) -> tuple[Array, Array]:
    """Hertz contact of parallel cylinders under a ``line_load`` q (N/m) (Johnson 1985, §4.3):
    half-width b = (4qR/(πE*))^{1/2} (m), 1/R = 1/R₁ + 1/R₂, and peak pressure p₀ = 2q/(πb) (Pa).
    Zero where q ≤ 0."""
    r1, r2 = np.asarray(r1, float), np.asarray(r2, float)
    q = np.maximum(np.asarray(line_load, float), 0.0)
    r = r1 * r2 / (r1 + r2)
    b = np.sqrt(4 * q * r * (compliance(E1, nu1) + compliance(E2, nu2)) / np.pi)
    p0 = np.divide(2 * q, np.pi * b, out=np.zeros_like(q), where=q > 0)
    return b, p0


def hertz_mindlin(
    line: bool,
    radius_a: npt.ArrayLike,
    radius_b: npt.ArrayLike,
    crossing_angle: npt.ArrayLike,
    tributary: npt.ArrayLike,
    *,
    E_a: npt.ArrayLike,
    nu_a: npt.ArrayLike,
    E_b: npt.ArrayLike,
    nu_b: npt.ArrayLike,
    mu: npt.ArrayLike | None = None,
    microslip: bool = False,
) -> tuple[NormalLaw, FrictionLaw | None]:
    """The laws of elastic wires in contact, from their radii (m) and moduli (Pa) alone.

    Crossings: ``HertzPointLaw`` of cylinders crossing at ``crossing_angle`` (rad); line pairs:
    ``HertzLineLaw`` over their ``tributary`` lengths (m). Friction: ``Mindlin`` with Coulomb
    coefficients ``mu`` (None: frictionless), or with ``microslip`` Mindlin–Deresiewicz's curve
    up to gross slip (``strand.contact.microslip.MindlinDeresiewicz``). Values are per pair (P,)
    or one for all.
    """
    r_a = np.asarray(radius_a, float)
    P = len(r_a)
    E_a, nu_a, E_b, nu_b, r_b, angle, length = (
        np.broadcast_to(np.asarray(v, float), (P,))
        for v in (E_a, nu_a, E_b, nu_b, radius_b, crossing_angle, tributary)
    )
    if line:
        law: NormalLaw = HertzLineLaw(
            r_a, r_b, compliance(E_a, nu_a), compliance(E_b, nu_b), length
        )
    else:
        law = HertzPointLaw(point_coefficient(r_a, r_b, angle, E_a, nu_a, E_b, nu_b))
    if mu is None:
        return law, None
    kind = MindlinDeresiewicz if microslip else Mindlin
    return law, kind(
        np.broadcast_to(np.asarray(mu, float), (P,)).copy(), mindlin_ratio(E_a, nu_a, E_b, nu_b)
    )
