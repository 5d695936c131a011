"""Stick bending with wires free to roll on stuck point ties: a smeared first-order estimate.

In full stick a tie between the **surface points** of two crossing wires still lets both wires
spin about their own axes: a wire can roll on its neighbours without slip, its centre moving
sideways, and the crossing angle turns one layer's sideways freedom into axial freedom for the
next. Only the wires' torsion (and a little in-surface bending) resists. This module estimates the
stick slope of a strand under that kinematics, and with the spin held (ties between the **centre
lines**, as classical beam-to-beam friction measures slip), so that a model's stick slope has a
reference beside EI_max.

Uniform curvature κ, plane-section base field; perturbations ∝ cos φ (φ from the neutral axis),
uniform along z, smeared over the crossings. Helical layer i (n wires of radius ρ = d/2 on the
helix radius r, lay angle α, hand h) has, in its cylindrical surface, the unit vectors
t = (cos α, h sin α) along the wire and b = (h sin α, −cos α) across it ((z, circumferential)
components), a centre shift A t + C b and a spin Θ. Energy per unit strand length, with
⟨sin²φ⟩ = ½:

    stretch   n EA/(4 cos α) (κ r cos²α − h sin α A/r)²
    torsion   n GJ/(4 cos α) (sin α Θ/r)²
    geodesic  n EI/(4 cos α) (sin²α C/r²)²

Ties (in-surface components, radial motion and tilts excluded): the inner surface point of
layer i moves by A t + (C + ρΘ) b, its outer one by A t + (C − ρΘ) b; the core's surface is held
by the plane sections, and layer i's outer point is tied to layer i+1's inner one. Minimising
over (A, C, Θ) subject to the ties gives E*, and

    EI_stick = EI_min + 2 E*/κ²,

with EI_min = Σ n E I (the EPRI variant, as ``strand.analytical.fibre.bending_stiffness_bounds``), so that
holding every spin gives EI_max exactly. A rotational stiffness per crossing (``k_roll`` on the
relative rotation about in-plane axes, ``k_drill`` about the normal) adds its energy at
N = n_i n_j (1/p_i + 1/p_j) crossings per metre. The estimate is first order and smeared (no
tilts, radial motion, contact compliance or end effects): a reference to rank hypotheses and test
a model's trends, not a validation.

``contact_patch`` gives what a Hertz contact patch offers against rolling and drilling.
Units: m, N, N m, rad.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from ..cable.description import Cable, Wire
from .stick_slip import ei_min

__all__ = ["StickEstimate", "stick_bending_estimate", "ContactPatch", "contact_patch"]

Array = npt.NDArray[np.float64]


@dataclass(frozen=True)
class StickEstimate:
    """The estimated stick slope and, per helical layer (1…N), the fields per unit curvature.

    Attributes:
        ei: stick slope M/κ, N m².
        ei_min, ei_max: the bounds (slipping wires; plane sections), N m².
        axial_share: wire axial-force amplitude over its plane-section value K r κ.
        spin: wire spin amplitude per unit curvature, rad m.
        torque: wire torsional moment amplitude per unit curvature, N m².
        sideways: centre shift across the wire (C) per unit curvature, m².
    """

    ei: float
    ei_min: float
    ei_max: float
    axial_share: Array
    spin: Array
    torque: Array
    sideways: Array

    @property
    def ratio(self) -> float:
        """EI_stick / EI_max."""
        return self.ei / self.ei_max


def _crossings_per_metre(cable: Cable, i: int) -> float:
    """Crossings per metre of strand between helical layers i and i + 1 (1-based layers)."""
    a, b = cable.layers[i], cable.layers[i + 1]
    return a.wires * b.wires * (1 / a.pitch + 1 / b.pitch)


def stick_bending_estimate(
    cable: Cable,
    spin: bool = True,
    torsion_scale: float = 1.0,
    bending_scale: float = 1.0,
    held: tuple[int, ...] = (),
    k_roll: float = 0.0,
    k_drill: float = 0.0,
) -> StickEstimate:
    """The smeared stick slope of ``cable`` (module docstring).

    Args:
        spin: wires free to spin at their ties (surface-point ties); False holds every spin
            (centre-line ties), which gives EI_max.
        torsion_scale, bending_scale: factors on every wire's GJ and EI (not on EI_min).
        held: helical layers (1-based) whose spin and sideways shift are held, as closed, stuck
            contacts between neighbours of one layer would.
        k_roll, k_drill: rotational stiffness per crossing, N m/rad.
    """
    layers = cable.layers[1:]
    n_layers = len(layers)
    if n_layers == 0:
        value = ei_min(cable)
        return StickEstimate(value, value, value, *(np.zeros(0) for _ in range(4)))
    nv = 3 * n_layers  # (A, C, Θ) per layer
    H, g, c0 = np.zeros((nv, nv)), np.zeros(nv), 0.0
    frames, plane = [], 0.0
    for i, lay in enumerate(layers):
        w, r, h = lay.wire, lay.radius, lay.hand
        ca, sa = np.cos(lay.alpha), np.sin(lay.alpha)
        inertia = np.pi * w.diameter**4 / 64
        EA, EI = w.E * w.area, w.E * inertia * bending_scale
        GJ = w.E / (2 * (1 + w.nu)) * 2 * inertia * torsion_scale
        frames.append((np.array([ca, h * sa]), np.array([h * sa, -ca]), w.diameter / 2))
        plane += 0.5 * lay.wires * EA * r**2 * ca**3
        weight = lay.wires * EA / (4 * ca)
        k0, kA = r * ca**2, -h * sa / r  # at κ = 1
        iA, iC, iT = 3 * i, 3 * i + 1, 3 * i + 2
        H[iA, iA] += 2 * weight * kA**2
        g[iA] += 2 * weight * kA * k0
        c0 += weight * k0**2
        H[iT, iT] += lay.wires * GJ / (2 * ca) * (sa / r) ** 2
        H[iC, iC] += lay.wires * EI / (2 * ca) * (sa**2 / r**2) ** 2
    for i in range(n_layers - 1):  # rotational restraint of the crossings i+1 | i+2
        count = _crossings_per_metre(cable, i + 1)
        (ti, _, _), (tj, _, _) = frames[i], frames[i + 1]
        roll = np.zeros((2, nv))
        roll[:, 3 * i + 2], roll[:, 3 * i + 5] = ti, -tj
        H += count * 0.5 * k_roll * roll.T @ roll
        drill = np.zeros(nv)
        for j in (i, i + 1):
            lay = layers[j]
            drill[3 * j + 1] = (1 if j == i else -1) * lay.hand * np.sin(lay.alpha) / lay.radius
        H += count * 0.5 * k_drill * np.outer(drill, drill)
    B = _ties(frames, spin, held)
    x = _minimise(H, g, B)
    energy = 0.5 * x @ H @ x + g @ x + c0
    low = ei_min(cable)
    spins = x[2::3]
    k0 = np.array([lay.radius * np.cos(lay.alpha) ** 2 for lay in layers])
    hs = np.array([lay.hand * np.sin(lay.alpha) / lay.radius for lay in layers])
    gj = np.array(
        [lay.wire.E / (1 + lay.wire.nu) * np.pi * lay.wire.diameter**4 / 64 for lay in layers]
    )
    return StickEstimate(
        ei=float(low + 2 * energy),
        ei_min=float(low),
        ei_max=float(low + plane),
        axial_share=(k0 - hs * x[0::3]) / k0,
        spin=np.abs(spins),
        torque=np.abs(torsion_scale * gj * np.abs(hs) * spins),
        sideways=np.abs(x[1::3]),
    )


def _ties(frames, spin: bool, held) -> Array:
    """The constraint rows B (B x = 0) of the stuck ties and held motions."""
    nv = 3 * len(frames)
    rows = []
    t, b, rho = frames[0]
    for k in range(2):  # the core's surface is held: layer 1's inner point does not move
        row = np.zeros(nv)
        row[0:3] = t[k], b[k], rho * b[k]
        rows.append(row)
    for i in range(len(frames) - 1):  # layer i's outer point = layer i+1's inner point
        (ti, bi, ri), (tj, bj, rj) = frames[i], frames[i + 1]
        for k in range(2):
            row = np.zeros(nv)
            row[3 * i : 3 * i + 3] = ti[k], bi[k], -ri * bi[k]
            row[3 * i + 3 : 3 * i + 6] = -tj[k], -bj[k], -rj * bj[k]
            rows.append(row)
    for i in range(len(frames)):
        if not spin or i + 1 in held:
            rows.append(np.eye(nv)[3 * i + 2])
        if i + 1 in held:
            rows.append(np.eye(nv)[3 * i + 1])
    return np.array(rows)


def _minimise(H: Array, g: Array, B: Array) -> Array:
    """argmin ½xᵀHx + gᵀx subject to Bx = 0, on a basis of B's null space."""
    _, s, vt = np.linalg.svd(B)
    rank = int(np.sum(s > 1e-12 * s.max()))
    Z = vt[rank:].T
    if Z.shape[1] == 0:
        return np.zeros(len(g))
    y = np.linalg.lstsq(Z.T @ H @ Z, -Z.T @ g, rcond=1e-14)[0]
    return Z @ y


