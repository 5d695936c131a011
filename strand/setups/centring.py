"""A core held on its first layer's axis: lateral springs between each core node and the
layer's centre there (``strand.cable.centring.ring_centres``).

Why: the uniform bending set-up (``bending.CoreStrut``) compresses the core by the strand's
tension, and relies on the core's contacts to hold it sideways, as a column in a tube. A core that
touches no wire (``[contact] first_layer = "ring"``: layer 1 vaulted over it, 14 µm clear on
Cardinal) is a free column of 1 m under 20–40 kN, hundreds of times its Euler load
(4π²EI/L² ≈ 51 N for Cardinal's steel core, EI = 1.28 N m²): the tangent is not positive, and
Newton's direction is the core bowing by 0.1 mm within its 14 µm (design notes, 2026-11-30). The strut is the set-up's,
not the strand's (an end tension puts no compression anywhere); so is this remedy, which keeps the
strut's line on the strand's axis: springs (``CENTRING_STIFFNESS`` per metre of core) on each core
node's offset from the ring's centre, in x and y (the offset starts at zero and the ring's own motions,
a uniform contraction, an ovalisation, a turn about the core, leave it there; only the ring's
drift off the core loads them). They carry the strut's transverse load T κ (20 kN/m at 40 kN and
0.5 1/m) to the ring, as the core's contacts do when they are closed.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

__all__ = ["CoreCentring", "CENTRING_STIFFNESS"]

Array = npt.NDArray[np.float64]

#: N/m per metre of core (N/m²): of the order of a closed Hertz line contact's stiffness per
#: metre (1e10–1e11 N/m² for steel wires at the tensions of a strand), and 30 times what holds a
#: column of EI = 1.28 N m² (Cardinal's steel core) under 40 kN on an elastic foundation,
#: T²/(4 EI) = 3.1e8 N/m²: the core drifts 2 µm off the ring's axis under 20 kN/m
CENTRING_STIFFNESS = 1e10


class CoreCentring:
    """Linear springs k_p on the lateral (x, y) offset r_p = Σ_k c_pk u(s_pk) of each core node
    from its ring's centre: residual k_p r_p c_pk on node s_pk, tangent k_p c_pk c_pl. A
    ``PairTerms`` on (P, m) local dof blocks ``stencils`` (the core node first) with weights
    ``weights`` (P, m) and stiffness ``stiffness`` (P,) or one for all (N/m)."""

    def __init__(
        self, stencils: npt.ArrayLike, weights: npt.ArrayLike, stiffness: npt.ArrayLike
    ) -> None:
        self.stencils = np.ascontiguousarray(stencils, dtype=np.int32)
        self.weights = np.asarray(weights, dtype=float).reshape(self.stencils.shape)
        P, m = self.stencils.shape
        self.k = np.broadcast_to(np.asarray(stiffness, float), (P,)).copy()
        #: the x and y dofs of each stencil node, in the layout of the residual and tangent
        self.dofs = (6 * np.arange(m)[:, None] + np.arange(2)).ravel()
        cc = self.weights[:, :, None] * self.weights[:, None, :] * self.k[:, None, None]
        K = np.einsum("pij,cd->picjd", cc, np.eye(2))
        self._K = K.reshape(P, 2 * m, 2 * m)

    def offsets(self, w: Array) -> Array:
        """The core nodes' lateral offsets from their rings' centres (P, 2), m."""
        return np.einsum("pk,pkc->pc", self.weights, w[self.stencils][:, :, :2])

    def evaluate(self, w: Array, jacobian: bool) -> tuple[Array, Array | None]:
        r = self.offsets(w) * self.k[:, None]
        f = (self.weights[:, :, None] * r[:, None, :]).reshape(len(r), -1)
        return f, (self._K.copy() if jacobian else None)

    def commit(self) -> None:
        pass

    def rollback(self) -> None:
        pass
