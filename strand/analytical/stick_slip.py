"""Stick–slip bending of a tensioned strand, and Masing cycles. Physics only (numpy).

**Stick–slip bending** (Lehanneur–Rebuffel–Papailiou type, as written by Cloutier & Cardou 2013,
*Stick-slip mechanical models for overhead electrical conductors in bending*, and coded in RTE's
``strdcable``). A wire of layer i at angle φ from the neutral axis needs, to follow plane sections,
the extra tension ΔT = K r κ sinφ, K = E A cos²α. Friction lets the tension change along the wire
by at most f per radian of φ (ds = r dφ/sinα): slip starts at the neutral axis when K r κ > f,

    κ_b = f / (K r)                                              (slip onset of the layer)

* ``rule="own_tension"``: f = μ T sinα, the capstan friction of the wire's own tension on the layer
  below (T the wire's tension, μ its coefficient with the layer below);
* ``rule="cumulative"``: f = (μ_in p_in + μ_out p_out) r / sinα with the line loads of all the
  layers outside pressing on both faces, p_in = cosα/n Σ_{j≥i} n_j T_j sin²α_j /(r_j cosα_j),
  p_out the same sum over j > i (Cloutier's "SC2" rule): the inner layers see the outer ones'
  pressure.

With a slipped sector [0, φ0] (ΔT = f φ, or T(e^{λφ} − 1) with λ = f/T for the exponential
capstan) and a sticking one beyond it, tangent to it (K r κ cos φ0 = f), the layer's moment is

    M_i = (2 n_i/π) r cosα ∫₀^{π/2} ΔT(φ) sinφ dφ,

which is (n/2) K r² cosα κ in stick (EI_s,i κ) and M_slip,i = (2n/π) r cosα f in full slip. The
strand's virgin curve is M(κ) = EI_min κ + Σ_i M_i(κ); ``piecewise`` gives the linearised law
EI_min κ + Σ min(EI_s,i κ, M_slip,i). Cyclic loading follows Masing's rules (``masing``).

Units: m, N, N m, 1/m.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from ..cable.description import Cable

__all__ = ["EI_MIN_VARIANTS", "ei_min", "StickSlipLaw", "masing", "loop_area"]

Array = npt.NDArray[np.float64]


def _second_moment(d: float) -> float:
    return np.pi * d**4 / 64


#: EI_min variants (as in RTE's strdcable), per layer: n E I × factor(α, ν)
EI_MIN_VARIANTS: dict[str, Callable[[float, float], float]] = {
    "EPRI": lambda a, nu: 1.0,
    "PAPAILIOU": lambda a, nu: np.cos(a),
    "LEHANNEUR": lambda a, nu: np.cos(a) * (1 - nu * np.sin(a) ** 2 / (2 * (1 + nu))),
    "COSTELLO": lambda a, nu: np.cos(a) * 2 / (2 + nu * np.sin(a) ** 2),
    "FOTI": lambda a, nu: 0.5 * np.cos(a) * (1 + np.cos(a) ** 2 + np.sin(a) / (1 + nu)),
}


def ei_min(cable: Cable, variant: str = "EPRI") -> float:
    """Bending stiffness of the strand with every wire slipping freely (N m²)."""
    factor = EI_MIN_VARIANTS[variant]
    return sum(
        max(lay.wires, 1)
        * lay.wire.E
        * _second_moment(lay.wire.diameter)
        * (factor(lay.alpha, lay.wire.nu) if lay.wires else 1.0)
        for lay in cable.layers
    )


@dataclass(frozen=True)
class _Layer:
    n: int
    r: float
    alpha: float
    K: float  # E A cos²α, N
    T: float  # wire tension, N
    f: float  # friction capacity per radian of φ, N


class StickSlipLaw:
    """Virgin moment–curvature law of ``cable`` under ``tension`` (N), ends held against rotation
    (wire tensions from the fibre model).

    Args:
        rule: "cumulative" (outer layers' pressure on both faces) or "own_tension".
        capstan: exponential capstan in the slipped sector instead of the linearised one.
        ei_min_variant: the ``EI_MIN_VARIANTS`` key for the wires' own bending.
    """

    def __init__(
        self,
        cable: Cable,
        tension: float,
        rule: str = "cumulative",
        capstan: bool = False,
        ei_min_variant: str = "EPRI",
    ):
        if rule not in ("cumulative", "own_tension"):
            raise ValueError(f"rule {rule!r}: choose cumulative or own_tension")
        self.cable, self.tension, self.rule, self.capstan = cable, tension, rule, capstan
        self.ei_min = ei_min(cable, ei_min_variant)
        lays = cable.layers
        k = sum(max(l.wires, 1) * l.wire.E * l.wire.area * np.cos(l.alpha) ** 3 for l in lays)
        eps = tension / k
        T = [l.wire.E * l.wire.area * np.cos(l.alpha) ** 2 * eps for l in lays]
        # line load per unit length of wire, pressed inwards by layer j, per wire of layer i
        press = [
            l.wires * T[j] * np.sin(l.alpha) ** 2 / (l.radius * np.cos(l.alpha)) if j else 0.0
            for j, l in enumerate(lays)
        ]
        self.layers: list[_Layer] = []
        for i, lay in enumerate(lays[1:], start=1):
            a, r, n = lay.alpha, lay.radius, lay.wires
            mu_in = lays[i - 1].friction  # with the layer below
            mu_out = lay.friction if i + 1 < len(lays) else 0.0
            if rule == "own_tension":
                f = mu_in * T[i] * np.sin(a)
            else:
                p_in = np.cos(a) / n * sum(press[i:])
                p_out = np.cos(a) / n * sum(press[i + 1 :])
                f = (mu_in * p_in + mu_out * p_out) * r / np.sin(a)
            K = lay.wire.E * lay.wire.area * np.cos(a) ** 2
            self.layers.append(_Layer(n, r, a, K, T[i], f))

    # -- per layer -------------------------------------------------------------------------------
    @property
    def stick_stiffness(self) -> Array:
        """EI_s,i = (n/2) E A r² cos³α per helical layer, N m²."""
        return np.array([l.n / 2 * l.K * l.r**2 * np.cos(l.alpha) for l in self.layers])

    @property
    def ei_max(self) -> float:
        return self.ei_min + float(self.stick_stiffness.sum())

    @property
    def slip_onset(self) -> Array:
        """κ_b per helical layer: slip starts at its neutral axis, 1/m."""
        return np.array([l.f / (l.K * l.r) for l in self.layers])

    @property
    def full_slip(self) -> Array:
        """κ_t = T (e^{λπ/2} − 1)/(K r), λ = f/T, per helical layer (docs/theory.md §5.4, whole quarter
        turn slipping), 1/m."""
        return np.array(
            [l.T * (np.exp(l.f / l.T * np.pi / 2) - 1) / (l.K * l.r) for l in self.layers]
        )

    @property
    def slip_moment(self) -> Array:
        """M_slip,i: the layer's moment once fully slipped, N m."""
        return np.array([self._layer_moment(l, np.inf) for l in self.layers])

    def _integral(self, l: _Layer, a: Array) -> Array:
        """∫₀^{π/2} ΔT(φ) sinφ dφ for demand slopes a = K r κ ≥ 0 (N)."""
        a = np.asarray(a, dtype=float)
        if not self.capstan:
            with np.errstate(divide="ignore", invalid="ignore"):
                c = np.clip(l.f / a, 0.0, 1.0)
            phi0 = np.arccos(c)
            s0 = np.sin(phi0)
            out = l.f * s0 + a * ((np.pi / 2 - phi0) / 2 - np.sin(2 * phi0) / 4)
            return np.where(np.isinf(a), l.f, np.where(a <= l.f, a * np.pi / 4, out))
        lam = l.f / l.T
        T = l.T

        def slip_part(p):  # ∫₀^p T(e^{λφ} − 1) sinφ dφ
            e = np.exp(lam * p)
            return T * ((e * (lam * np.sin(p) - np.cos(p)) + 1) / (1 + lam**2) - (1 - np.cos(p)))

        out = np.empty_like(a)
        for k, ak in np.ndenumerate(a):
            if ak <= lam * T:
                out[k] = ak * np.pi / 4
                continue
            if not np.isfinite(ak):
                out[k] = slip_part(np.pi / 2)
                continue
            # tangency a cos p = λ T e^{λp}: g(0) = a − λT > 0 > g(π/2), so one root in between
            g = lambda p, ak=ak: ak * np.cos(p) - lam * T * np.exp(lam * p)  # noqa: E731
            lo, hi = 0.0, np.pi / 2
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if g(mid) > 0 else (lo, mid)
            p = 0.5 * (lo + hi)
            dT0 = T * (np.exp(lam * p) - 1)
            stick = ak * ((np.pi / 2 - p) / 2 + np.sin(2 * p) / 4 - np.sin(p) * np.cos(p))
            out[k] = slip_part(p) + stick + dT0 * np.cos(p)
        return out

    def _layer_moment(self, l: _Layer, kappa) -> Array:
        k = np.abs(np.asarray(kappa, dtype=float))
        a = np.where(np.isinf(k), np.inf, l.K * l.r * k)
        return np.sign(kappa) * 2 * l.n / np.pi * l.r * np.cos(l.alpha) * self._integral(l, a)

    # -- the strand ------------------------------------------------------------------------------
    def layer_moments(self, kappa: npt.ArrayLike) -> Array:
        """(helical layers, len(κ)) moments of each layer on the virgin curve, N m."""
        return np.array([self._layer_moment(l, kappa) for l in self.layers])

    def moment(self, kappa: npt.ArrayLike) -> Array:
        """Virgin curve M(κ), N m (odd in κ)."""
        k = np.asarray(kappa, dtype=float)
        return self.ei_min * k + self.layer_moments(k).sum(axis=0)

    def piecewise(self, kappa: npt.ArrayLike) -> Array:
        """The linearised bending law EI_min κ + Σ min(EI_s,i abs(κ), M_slip,i) sign κ, N m."""
        k = np.asarray(kappa, dtype=float)
        caps = [2 * l.n / np.pi * l.r * np.cos(l.alpha) * l.f for l in self.layers]
        terms = [
            np.minimum(s * np.abs(k), c) for s, c in zip(self.stick_stiffness, caps, strict=True)
        ]
        return self.ei_min * k + np.sign(k) * np.sum(terms, axis=0)

    def curvature(self, moment: npt.ArrayLike) -> Array:
        """Inverse of the virgin curve (monotonic), by interpolation on κ ∈ [1e-7, 10] 1/m."""
        if not hasattr(self, "_inverse"):
            grid = np.r_[0.0, np.geomspace(1e-7, 10.0, 4000)]
            self._inverse = (self.moment(grid), grid)
        M = np.asarray(moment, dtype=float)
        return np.sign(M) * np.interp(np.abs(M), *self._inverse)


def masing(virgin: Callable[[Array], Array], path: npt.ArrayLike) -> Array:
    """Response along a history ``path`` (samples of the driving variable, starting at 0) of a
    Masing (Iwan) system whose virgin curve ``virgin`` is odd: after a reversal at (x_r, y_r),
    y = y_r + 2 v((x − x_r)/2); a branch that runs past the reversal it started from rejoins the
    branch before it (memory: closed loops are forgotten)."""
    x = np.asarray(path, dtype=float)
    out = np.zeros_like(x)
    branches = [(0.0, 0.0, 1.0)]  # (origin x, origin y, scale): virgin first
    direction = 0.0

    def on(branch, xi):
        x0, y0, c = branch
        return y0 + c * float(virgin(np.array([(xi - x0) / c]))[0])

    for k in range(1, len(x)):
        dx = x[k] - x[k - 1]
        if dx == 0:
            out[k] = out[k - 1]
            continue
        d = np.sign(dx)
        if direction and d != direction:  # reversal
            branches.append((x[k - 1], out[k - 1], 2.0))
        direction = d
        while len(branches) > 1:
            limit = branches[-2][0] if len(branches) > 2 else -branches[-1][0]
            if (x[k] - limit) * d > 0:  # past the point this branch started from
                branches.pop()
                if len(branches) > 1:
                    branches.pop()
            else:
                break
        out[k] = on(branches[-1], x[k])
    return out


def loop_area(x: npt.ArrayLike, y: npt.ArrayLike) -> float:
    """Area enclosed by a closed path (x, y) (shoelace), e.g. the dissipated energy per unit
    length of one M–κ cycle, J/m."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    return float(0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))
