"""Who writes what in a distributed run: rank 0 writes the files a serial run writes.

Every rank runs the same code (set-up, solve, recorders, post-processing), so that collective
calls (gathers of nodal values, pair and cell results; the field writers) line up. The files
that are not collective (CSV tables, histories, summary, figures) are opened on rank 0 only:
``root_open`` hands the other ranks a sink. Checks that touch the disk (the results folder) run
once on rank 0 and their verdict, error included, is shared with ``on_root``.
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable
from pathlib import Path

from mpi4py import MPI

__all__ = ["is_root", "root_open", "on_root", "root_stream", "serial_only", "abort_on_error"]


def is_root(comm: MPI.Comm = MPI.COMM_WORLD) -> bool:
    """Whether this rank writes the run's files (rank 0)."""
    return comm.rank == 0


def root_open(path: str | Path, mode: str = "w", comm: MPI.Comm = MPI.COMM_WORLD, **kwargs):
    """``open(path, mode)`` on rank 0; on the other ranks a sink (``os.devnull``)."""
    return open(path if is_root(comm) else os.devnull, mode, **kwargs)


def root_stream(stream, comm: MPI.Comm = MPI.COMM_WORLD):
    """``stream`` on rank 0 (progress lines are printed once); a sink on the other ranks."""
    return stream if is_root(comm) else open(os.devnull, "w")  # noqa: SIM115


def on_root[T](task: Callable[[], T], comm: MPI.Comm = MPI.COMM_WORLD) -> T:
    """Run ``task`` on rank 0 and return its result on every rank; an exception it raises is
    raised on every rank (so that all stop with the same one-line error, none hangs)."""
    if comm.size == 1:
        return task()
    outcome: tuple[bool, object] | None = None
    if is_root(comm):
        try:
            outcome = (True, task())
        except Exception as e:  # shared, then raised everywhere
            outcome = (False, e)
    ok, value = comm.bcast(outcome, root=0)
    if not ok:
        raise value
    return value


def serial_only(what: str, comm: MPI.Comm = MPI.COMM_WORLD) -> None:
    """Stop a script that runs on one process only when started on several ranks: one line
    (from rank 0) and exit code 2 on every rank, before any computing."""
    if comm.size > 1:
        if is_root(comm):
            print(f"strand: {what} runs on one process: start it without mpirun", file=sys.stderr)
        raise SystemExit(2)


def abort_on_error(comm: MPI.Comm = MPI.COMM_WORLD) -> None:
    """In a distributed run, make an exception that escapes on one rank end every rank: print
    its traceback, then ``comm.Abort(1)``. Without it the other ranks wait for that rank at
    their next collective call, for ever (e.g. an error in what rank 0 alone writes)."""
    if comm.size == 1 or getattr(sys.excepthook, "aborts", False):
        return
    previous = sys.excepthook

    def hook(kind, value, traceback):
        previous(kind, value, traceback)
        sys.stderr.flush()
        # mpirun forwards the ranks' output through its proxies, which the abort may stop
        # before they have read it all: on a loaded machine the traceback's last line (the
        # error itself) was once lost. Half a second lets them catch up.
        time.sleep(0.5)
        comm.Abort(1)

    hook.aborts = True  # type: ignore[attr-defined]  # marks strand's hook
    sys.excepthook = hook
