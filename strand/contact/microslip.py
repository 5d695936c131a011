"""Mindlin–Deresiewicz microslip: a stick–slip law without a kink at gross slip.

Physics only (numpy, arrays over pairs). Units: m, N; stiffnesses in N/m (per pair).

A Hertzian contact under a constant normal force P, loaded tangentially from rest, slips over an
annulus that grows with the load (Mindlin & Deresiewicz 1953; Johnson, *Contact Mechanics*, 1985,
§7.2–7.4). Its load–displacement curve meets gross slip with zero slope:

    Q(δ) = μP [1 − (1 − δ/δ*)^{3/2}],   δ* = 3μP/(2 K₀),

K₀ = 8 G* a being Mindlin's initial tangential stiffness (``Mindlin``'s K_T). Along it the tangent
is K₀ (1 − Q/μP)^{1/3} (Thornton & Yin 1991). A reversal at (δ_r, Q_r) starts Masing's branch,
the virgin curve doubled, Q = Q_r − 2μP [1 − (1 − (δ_r − δ)/(2δ*))^{3/2}], whose tangent is back
at K₀: only reversals keep a kink.

The incremental form used here, for two tangential directions and a varying normal force. A
pair's history is its traction t_old at the last converged step and its branch: the anchor t_r
where the branch started (0 on the virgin curve) and the branch factor c (1 virgin, 2 after a
reversal). Over a step:

* the branch's traction τ₀ = t_old − t_r is mapped to its distance along the branch,
  s₀ = X₀ [1 − (1 − ‖τ₀‖/C₀)^{2/3}] with the capacity C₀ = cμP₀ and X₀ = 3C₀/(2K₀), at the normal
  force P₀ of the step's start (with which K₀ is frozen, as in ``Mindlin``);
* a slip Δg_T with Δg_T·τ₀ < 0 reverses the branch: anchor t_old, c = 2, s₀ = 0;
* the branch goes on along S = s₀ τ₀/‖τ₀‖ + Δg_T: τ = C h(‖S‖/X) S/‖S‖, h(r) = 1 − (1 − r)^{3/2}
  (1 past r = 1), with C = cμp and X = 3C/(2K₀) at the current normal force p;
* t = t_r + τ, capped radially at μp (the cap binds only on a reversal branch whose direction or
  normal force has changed; the virgin branch saturates at μp by itself).

At constant P and along one direction this is Mindlin–Deresiewicz's curve and Masing's loop
exactly (``tests/test_microslip.py`` holds a crossed pair's loop and its energy per cycle to the
closed forms). A branch that reaches the traction −t_r of its anchor, or the cap, goes on along
the virgin curve (Masing's memory of one loop: symmetric cycles close on the curve they left);
so does a pair that opens. In two directions, "reaches −t_r" reads: ‖t‖ ≥ ‖t_r‖ with
(t − t_r)·t_r < 0 (a small loop left sideways is left behind too). For line contact (parallel
or near-parallel wires) the same curve is used with the line law's K₀: Cattaneo–Mindlin's strip
has a logarithmic compliance that depends on the contact's extent, so the point-contact shape
stands for it (stated in docs/theory.md).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import numpy.typing as npt

from .friction_laws import CoulombResult, Mindlin
from .group import tangential_part

__all__ = ["MindlinDeresiewicz", "microslip_return", "loop_energy"]

Array = npt.NDArray[np.float64]


def _along(x: Array, capacity: Array, k0: Array) -> tuple[Array, Array, Array]:
    """The branch's traction F(x) = C h(x/X), dF/dx and ∂F/∂C (C and X = 3C/(2K₀) together),
    at distances ``x`` (m) along branches of capacities C (N) and initial stiffnesses K₀ (N/m);
    zero where C or K₀ is zero."""
    live = (capacity > 0) & (k0 > 0)
    span = np.where(live, 1.5 * capacity / np.where(live, k0, 1.0), 1.0)
    r = np.minimum(np.where(live, x / span, 0.0), 1.0)
    rest = np.sqrt(1.0 - r)
    h = 1.0 - rest**3
    force = np.where(live, capacity * h, 0.0)
    slope = np.where(live, k0 * rest, 0.0)
    d_capacity = np.where(live, h - 1.5 * r * rest, 0.0)
    return force, slope, d_capacity


def _distance(tau: Array, capacity: Array, k0: Array) -> Array:
    """The distance s (m) along a branch at which its traction is ``tau`` (N): the inverse of
    ``_along``, with ‖τ‖ capped at the capacity."""
    live = (capacity > 0) & (k0 > 0)
    ratio = np.minimum(np.where(live, tau / np.where(live, capacity, 1.0), 0.0), 1.0)
    return np.where(live, 1.5 * capacity / np.where(live, k0, 1.0), 0.0) * (
        1.0 - (1.0 - ratio) ** (2.0 / 3.0)
    )


#: a branch's traction below this fraction of μP₀ is round-off: nothing to reverse from
NEGLIGIBLE = 1e-9


def reversal(
    slip: Array, t_old: Array, normal: Array, anchor: Array, cap: Array
) -> npt.NDArray[np.bool_]:
    """Whether each pair's slip Δg_T goes against its branch: Δg_T·τ₀ < 0, τ₀ = t_old − t_r on
    the plane normal to ``normal``, where ‖τ₀‖ is more than round-off (``NEGLIGIBLE`` × the
    pair's Coulomb limit ``cap`` = μP₀, N)."""
    tau0 = tangential_part(t_old, normal) - tangential_part(anchor, normal)
    real = np.linalg.norm(tau0, axis=1) > NEGLIGIBLE * cap
    return (np.einsum("pi,pi->p", slip, tau0) < 0) & real


def microslip_return(
    t_old: Array,
    slip: Array,
    normal: Array,
    p: Array,
    p_start: Array,
    mu: Array,
    k0: Array,
    *,
    anchor: Array,
    branch: Array,
    decided: Array | None = None,
) -> tuple[CoulombResult, dict[str, Array]]:
    """Mindlin–Deresiewicz's traction for all pairs, and the branch history after the step.

    Args:
        t_old: traction at the last converged step (P, 3), N; slip: Δg_T since then (P, 3), m.
        normal: the unit normals of the step's start (P, 3).
        p: current normal force (P,), N; p_start: the normal force P₀ at the step's start (P,).
        mu: Coulomb coefficients (P,); k0: Mindlin's initial stiffnesses K₀ at P₀ (P,), N/m.
        anchor: the traction t_r where each pair's branch started (P, 3), N; branch: c (P,),
            1 on the virgin curve, 2 after a reversal.
        decided: which pairs reverse in this step (P,), if decided already; None: those whose
            slip goes against their branch, Δg_T·τ₀ < 0.

    Returns the traction with dt/dΔg_T and dt/dp (``CoulombResult``; ``slipping``: gross slip,
    the branch saturated or at the cap), and ``{"anchor", "branch"}`` for the next step with
    ``"reversed"``, the choice made.
    """
    n = len(p)
    eye = np.broadcast_to(np.eye(3), (n, 3, 3))
    t0, t_r = (tangential_part(t, normal) for t in (t_old, anchor))
    tau0 = t0 - t_r
    size0 = np.linalg.norm(tau0, axis=1)
    reverse = reversal(slip, t_old, normal, anchor, mu * p_start) if decided is None else decided
    c = np.where(reverse, 2.0, branch)
    start = np.where(reverse[:, None], t0, t_r)
    s0 = np.where(reverse, 0.0, _distance(size0, c * mu * p_start, k0))
    along0 = tau0 / np.where(size0 > 0, size0, 1.0)[:, None]
    S = s0[:, None] * along0 + slip
    x = np.linalg.norm(S, axis=1)
    S_hat = S / np.where(x > 0, x, 1.0)[:, None]
    p_pos = np.maximum(p, 0.0)
    force, slope, d_capacity = _along(x, c * mu * p_pos, k0)
    secant = np.where(x > 0, force / np.where(x > 0, x, 1.0), np.where(p_pos > 0, k0, 0.0))
    outer = S_hat[:, :, None] * S_hat[:, None, :]
    d_slip = slope[:, None, None] * outer + secant[:, None, None] * (eye - outer)
    d_pressure = (c * mu * d_capacity)[:, None] * S_hat * (p > 0)[:, None]
    trial = start + force[:, None] * S_hat
    size = np.linalg.norm(trial, axis=1)
    cap = mu * p_pos
    capped = size > cap
    traction = trial.copy()
    if np.any(capped):
        k = capped
        nu = trial[k] / np.where(size[k] > 0, size[k], 1.0)[:, None]
        scale = np.where(size[k] > 0, cap[k] / np.where(size[k] > 0, size[k], 1.0), 0.0)
        proj = scale[:, None, None] * (eye[k] - nu[:, :, None] * nu[:, None, :])
        traction[k] = cap[k, None] * nu
        d_slip[k] = proj @ d_slip[k]
        d_pressure[k] = mu[k, None] * nu + np.einsum("pij,pj->pi", proj, d_pressure[k])
    span = 1.5 * c * mu * p_pos / np.where(k0 > 0, k0, 1.0)
    saturated = (k0 > 0) & (x >= span)
    # the history if this evaluation is committed: the branch, or the virgin curve again where
    # the pair opened, reached the cap, or (a reversal branch) passed its anchor's level moving
    # away from it: the loop closed (1D: at −t_r)
    passed = np.linalg.norm(traction, axis=1) >= np.linalg.norm(start, axis=1)
    away = np.einsum("pi,pi->p", traction - start, start) < 0
    rejoin = capped | (p <= 0) | ((c == 2) & passed & away)
    history = {
        "anchor": np.where(rejoin[:, None], 0.0, start),
        "branch": np.where(rejoin, 1.0, c),
        "reversed": reverse,
    }
    return CoulombResult(traction, d_slip, d_pressure, (saturated | capped) & (p > 0)), history


def loop_energy(amplitude, mu_p, k0):
    """Energy (J) a Hertzian contact dissipates per cycle of the tangential load ±Q* at constant
    normal force P (Mindlin & Deresiewicz; Johnson 1985, eq. 7.59), in terms of μP (N) and
    Mindlin's initial stiffness K₀ = 8G*a (N/m):

        W = (36/5) (μP)²/K₀ [1 − (1 − q)^{5/3} − (5q/6)(1 + (1 − q)^{2/3})],  q = Q*/μP,

    about 2Q*³/(9 K₀ μP) for small amplitudes: the area of the Masing loop on the curve
    above, integrated exactly (with K₀ = 8a/[(2 − ν₁)/G₁ + (2 − ν₂)/G₂] this is Johnson's
    (9μ²P²/10a)[(2 − ν₁)/G₁ + (2 − ν₂)/G₂][…])."""
    q = np.asarray(amplitude, float) / np.asarray(mu_p, float)
    bracket = 1 - (1 - q) ** (5 / 3) - (5 * q / 6) * (1 + (1 - q) ** (2 / 3))
    return 7.2 * np.asarray(mu_p, float) ** 2 / np.asarray(k0, float) * bracket


@dataclass(frozen=True)
class MindlinDeresiewicz(Mindlin):
    """Mindlin's initial stiffness K₀ = ``ratio`` × dp/dδ(P₀) (as ``Mindlin``), with the
    microslip curve up to gross slip and Masing's branches after reversals
    (``microslip_return``): the traction meets μp with zero slope."""

    CHOICES: ClassVar[tuple[str, ...]] = ("reversed",)

    def initial_history(self, n_pairs: int) -> dict[str, Array]:
        return {"anchor": np.zeros((n_pairs, 3)), "branch": np.ones(n_pairs)}

    def choose(
        self, slip: Array, t_old: Array, n_old: Array, p_old: Array, history: dict[str, Array]
    ):  # the base's dict of float arrays: its flag is a bool array
        """A pair reverses where its slip goes against its branch, Δg_T·(t_old − t_r) < 0."""
        mu = np.broadcast_to(np.asarray(self.mu, float), p_old.shape)
        return {"reversed": reversal(slip, t_old, n_old, history["anchor"], mu * p_old)}

    def _return(self, t_old, slip, n_old, p, p_old, mu, k_t, history):
        if history is None:
            history = self.initial_history(len(p))
        return microslip_return(
            t_old,
            slip,
            n_old,
            p,
            p_old,
            mu,
            k_t,
            anchor=history["anchor"],
            branch=history["branch"],
            decided=history.get("reversed"),
        )
