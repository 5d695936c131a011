"""The main job: a strand pulled to its tension, then cycled by its test set-up's load.

``run_case`` builds the strand of a ``Case``, its test set-up and load programme, and runs them
with per-step recorders that write as the run goes (so that a failed step loses nothing):

* ``fields.xdmf`` (+ ``.h5``) and ``fields.bp`` (VTX) — u, θ, section forces and wire/layer ids at
  every converged step, at the programme time (stage k runs from t = k to k + 1);
* ``steps.csv`` — every converged step: stage, time, loads, the set-up's measures, Newton's
  iterations and final residual;
* ``axial_forces.csv`` — the axial force of every element (wire, layer, z, φ) at every step;
* ``moment_curvature.csv`` — the set-up's bending measures at every step of the cycle;
* PNG figures at the end (``plots.results_figures``) and ``summary.txt``.

The folder is checked before any computing, written only once the strand is built (a case that
fails to build leaves it as it was), and never mixes two runs (``folder.py``). Ctrl-C
stops the run at the last converged step, with its summary and figures.

The jobs are modules of their own, their main names importable from here too: ``strand.app.build``
(the folder, the problem and its programme, a restart's state), ``strand.app.runner`` (the programme
with the recorders, then the summary, fatigue report and figures), ``strand.app.sweep``,
``strand.app.summary`` and ``strand.app.run_result`` (the records a run returns); what depends on
the set-up's kind comes from its module in ``strand.app.kinds``.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from forms import ReissnerBeam

from ..beam.parallel import root_stream
from ..model.checkpoint import read_checkpoint
from ..model.model import BeamFactory
from .build import build_problem as build_problem
from .build import check_folder, restart_from, results_folder
from .build import setup_and_programme as setup_and_programme
from .kinds import SetupKind, kind_of
from .run_result import RunResult as RunResult
from .run_result import Start as Start
from .runner import run_programme_with_outputs
from .settings import Case
from .summary import summarize as summarize
from .sweep import run_sweep as run_sweep

__all__ = ["run_case"]


def run_case(
    case: Case,
    folder: str | Path | None = None,
    stream=None,
    overwrite: bool = False,
    restart: str | Path | None = None,
    *,
    kind: SetupKind | None = None,
    beam: BeamFactory = ReissnerBeam,
) -> RunResult:
    """Run ``case``; outputs go to ``folder`` (default: the case's output folder), which must be
    new or empty, or hold an earlier run to be replaced with ``overwrite`` (``FolderError``
    otherwise, raised before any computing). ``restart``: a checkpoint (``checkpoint.h5`` of an
    earlier run of the same strand) to continue from, with this case's load programme; the new
    folder's first step is the checkpoint's state. ``kind``: the case's set-up kind (None:
    ``kinds.kind_of(case)``), resolved once here and carried through the run. ``beam``: the
    wires' beam law, called as ``beam(w, section)`` (``StrandModel``; default
    ``ReissnerBeam``), for a script that runs a case with a law of its own."""
    stream = root_stream(stream or sys.stdout)  # printed once in a distributed run
    t_start = time.perf_counter()
    checkpoint = None
    if restart is not None:
        checkpoint = read_checkpoint(restart)
    folder = folder or case.output.folder
    check_folder(case, folder, overwrite)  # refused before anything is built
    kind = kind_of(case) if kind is None else kind
    problem, programme = build_problem(case, stream, kind=kind, beam=beam)
    try:
        start = (
            None if checkpoint is None else restart_from(problem, programme, checkpoint, restart)
        )
        # written once the strand is built and restored: a case that cannot be leaves it be
        folder = results_folder(case, folder, overwrite, restart)
        return run_programme_with_outputs(
            case, problem, programme, folder, stream, start, t_start, kind=kind
        )
    finally:
        problem.solver.destroy()
