"""strand: wire-by-wire FEniCSx simulation of spiral strand cables.

Units are SI throughout: m, N, Pa, rad (contact stiffnesses in N/m).
"""

from __future__ import annotations

try:  # the PyPI wheel of dolfinx must load its MPI/PETSc libraries first
    import dolfinx_solver  # noqa: F401
except ImportError:  # conda/apt dolfinx: nothing to do
    pass

__version__ = "0.1.0"
