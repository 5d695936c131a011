"""Contact laws for all pairs at once (numpy): penalty normal force and Coulomb friction.

Physics only: functions of gaps, slips and histories, returning forces and their exact derivatives.
Units: m, N; K_N and K_T in N/m (per pair).

Normal law. p = K_N ⟨−g⟩ (compression positive). A pair counts as closed in the tangent for g ≤ 0:
pairs start at g = 0, and the strict g < 0 rule gives a first tangent without contact stiffness.

Friction. Elastic slip with stiffness K_T = μ P₀/g_lim (P₀ the normal force at the start of the
step, frozen over the step so that Newton stays quadratic) and a radial return onto the Coulomb
cone: the trial traction t_tr = P_n t_old + K_T Δg_T (P_n = I − n⊗n re-projects the stored
traction onto the current tangent plane) is kept when |t_tr| ≤ μp (stick), else scaled back to
μp t_tr/|t_tr| (slip).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = ["normal_force", "CoulombResult", "coulomb_return", "tangential_stiffness"]

Array = npt.NDArray[np.float64]


def normal_force(g: Array, k_n: Array | float) -> tuple[Array, Array]:
    """p = K_N⟨−g⟩ and dp/dg = −K_N for closed pairs (g ≤ 0), 0 for open ones."""
    closed = g <= 0.0
    k = np.broadcast_to(k_n, g.shape)
    return np.where(closed, -k * g, 0.0), np.where(closed, -k, 0.0)


def tangential_stiffness(mu: Array, p_start: Array, g_lim: float) -> Array:
    """K_T = μ P₀/g_lim (N/m), from the normal force P₀ at the start of the step."""
    return mu * p_start / g_lim


@dataclass
class CoulombResult:
    """Frictional traction t (P, 3) and its derivatives: dt/dΔg_T (P, 3, 3) and dt/dp (P, 3)."""

    traction: Array
    d_slip: Array
    d_pressure: Array
    slipping: npt.NDArray[np.bool_]


def coulomb_return(
    t_old: Array, slip: Array, normal: Array, p: Array, mu: Array, k_t: Array
) -> CoulombResult:
    """Radial return for all pairs.

    Args:
        t_old: traction at the last converged step (P, 3), N.
        slip: tangential slip increment since that step, Δg_T (P, 3), m (in the tangent plane).
        normal: current unit normals (P, 3).
        p: current normal force (P,), N.
        mu: friction coefficients (P,); k_t: slip stiffnesses (P,), N/m.
    """
    P_n = np.eye(3) - normal[:, :, None] * normal[:, None, :]
    trial = np.einsum("pij,pj->pi", P_n, t_old) + k_t[:, None] * slip
    size = np.linalg.norm(trial, axis=1)
    cap = mu * p
    slipping = size > cap
    safe = np.where(size > 0, size, 1.0)
    nu = trial / safe[:, None]
    eye = np.broadcast_to(np.eye(3), (len(p), 3, 3))
    # stick: t = trial
    d_slip = k_t[:, None, None] * eye
    d_pressure = np.zeros_like(trial)
    traction = trial.copy()
    # slip: t = μ p ν, dt/dtrial = μp/|trial| (I − ν⊗ν)
    s = slipping
    if np.any(s):
        proj = eye[s] - nu[s, :, None] * nu[s, None, :]
        d_slip[s] = (cap[s] * k_t[s] / safe[s])[:, None, None] * proj
        d_pressure[s] = mu[s, None] * nu[s]
        traction[s] = cap[s, None] * nu[s]
    return CoulombResult(traction, d_slip, d_pressure, slipping)
