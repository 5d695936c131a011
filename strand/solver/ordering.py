"""The MUMPS ordering that factorises a sparsity pattern in the fewest operations.

The fill of an LU factorisation is a property of the matrix's graph and the elimination order;
which of MUMPS's orderings (``ICNTL(7)``) fills least depends on the graph. A strand's graph is a
rod: its wires run along the axis, coupled at crossings and, with same-layer contact, to their
neighbours at every node. Measured on Cardinal with packed layers (the counts each run prints in
its first lines, ``strand run cardinal``): over 0.5 m (65,034 unknowns) PORD needs 2.5e10
operations per LU and AMF 2.7e10; over 1 m (129,492) PORD needs 6.2e10 and AMF 5.3e10.
So neither is best for every strand, and ``cheapest_ordering`` factorises the pattern once with each
candidate and keeps the cheapest.

The values are replaced by those of a symmetric, strictly diagonally dominant matrix on the same
pattern, so that no pivot is delayed and the operation count (MUMPS's ``RINFOG(3)``) is the
pattern's alone: the same on every run, whatever the state.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from petsc4py import PETSc

__all__ = ["ORDERINGS", "cheapest_ordering", "factorisation_flops", "mumps_lu", "pattern_lu"]

#: MUMPS's sequential orderings (``ICNTL(7)``) by name
ORDERINGS = {"amd": 0, "amf": 2, "scotch": 3, "pord": 4, "metis": 5, "qamd": 6}


def mumps_lu(A: PETSc.Mat, icntl: dict[int, int]) -> tuple[PETSc.KSP, PETSc.Mat]:
    """A KSP that factorises ``A`` by MUMPS's LU (set up at ``ksp.setUp()``) and its factor
    matrix, with MUMPS's ``ICNTL`` values ``icntl``; the caller destroys the KSP."""
    ksp = PETSc.KSP().create(A.comm)
    ksp.setOperators(A)
    ksp.setType("preonly")
    pc = ksp.getPC()
    pc.setType("lu")
    pc.setFactorSolverType("mumps")
    pc.setFactorSetUpSolverType()
    F = pc.getFactorMatrix()
    for k, v in icntl.items():
        F.setMumpsIcntl(k, v)
    return ksp, F


def pattern_lu(A: PETSc.Mat, ordering: int) -> tuple[float, float]:
    """MUMPS's operations (``RINFOG(3)``) and factor entries (``INFOG(29)``) of the LU of
    ``A``'s sparsity pattern with ``ICNTL(7) = ordering``, its values replaced by a diagonally
    dominant matrix (module docstring). Collective on ``A``'s communicator."""
    B = A.duplicate(copy=False)
    try:
        ia, ja, _ = A.getValuesCSR()
        B.setValuesCSR(ia, ja, np.full(len(ja), -1e-3))
        B.assemble()
        B.shift(1.0)
        # ICNTL(14): strand.model.problem's distributed workspace
        icntl = {7: ordering, **({14: 100} if A.comm.size > 1 else {})}
        ksp, F = mumps_lu(B, icntl)
        try:
            ksp.setUp()
            return float(F.getMumpsRinfog(3)), float(F.getMumpsInfog(29))
        finally:
            ksp.destroy()
    finally:
        B.destroy()


def factorisation_flops(A: PETSc.Mat, ordering: int) -> float:
    """MUMPS's operations for the LU of ``A``'s pattern with ``ICNTL(7) = ordering``
    (``pattern_lu``)."""
    return pattern_lu(A, ordering)[0]


def cheapest_ordering(
    A: PETSc.Mat, candidates: Sequence[str] = ("pord", "amf")
) -> tuple[str, dict[str, float]]:
    """The ordering among ``candidates`` (names of ``ORDERINGS``) whose LU of ``A``'s pattern
    takes the fewest operations (ties: the first), and every candidate's count."""
    unknown = [c for c in candidates if c not in ORDERINGS]
    if unknown or not candidates:
        raise ValueError(f"MUMPS orderings {unknown}: choose among {sorted(ORDERINGS)}")
    flops = {c: factorisation_flops(A, ORDERINGS[c]) for c in candidates}
    return min(flops, key=flops.get), flops
