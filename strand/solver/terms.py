"""Residual and tangent terms assembled outside UFL (contact pairs, links, nodal loads).

A term set owns a fixed array of node stencils and returns, for the current state, all its
residual vectors and tangent blocks at once (numpy arrays): the ``PairTerms`` protocol.
``create_extended_matrix`` gives the Jacobian a sparsity pattern that holds the stencils, and
``PairAssembler`` adds the terms to what dolfinx assembles from the forms, with the Dirichlet dofs
masked and the stencils' coupling to prescribed motions lifted onto the free rows (as dolfinx's
``apply_lifting`` does for the forms). A residual alone (a line search's trial point) is evaluated
without the tangent blocks; the Jacobian adds them.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from typing import NamedTuple, Protocol

import dolfinx
import numpy as np
import numpy.typing as npt
from dolfinx import fem
from petsc4py import PETSc

__all__ = ["PairTerms", "NodalLoad", "PairAssembler", "EvaluatedTerms", "create_extended_matrix"]

Array = npt.NDArray[np.float64]


class PairTerms(Protocol):
    """Residual and tangent contributions assembled outside UFL, e.g. contact pairs.

    ``stencils`` is a fixed (P, k) int32 array of local dof-block (node) indices: term p couples
    the nodes ``stencils[p]``. ``evaluate(w)`` receives the local nodal values (n_blocks, 6) of the
    current iterate (ghosts included) and returns the residual contributions f (P, 6k) and, when
    ``jacobian`` is true, the tangent blocks K = ∂f/∂w (P, 6k, 6k), or None for state-independent
    terms. Each rank returns each term once. ``commit``/``rollback`` accept or discard the history
    built since the last converged step. ``evaluate`` may be called at one w without, then with
    the tangent: the residual must be the same (a function of w and the committed history).

    A term set whose blocks are sparse within the stencil may declare ``dofs`` (m,): the positions
    (in 0..6k) of the stencil dofs that f (P, m) and K (P, m, m) hold; the others are zero and are
    neither computed nor inserted (e.g. the rotations of nodes that enter through positions only).

    A term set may declare ``owned_only = True``: its terms whose first node is a ghost on this
    rank are dropped, since the rank owning that node adds them. It may then be given every
    local node, ghosts included (what ``fem.locate_dofs_*`` and ``locate_nodes`` return), and
    still counts each term once over the ranks.
    """

    stencils: npt.NDArray[np.int32]
    # optional: dofs: npt.NDArray[np.intp]

    def evaluate(self, w: Array, jacobian: bool) -> tuple[Array, Array | None]: ...

    def commit(self) -> None: ...

    def rollback(self) -> None: ...


class NodalLoad:
    """External nodal forces/moments F (n, 6) on nodes ``blocks`` (n,), scaled by ``factor``.

    Its residual contribution is −factor·F (the residual is internal minus external forces).
    ``blocks`` are local dof blocks, ghosts allowed: a node is loaded once, by the rank owning it
    (``owned_only``).
    """

    owned_only = True

    def __init__(self, blocks: npt.ArrayLike, values: npt.ArrayLike, factor: float = 0.0):
        self.stencils = np.asarray(blocks, dtype=np.int32).reshape(-1, 1)
        self.values = np.asarray(values, dtype=np.float64).reshape(-1, 6)
        if len(self.values) != len(self.stencils):
            raise ValueError("NodalLoad: one 6-vector of forces/moments per node is needed")
        self.factor = factor

    def evaluate(self, w: Array, jacobian: bool) -> tuple[Array, None]:
        return -self.factor * self.values, None

    def commit(self) -> None:
        pass

    def rollback(self) -> None:
        pass


def create_extended_matrix(J: fem.Form, stencils: Sequence[npt.ArrayLike]) -> PETSc.Mat:
    """The Jacobian matrix of ``J`` with its sparsity pattern extended by every stencil's k×k node
    couplings, primed with zeros so that the first assembly does not squeeze the extra slots out
    (PETSc error 63, "new nonzero caused a malloc", at the first pair insertion otherwise)."""
    sp = fem.create_sparsity_pattern(J)
    for s in stencils:
        s = np.asarray(s, dtype=np.int32)
        if s.shape[1] >= 2:
            for row in np.unique(np.sort(s, axis=1), axis=0):
                sp.insert(row, row)
    sp.finalize()
    A = dolfinx.cpp.la.petsc.create_matrix(J.mesh.comm, sp, None)
    A.setOption(PETSc.Mat.Option.NEW_NONZERO_ALLOCATION_ERR, True)
    cols, offsets = sp.graph
    A.setValuesBlockedLocalCSR(offsets.astype(np.int32), cols, np.zeros(len(cols) * 36))
    A.assemble()
    return A


class EvaluatedTerms(NamedTuple):
    """One term set at one state: local dof indices ``idx`` (P, m), residuals ``f`` (P, m) and
    tangents ``K`` (P, m, m) with the Dirichlet dofs masked (and lifted), the stencils ``rows``
    touching a Dirichlet dof and their unmasked residuals ``f_rows`` (for the reactions).
    ``tangent``: whether the tangent was asked for (K None then means a state-independent set)."""

    idx: npt.NDArray[np.int32]
    f: Array
    K: Array | None
    rows: npt.NDArray[np.intp]
    f_rows: Array
    tangent: bool = True


class PairAssembler:
    """The pair terms of a problem with Dirichlet conditions ``bcs`` on the blocked space ``V``:
    evaluates them once per state, masks them, and adds them to a vector or a matrix.

    A residual alone is evaluated without the tangent blocks (``evaluate(..., tangent=False)``),
    except for a term set whose stencils touch a Dirichlet dof that is not yet at its prescribed
    value: its lifting needs K there, so it is evaluated whole, and the residual is the one the
    full evaluation gives. A later request for the tangent at the same state evaluates the sets
    that lack it, once (a set's ``evaluate`` must then give the same residual again: a function
    of the unknowns and the committed history).
    """

    def __init__(
        self, terms: Sequence[PairTerms], bcs: Sequence[fem.DirichletBC], V: fem.FunctionSpace
    ):
        self.terms = list(terms)
        self.bcs = list(bcs)
        # Dirichlet mask over local dofs (ghosts included): contributions there are dropped.
        n_local = V.dofmap.index_map.size_local + V.dofmap.index_map.num_ghosts
        self._n_owned = V.dofmap.index_map.size_local
        self._bc_mask = np.zeros(6 * n_local, dtype=bool)
        for bc in self.bcs:
            dofs, _ = bc.dof_indices()
            self._bc_mask[dofs] = True
        self._cache: tuple[Array, list[EvaluatedTerms]] | None = None
        self._layouts: list | None = None

    @property
    def bc_mask(self) -> npt.NDArray[np.bool_]:
        """The Dirichlet dofs among the local ones, ghosts included (6 per node)."""
        return self._bc_mask

    def evaluate(
        self, wl: Array, timings: dict[str, float], tangent: bool = True
    ) -> list[EvaluatedTerms]:
        """Every term set at the local unknowns ``wl`` (ghosts included), Dirichlet dofs masked,
        with its tangent blocks if ``tangent``; the seconds spent go to ``timings["terms"]``.
        Each set is evaluated once per state (SNES asks for the residual, then the Jacobian at
        the same w), and a second time only to add the tangent it was first evaluated without.
        Counts the terms (stencils) evaluated with their tangent in ``timings["tangent_terms"]``,
        those evaluated without in ``timings["residual_terms"]``."""
        cached = None
        if self._cache is not None and np.array_equal(self._cache[0], wl):
            cached = self._cache[1]
            if not tangent or all(e.tangent for e in cached):
                return cached
        t0 = time.perf_counter()
        wn = wl.reshape(-1, 6)
        layouts = self._term_layouts()
        # g − w at the Dirichlet dofs, for the stencils that touch one (few: rows)
        lift = self._prescribed_increment(wl) if any(len(lay[1]) for lay in layouts) else None
        out = []
        for i, (t, layout) in enumerate(zip(self.terms, layouts, strict=True)):
            if cached is not None and cached[i].tangent:
                out.append(cached[i])
            else:
                out.append(self._evaluate_set(t, layout, wn, lift, tangent))
                key = "tangent_terms" if out[-1].tangent else "residual_terms"
                timings[key] = timings.get(key, 0) + len(layout[0])
        self._cache = (wl.copy(), out)
        timings["terms"] += time.perf_counter() - t0
        return out

    @staticmethod
    def _evaluate_set(
        t: PairTerms, layout: tuple, wn: Array, lift: Array | None, tangent: bool
    ) -> EvaluatedTerms:
        """One term set at the nodal unknowns ``wn`` (n_blocks, 6), masked and lifted; with its
        tangent if ``tangent`` or if its lifting needs it (``lift``: g − w, local)."""
        idx, rows, mask, ghosts = layout
        d = None
        if len(rows):  # only the few stencils that touch a Dirichlet dof
            d = np.where(mask, lift[idx[rows]], 0.0)
            tangent = tangent or bool(np.any(d != 0.0))  # the lifting needs K
        with np.errstate(all="ignore"):  # a wild iterate's inf/nan stops SNES, then a cut
            f, K = t.evaluate(wn, tangent)
        if not tangent:
            K = None
        if len(ghosts):  # owned_only: the owner of their first node adds these
            f = f.copy()
            f[ghosts] = 0.0
            if K is not None:
                K = K.copy()
                K[ghosts] = 0.0
        f_rows = f[rows].copy()  # unmasked, for the reactions
        if len(rows):
            if K is not None:
                # lifting, as dolfinx's apply_lifting does for the forms: the free rows get
                # K_fb (g − w_b), so that the step that moves the prescribed dofs to their
                # values moves the others with them (Newton stays quadratic). Without K,
                # d = 0: the lift adds nothing
                f[rows] += np.einsum("pij,pj->pi", K[rows], d)
                K[rows] = np.where(mask[:, :, None] | mask[:, None, :], 0.0, K[rows])
            f[rows] = np.where(mask, 0.0, f[rows])
        return EvaluatedTerms(idx, f, K, rows, f_rows, tangent)

    def forget(self) -> None:
        """Drop the last evaluation (the terms' state changed without the unknowns changing)."""
        self._cache = None

    @staticmethod
    def add_residuals(local: Array, evaluated: list[EvaluatedTerms], reactions=False) -> None:
        """Add the terms' residuals to the local form ``local`` (ghosts included) of a vector;
        ``reactions``: unmasked, as they act on the supports."""
        for e in evaluated:
            f = e.f
            if reactions:
                f = f.copy()
                f[e.rows] = e.f_rows
            local += np.bincount(e.idx.ravel(), weights=f.ravel(), minlength=len(local))

    @staticmethod
    def add_tangents(A: PETSc.Mat, evaluated: list[EvaluatedTerms]) -> None:
        """Add the terms' tangent blocks to ``A`` (local indices; assembled by the caller)."""
        for e in evaluated:
            if e.K is not None and len(e.idx):
                A.setValuesLocalRCV(
                    e.idx, e.idx, np.ascontiguousarray(e.K), addv=PETSc.InsertMode.ADD_VALUES
                )

    def commit(self) -> None:
        """Accept every term set's history since the last converged step."""
        for t in self.terms:
            t.commit()

    def rollback(self) -> None:
        """Discard every term set's history since the last converged step."""
        for t in self.terms:
            t.rollback()
        self._cache = None

    def _prescribed_increment(self, wl: Array) -> Array:
        """g − w at the Dirichlet dofs (local, ghosts included), zero elsewhere."""
        d = np.zeros_like(wl)
        for bc in self.bcs:
            bc.set(d, x0=wl, alpha=1.0)
        return d

    def _term_layouts(self) -> list:
        """Per term set: local dof indices (P, m) of f and K, the rows (stencils) holding a
        Dirichlet dof, their dof masks, and the rows an ``owned_only`` set drops. Built once."""
        if self._layouts is None:
            self._layouts = []
            for t in self.terms:
                st = np.asarray(t.stencils)
                layout = getattr(t, "dofs", None)
                if layout is None:
                    layout = np.arange(6 * st.shape[1])
                idx = np.ascontiguousarray(6 * st[:, layout // 6] + layout % 6, dtype=np.int32)
                m = self._bc_mask[idx]
                rows = np.flatnonzero(m.any(axis=1))
                ghosts = np.zeros(0, dtype=np.intp)
                if getattr(t, "owned_only", False) and len(st):
                    ghosts = np.flatnonzero(st[:, 0] >= self._n_owned)
                self._layouts.append((idx, rows, m[rows], ghosts))
        return self._layouts
