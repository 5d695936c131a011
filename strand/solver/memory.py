"""Freed memory kept in the process, so that each LU factorisation does not fault it in again.

MUMPS allocates its workspace at every numerical factorisation and frees it after. glibc's
``malloc`` serves blocks above a threshold (128 kB, rising to at most 32 MB) with ``mmap`` and
hands them back with ``munmap``, and trims the top of its heap: the next factorisation then
touches fresh pages, each a page fault that the kernel zeroes. ``keep_freed_memory`` raises both
thresholds (``mallopt``), so that freed blocks are reused. The process keeps its peak memory
instead of returning it between factorisations. ``benchmarks/freed_memory.py`` measures it.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os

__all__ = ["keep_freed_memory"]

#: ``mallopt`` parameters (glibc's malloc.h)
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3
#: 1 GiB: above any one MUMPS workspace of the strands run here, within ``mallopt``'s int
THRESHOLD = 1 << 30
#: set to "0" to leave glibc's defaults (benchmarks/freed_memory.py compares the two)
ENVIRONMENT = "STRAND_KEEP_FREED_MEMORY"


def keep_freed_memory(threshold: int = THRESHOLD) -> bool:
    """Ask glibc's ``malloc`` to serve blocks of up to ``threshold`` bytes from its heap and to
    keep freed memory rather than return it to the system; for the rest of the process. Returns
    whether it applied: False where the C library is not glibc, or where ``STRAND_KEEP_FREED_MEMORY``
    is "0"."""
    if os.environ.get(ENVIRONMENT, "1") == "0":
        return False
    name = ctypes.util.find_library("c")
    try:
        mallopt = ctypes.CDLL(name).mallopt
    except (OSError, AttributeError, TypeError):  # no C library found, or no mallopt (not glibc)
        return False
    mallopt.argtypes, mallopt.restype = (ctypes.c_int, ctypes.c_int), ctypes.c_int
    return bool(mallopt(_M_MMAP_THRESHOLD, threshold)) and bool(
        mallopt(_M_TRIM_THRESHOLD, threshold)
    )
