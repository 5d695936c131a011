"""Surface stresses of round wires from their section forces (beam theory; physics only, numpy).

A wire's section at a step carries the axial force N, the bending moments M₁, M₂ about the unit
vectors e₁, e₂ of the section's plane and the torque T about its tangent t (e₂ = t × e₁). At the
surface point of angle ψ from e₁ towards e₂, at radius r (Navier, Saint-Venant torsion):

    σ(ψ) = N/A + (r/I)(M₁ sin ψ − M₂ cos ψ),     τ = T r/J,

with A = πd²/4, I = πd⁴/64, J = πd⁴/32 of the wire's diameter d. strand's frame puts e₁ along the
outward radius of the strand (ψ = 0: the side facing the next layer out, 180°: the side facing the
core); for the core, e₁ is the set-up's load direction. Units: N, N m, m, Pa, rad.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

__all__ = ["section_frames", "section_components", "surface_stress", "shear_stress"]

Array = npt.NDArray[np.float64]


def section_frames(tangent: Array, radial: Array, fallback=(1.0, 0.0, 0.0)) -> tuple[Array, Array]:
    """Unit vectors e₁ (``radial`` less its part along ``tangent``) and e₂ = t × e₁, (n, 3)
    each; where ``radial`` is along t or zero (the core), e₁ comes from ``fallback``."""
    t = tangent / np.linalg.norm(tangent, axis=1)[:, None]
    e1 = radial - np.einsum("ij,ij->i", radial, t)[:, None] * t
    size = np.linalg.norm(e1, axis=1)
    weak = size < 1e-9 * np.maximum(np.linalg.norm(radial, axis=1), 1e-300)
    if np.any(weak):
        f = np.broadcast_to(np.asarray(fallback, float), (int(weak.sum()), 3))
        e1[weak] = f - np.einsum("ij,ij->i", f, t[weak])[:, None] * t[weak]
        size[weak] = np.linalg.norm(e1[weak], axis=1)
    e1 /= size[:, None]
    return e1, np.cross(t, e1)


def section_components(moment: Array, tangent: Array, e1: Array, e2: Array) -> Array:
    """(n, 3): M₁ = m·e₁, M₂ = m·e₂ and T = m·t of the spatial section moments ``moment``."""
    t = tangent / np.linalg.norm(tangent, axis=1)[:, None]
    return np.column_stack([np.einsum("ij,ij->i", moment, e) for e in (e1, e2, t)])


def surface_stress(axial, m1, m2, diameter, angle) -> Array:
    """Axial stress σ (Pa) at the surface point of ``angle`` ψ (rad) of sections with axial
    force ``axial`` (N) and bending moments ``m1``, ``m2`` (N m); arrays broadcast (give the
    angles an axis of their own for several points per section)."""
    d = np.asarray(diameter, float)
    r, A, I = d / 2, np.pi * d**2 / 4, np.pi * d**4 / 64
    psi = np.asarray(angle, float)
    N, m1, m2 = (np.asarray(v, float) for v in (axial, m1, m2))
    return N / A + (r / I) * (m1 * np.sin(psi) - m2 * np.cos(psi))


def shear_stress(torque, diameter) -> Array:
    """Torsional shear stress τ = T r/J (Pa) at the surface of round wires."""
    d = np.asarray(diameter, float)
    return np.asarray(torque, float) * (d / 2) / (np.pi * d**4 / 32)
