"""What the benchmark scripts share: their argument parser, the stamp line, table printing, peak
memory, and the runs of named variants each in a process of its own.

A script in this folder imports it as ``from harness import …`` (the script's folder is first on
Python's path when it runs). It imports nothing of strand, dolfinx or MPI: mpi4py only where a
communicator is passed in.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shlex
import subprocess
import sys
import time
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def parser(doc: str, quick: str) -> argparse.ArgumentParser:
    """A script's argument parser: its docstring ``doc`` as the description (the first
    paragraph) and the epilog (the rest, its ``Run:`` line on, as written), and ``--quick``,
    the same code path on the smallest problem that takes it, as a smoke test of the script
    (its numbers mean nothing); ``quick`` says what that runs."""
    first, _, rest = doc.strip().partition("\n\n")
    out = argparse.ArgumentParser(
        description=first,
        epilog=rest,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    out.add_argument("--quick", action="store_true", help=f"a smoke test: {quick}")
    return out


def add_settings(parser: argparse.ArgumentParser, example: str = "load.lateral=1000") -> None:
    """``--set section.key=value`` (repeated, as ``strand run --set``) into ``settings``."""
    parser.add_argument(
        "--set",
        dest="settings",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help=f"a case setting, as strand run --set (e.g. {example}); repeat for more",
    )


def _git(*args: str) -> str:
    done = subprocess.run(["git", "-C", str(ROOT), *args], capture_output=True, text=True)
    return done.stdout.strip() if done.returncode == 0 else ""


def stamp(command: Sequence[str] | None = None) -> str:
    """The line that stamps a table: date and time, the commit of this tree (``modified`` if
    tracked files differ from it), the machine's cores, and the command (default: this
    process's, ``python benchmarks/<script> …``)."""
    if command is None:
        script = Path(sys.argv[0])
        where = (
            f"benchmarks/{script.name}"
            if script.parent.resolve() == ROOT / "benchmarks"
            else str(script)
        )
        command = ["python", where, *sys.argv[1:]]
    commit = _git("rev-parse", "--short", "HEAD") or "unknown"
    dirty = _git("status", "--porcelain", "--untracked-files=no")
    return (
        f"{time.strftime('%Y-%m-%d %H:%M')}, commit {commit}{' (modified)' if dirty else ''}, "
        f"{os.cpu_count()} cores, `{shlex.join(command)}`"
    )


def table(
    rows: Iterable[Sequence], columns: Sequence[str], plain: bool = False, head: bool = True
) -> str:
    """``rows`` (each a sequence of cells, shown with ``str``) under ``columns``. Markdown
    (``| a | b |`` under a ``|---|`` line; ``head=False``: the rows alone, for a table printed a
    row at a time) or, with ``plain``, columns padded to their widest cell, the first aligned
    left and the others right."""
    cells = [[str(c) for c in row] for row in rows]
    for row in cells:
        if len(row) != len(columns):
            raise ValueError(f"a row of {len(row)} cells under {len(columns)} columns: {row}")
    if not plain:
        lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)] if head else []
        return "\n".join(lines + ["| " + " | ".join(row) + " |" for row in cells])
    widths = [max(len(c) for c in column) for column in zip(columns, *cells, strict=True)]

    def line(row: Sequence[str]) -> str:
        return " ".join(
            c.ljust(w) if i == 0 else c.rjust(w)
            for i, (c, w) in enumerate(zip(row, widths, strict=True))
        ).rstrip()

    return "\n".join(([line(columns)] if head else []) + [line(row) for row in cells])


def peak_mib(comm=None) -> float:
    """This process's peak resident memory (MiB, ``ru_maxrss``); with an MPI communicator, the
    largest of its ranks' (collective)."""
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    if comm is None:
        return peak
    from mpi4py import MPI

    return comm.allreduce(peak, op=MPI.MAX)


def print_result(measured: dict, comm=None) -> None:
    """A variant's side of :func:`run_variants`: its measurements as one JSON line, on rank 0."""
    if comm is None or comm.rank == 0:
        print(json.dumps(measured), flush=True)


def run_variants(
    script: str | Path,
    names: Sequence[str],
    args: Sequence[str] = (),
    ranks: Callable[[str], int] | int = 1,
    env: Callable[[str], dict[str, str] | None] | None = None,
) -> dict[str, dict]:
    """Run each named variant in a process of its own, one after the other, so that each has the
    machine and its own peak memory: ``[mpirun -n <ranks>] python <script> <args> --one <name>``
    (``ranks`` and ``env`` per name, or one rank count for all), the variant printing its
    measurements with :func:`print_result`. Returns them by name; stops at the first failure
    with the end of its error output."""
    mpirun = [str(Path(sys.executable).parent / "mpirun")]
    out = {}
    for name in names:
        n = ranks(name) if callable(ranks) else ranks
        command = [
            *([*mpirun, "-n", str(n)] if n > 1 else []),
            sys.executable,
            str(script),
            *args,
            "--one",
            name,
        ]
        print(f"running: {name} …", file=sys.stderr, flush=True)
        done = subprocess.run(
            command, capture_output=True, text=True, env=env(name) if env else None
        )
        if done.returncode != 0:
            print(done.stderr[-3000:], file=sys.stderr)
            raise SystemExit(f"{name}: failed (exit code {done.returncode})")
        out[name] = json.loads(done.stdout.strip().splitlines()[-1])
    return out