@dataclass(frozen=True)
class ContactPatch:
    """A Hertz contact patch between two crossed wires and its rotational stiffness.

    Attributes:
        radius: equivalent patch radius c = √(ab), m.
        k_drill: no-slip torsional (drilling) stiffness 16c³/(3(1/G₁ + 1/G₂)), N m/rad
            (Johnson, Contact Mechanics, 1985, §7.3).
        k_roll: rocking stiffness of the patch (4/3)E*c³ (a flat circular punch tilted on a
            half-space), N m/rad.
        drill_slip_torque: full-slip drilling torque (3π/16)μPc (Lubkin 1951), N m.
    """

    radius: float
    k_drill: float
    k_roll: float
    drill_slip_torque: float


def contact_patch(
    force: float, wire_a: Wire, wire_b: Wire, crossing_angle: float, friction: float
) -> ContactPatch:
    """The patch of two wires crossing at ``crossing_angle`` (rad) pressed by ``force`` (N):
    crossed cylinders as an equivalent sphere (Johnson §4.2: A + B = ½(1/R₁ + 1/R₂),
    B − A = ½[1/R₁² + 1/R₂² + 2cos 2θ/(R₁R₂)]^½, R_e = 1/(2√(AB)), c = (3PR_e/(4E*))^⅓)."""
    R1, R2 = wire_a.diameter / 2, wire_b.diameter / 2
    total = 0.5 * (1 / R1 + 1 / R2)
    diff = 0.5 * np.sqrt(1 / R1**2 + 1 / R2**2 + 2 * np.cos(2 * crossing_angle) / (R1 * R2))
    A, B = (total - diff) / 2, (total + diff) / 2
    Re = 1 / (2 * np.sqrt(A * B))
    E_star = 1 / ((1 - wire_a.nu**2) / wire_a.E + (1 - wire_b.nu**2) / wire_b.E)
    c = (3 * force * Re / (4 * E_star)) ** (1 / 3)
    Ga, Gb = wire_a.E / (2 * (1 + wire_a.nu)), wire_b.E / (2 * (1 + wire_b.nu))
    return ContactPatch(
        radius=float(c),
        k_drill=float(16 * c**3 / (3 * (1 / Ga + 1 / Gb))),
        k_roll=float(4 / 3 * E_star * c**3),
        drill_slip_torque=float(3 * np.pi * friction * force * c / 16),
    )
