"""The small-sliding contact element: pair residuals and consistent tangents for Newton.

Each ``ContactGroup`` holds the pairs of one kind (crossings or line pairs) and implements the
solver's ``PairTerms`` protocol: given the nodal unknowns, it returns every pair's residual vector
and tangent block at once (numpy over all pairs, no loop). Per pair, with stencil dofs q:

* normal part: energy ½K_N⟨−g⟩², residual −p ∂g/∂q, tangent K_N H(−g) ∂g⊗∂g − p ∂²g/∂q²;
* friction: slip Δg_T = S Δq since the last converged step, S = P_n[−I, r_a n×, I, r_b n×]
  acting on (u_a, θ_a, u_b, θ_b), n and the tangent plane frozen at the start of the step; the
  traction t from the radial return (``laws.coulomb_return``); residual Sᵀt, tangent
  Sᵀ (∂t/∂Δg_T) S + Sᵀ (∂t/∂p)⊗(∂p/∂q) — unsymmetric in slip.

History (traction, normal, normal force, nodal values of a and b) is committed after converged
steps only. Units: m, N, rad.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from ..cable import CableError
from ..geometry import LINE, POINT, StrandGeometry
from .kinematics import NORMALS, gap_derivatives, skew, stencil_nodes
from .laws import coulomb_return, normal_force, tangential_stiffness

__all__ = [
    "ContactSettings",
    "ContactGroup",
    "ContactState",
    "contact_groups",
    "friction_terms",
    "tangential_part",
]

Array = npt.NDArray[np.float64]


@dataclass(frozen=True)
class ContactSettings:
    """Contact model settings (SI units).

    Attributes:
        normal: "director" (the seed paper's: rotated nodal tangents), "neighbour"
            (translation-only, from neighbour chords), "frozen" (initial radial normal), or
            "auto" (default): "director" with friction, "frozen" without. With friction the two
            geometry-following normals converge alike and give the same gaps (Cardinal, 4.3 kN:
            max error 3.7 vs 3.4 µm); "director" keeps 2-node stencils, so its LU is 1.6× cheaper.
            A frictionless strand has near-zero-energy modes (wires rolling around the layer
            below) that only the frozen normal's spurious stiffness holds; its gaps are then only
            approximate in bending (up to 11 µm). See ``strand.contact.kinematics``.
        k_point: penalty stiffness of a crossing, N/m (5e4 N/mm).
        k_line: penalty of the core | layer-1 line contact per metre of layer-1 wire, N/m²; each
            line pair gets k_line × its tributary length.
        g_lim: slip at which friction reaches μP (elastic slip, K_T = μP/g_lim), m.
        friction: use the Coulomb coefficients of the cable (False: frictionless).
        model: "small" sliding (pairs fixed at t = 0, this module) or "large" sliding (pairs
            re-projected at every iteration, ``strand.contact.sliding``: the baseline).
        reach: large sliding only: sliding distance reserved either side of each initial pair,
            m (its window holds every segment of the two wires within reach).
    """

    normal: str = "auto"
    k_point: float = 5e7
    k_line: float = 5e9
    g_lim: float = 5e-6
    friction: bool = True
    model: str = "small"
    reach: float = 1e-3

    def __post_init__(self):
        if self.normal == "auto":
            object.__setattr__(self, "normal", "director" if self.friction else "frozen")
        if self.normal not in NORMALS:
            raise CableError(
                f"contact normal {self.normal!r} is unknown; choose auto, {', '.join(NORMALS)}"
            )
        if self.model not in ("small", "large"):
            raise CableError(f"contact model {self.model!r} is unknown; choose small or large")
        for name in ("k_point", "k_line", "g_lim", "reach"):
            value = getattr(self, name)
            if not (isinstance(value, int | float) and value > 0):
                raise CableError(f"contact {name} = {value!r}: must be a positive number")


@dataclass
class ContactState:
    """Per-pair results of the last evaluation: gap g (m), normal force p (N), traction t (N),
    current normal n, whether the pair slips."""

    gap: Array
    force: Array
    traction: Array
    normal: Array
    slipping: npt.NDArray[np.bool_]


def friction_terms(S, dq, p, dp_dq, mu, p_old, t_old, n_old, g_lim, jacobian: bool):
    """Coulomb friction of all pairs on a slip operator S (P, 3, m): Δg_T = S Δq.

    Returns the residual Sᵀt (P, m), the tangent Sᵀ(∂t/∂Δg_T)S + Sᵀ(∂t/∂p)⊗∂p/∂q (P, m, M) over
    all M dofs of the pair's layout (``dp_dq`` (P, M); None without ``jacobian``), the traction and
    the slipping flags (pairs at the cap with a positive normal force).
    """
    slip = np.einsum("pij,pj->pi", S, dq)
    k_t = tangential_stiffness(mu, p_old, g_lim)
    ret = coulomb_return(t_old, slip, n_old, p, mu, k_t)
    f = np.einsum("pij,pi->pj", S, ret.traction)
    K = None
    if jacobian:
        St = S.transpose(0, 2, 1)
        K = np.einsum("pj,pk->pjk", np.einsum("pij,pi->pj", S, ret.d_pressure), dp_dq)
        K[:, :, : S.shape[2]] += St @ ret.d_slip @ S
    return f, K, ret.traction, ret.slipping & (p > 0)


def tangential_part(t, n):
    """The traction t (P, 3) projected on the plane normal to n: the history carried to a step."""
    return t - np.einsum("pi,pi->p", t, n)[:, None] * n


class ContactGroup:
    """Contact pairs of one kind sharing a stencil layout; a ``PairTerms`` for ``NewtonSolver``.

    Args:
        stencils: (P, k) local dof blocks, ordered as ``stencil_nodes(normal, line)``.
        initial_positions: (P, k, 3) positions of the stencil nodes at t = 0, m.
        line: line pairs (projected normal) rather than crossings.
        radius_a, radius_b: wire radii (P,), m; normal0: (P, 3) initial normals a → b;
        stiffness: K_N per pair (P,), N/m; mu: Coulomb coefficients (P,); g_lim: m.
        normal: the normal ("frozen", "neighbour", "director").
        tangent0: (P, 2, 3) initial unit tangents at a and b (``director`` only).
        index: (P,) pair ids in the geometry's pair list, for reporting.
    """

    def __init__(
        self,
        stencils,
        initial_positions,
        line: bool,
        radius_a,
        radius_b,
        normal0,
        stiffness,
        mu,
        g_lim: float,
        normal: str,
        tangent0=None,
        index=None,
    ):
        self.stencils = np.ascontiguousarray(stencils, dtype=np.int32)
        n_pairs, k = self.stencils.shape
        if k != len(stencil_nodes(normal, line)):
            raise ValueError(
                f"{normal} normal needs stencils of {len(stencil_nodes(normal, line))}"
            )
        self.X = np.asarray(initial_positions, dtype=float)
        #: stencil dofs that the residual and tangent hold: (u, θ) of a and b, and the positions of
        #: the neighbour nodes (their rotations never enter)
        self.dofs = np.concatenate(
            [np.arange(12), (6 * np.arange(2, k)[:, None] + np.arange(3)).ravel()]
        )
        self.line = line
        self.normal_kind = normal
        self.r_a = np.asarray(radius_a, dtype=float)
        self.r_b = np.asarray(radius_b, dtype=float)
        self.k_n = np.asarray(stiffness, dtype=float)
        self.mu = np.asarray(mu, dtype=float)
        self.g_lim = g_lim
        self.index = np.arange(n_pairs) if index is None else np.asarray(index)
        n0 = np.asarray(normal0, dtype=float)
        self.data: dict = {"g0": np.zeros(n_pairs), "n0": n0}
        X = self.X
        if not line and normal in ("neighbour", "director"):
            if normal == "neighbour":
                ca, cb = X[:, 3] - X[:, 2], X[:, 5] - X[:, 4]
            else:
                ca, cb = tangent0[:, 0], tangent0[:, 1]
            self.data["sign"] = np.sign(np.einsum("pi,pi->p", np.cross(ca, cb), n0))
            if np.any(self.data["sign"] == 0):
                raise ValueError("a crossing pair has parallel tangents; use a line pair")
        if normal == "director":
            self.data["t0"] = np.asarray(tangent0, dtype=float)
        # g0: the initial value, so that g ≡ 0 at t = 0
        zero = np.zeros_like(X)
        self.data["g0"] = gap_derivatives(normal, line, X, zero, self.data).gap.copy()
        # friction history
        self._q_old = np.zeros((n_pairs, 12))
        self._t_old = np.zeros((n_pairs, 3))
        self._n_old = n0.copy()
        self._p_old = np.zeros(n_pairs)
        self._last: tuple | None = None
        self._S: Array | None = None  # slip operator of the current step
        self.state = ContactState(
            np.zeros(n_pairs),
            np.zeros(n_pairs),
            np.zeros((n_pairs, 3)),
            n0.copy(),
            np.zeros(n_pairs, dtype=bool),
        )

    def __len__(self) -> int:
        return len(self.stencils)

    @property
    def friction(self) -> bool:
        return bool(np.any(self.mu > 0))

    def slip_operator(self) -> Array:
        """S (P, 3, 12): Δg_T = S Δ(u_a, θ_a, u_b, θ_b), with the normal frozen over the step."""
        if self._S is None:
            self._S = self._build_slip_operator()
        return self._S

    def _build_slip_operator(self) -> Array:
        n = self._n_old
        P_n = np.eye(3) - n[:, :, None] * n[:, None, :]
        N = skew(n)
        return np.concatenate(
            [-P_n, self.r_a[:, None, None] * N, P_n, self.r_b[:, None, None] * N], axis=2
        )

    def evaluate(self, w: Array, jacobian: bool = True):
        W = w[self.stencils]  # (P, k, 6)
        x = self.X + W[..., :3]
        gd = gap_derivatives(
            self.normal_kind,
            self.line,
            x,
            W[..., 3:],
            self.data,
            hessian_where=(lambda g: g <= 0.0) if jacobian else None,
        )
        p, dp_dg = normal_force(gd.gap, self.k_n)
        G = gd.gradient[:, self.dofs]
        f = -p[:, None] * G
        K = None
        if jacobian:
            K = G[:, :, None] * G[:, None, :]
            K *= -dp_dg[:, None, None]
            gd.add_hessian(K, -p, self.dofs)
        traction = np.zeros((len(p), 3))
        slipping = np.zeros(len(p), dtype=bool)
        if self.friction:
            dq = W[:, :2].reshape(-1, 12) - self._q_old
            f_t, K_t, traction, slipping = friction_terms(
                self.slip_operator(), dq, p, dp_dg[:, None] * G, self.mu, self._p_old,
                self._t_old, self._n_old, self.g_lim, jacobian,
            )  # fmt: skip
            f[:, :12] += f_t
            if jacobian:
                K[:, :12, :] += K_t
        self.state = ContactState(gd.gap, p, traction, gd.normal, slipping)
        self._last = W[:, :2].reshape(-1, 12).copy()
        return f, K

    def commit(self) -> None:
        """Accept the last evaluated state (the converged one) as the friction history."""
        if self._last is None:
            return
        n = self.state.normal
        t = self.state.traction
        self._t_old = tangential_part(t, n)  # onto the new tangent plane
        self._n_old = n.copy()
        self._p_old = self.state.force.copy()
        self._q_old = self._last.copy()
        self._S = None

    def rollback(self) -> None:
        """Forget the current step (history is only changed by ``commit``)."""
        self._last = None

    @property
    def committed_force(self) -> Array:
        """Normal forces (N) at the last committed step."""
        return self._p_old


def _neighbours(geometry: StrandGeometry, nodes: npt.NDArray[np.int64]):
    """Input indices of the previous and next node on the same wire (the node itself at ends)."""
    wire = geometry.point_wire[nodes]
    lo, hi = geometry.wire_offsets[wire], geometry.wire_offsets[wire + 1] - 1
    return np.maximum(nodes - 1, lo), np.minimum(nodes + 1, hi)


def _initial_tangents(geometry: StrandGeometry, nodes):
    prev, nxt = _neighbours(geometry, nodes)
    c = geometry.points[nxt] - geometry.points[prev]
    return c / np.linalg.norm(c, axis=1)[:, None]


def contact_groups(
    geometry: StrandGeometry, input_to_block: npt.NDArray[np.int32], settings: ContactSettings
) -> list[ContactGroup]:
    """The contact pairs of a strand as ``ContactGroup`` objects (one per pair kind present).

    ``input_to_block`` maps the geometry's point indices to local dof blocks (``mesh.input_to_block``).
    """
    pairs = geometry.pairs
    groups = []
    for kind in (POINT, LINE):
        sel = np.flatnonzero(pairs.kind == kind)
        if len(sel) == 0:
            continue
        line = kind == LINE
        a, b = pairs.a[sel], pairs.b[sel]
        nodes = {"a": a, "b": b}
        nodes["a-"], nodes["a+"] = _neighbours(geometry, a)
        nodes["b-"], nodes["b+"] = _neighbours(geometry, b)
        roles = stencil_nodes(settings.normal, line)
        points = np.stack([nodes[r] for r in roles], axis=1)
        if np.any(input_to_block[points] < 0):
            raise NotImplementedError(
                "contact pairs whose nodes are not all on this process: strand's contact runs "
                "serially for now (pair ownership with a slab partitioner is the way to MPI)"
            )
        stiffness = (
            settings.k_line * pairs.tributary[sel] if line else np.full(len(sel), settings.k_point)
        )
        mu = pairs.friction[sel] if settings.friction else np.zeros(len(sel))
        tangent0 = np.stack([_initial_tangents(geometry, a), _initial_tangents(geometry, b)], 1)
        groups.append(
            ContactGroup(
                input_to_block[points],
                geometry.points[points],
                line,
                pairs.radius_a[sel],
                pairs.radius_b[sel],
                pairs.normal[sel],
                stiffness,
                mu,
                settings.g_lim,
                settings.normal,
                tangent0,
                index=sel,
            )
        )
    return groups
