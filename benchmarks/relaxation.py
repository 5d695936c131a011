"""One load step solved by the relaxation alone (pseudo-transient continuation,
``Stabiliser.relaxed_solve``), from a run's checkpoint: its pseudo-time steps and where it moved
the strand.

Run: [.venv/bin/mpirun -n 2] .venv/bin/python benchmarks/relaxation.py CASE CHECKPOINT
[--increment N] [--stiffness C] [--steps S] [--set key=value …] [--quick]
(--quick: the quick 1+6, pulled to 500 N here, relaxed to 1 kN)

Puts CHECKPOINT (the ``checkpoint.h5`` of a tension stage run of CASE with the same ``--set``)
into the problem, adds ``--increment`` (N) to the tension and solves that step by the relaxation
alone, from the first stiffness ``--stiffness`` (N/m) for at most ``--steps`` pseudo-time steps
(``[steps] relax``, theory §6). Prints each pseudo-time step (the springs, Newton's iterations,
the springs' force: the strand's own residual), the outcome, and per layer the largest change of
radial, hoop and axial displacement (µm) and of rotation (mrad) from the checkpoint's state.
E.g. the vaulted ring's stall: ``benchmarks/state_changes.py --case cases/cardinal_bending.toml
--set 'contact.first_layer="ring"' --set output.checkpoint=true``, then this script on
``results/state_changes_2/checkpoint.h5`` with the same ``--set``.
"""

import strand  # noqa: F401

# isort: split

import io
import time

import numpy as np
from harness import ROOT, add_settings, parser, stamp, table
from mpi4py import MPI

from strand.app.build import build_problem, restart_from, setup_and_programme
from strand.app.case import load_case
from strand.app.kind_registry import lookup
from strand.model.checkpoint import read_checkpoint
from strand.solver import Stabiliser


def layer_moves(problem, w0: np.ndarray) -> list[list[str]]:
    """Per layer: the largest |Δ| of the radial, hoop and axial displacement (µm) and of the
    rotation (mrad) since ``w0``, over all ranks; on the axis (the core), the lateral
    displacement's magnitude in the radial column, none in the hoop one."""
    model, g = problem.model, problem.geometry
    pts = model.owned_points
    d = (problem.solver.w.x.array - w0).reshape(-1, 6)[model.i2b[pts]]
    x = g.points[pts]
    r = np.linalg.norm(x[:, :2], axis=1)
    axis = r < 1e-9 * g.length  # the core: no radial direction
    r = np.where(axis, 1.0, r)
    c, s = x[:, 0] / r, x[:, 1] / r
    radial, hoop = d[:, 0] * c + d[:, 1] * s, -d[:, 0] * s + d[:, 1] * c
    radial[axis], hoop[axis] = np.linalg.norm(d[axis, :2], axis=1), 0.0
    layer = g.wire_layer[g.point_wire[pts]]
    rows = []
    for i in range(len(g.cable.layers)):
        k = layer == i
        local = [np.abs(v[k]).max(initial=0.0) for v in (radial, hoop, d[:, 2])]
        local.append(np.abs(d[k, 3:]).max(initial=0.0))
        top = np.empty(4)
        model.comm.Allreduce(np.array(local), top, op=MPI.MAX)
        rows.append([str(i), *(f"{v * 1e6:.2f}" for v in top[:3]), f"{top[3] * 1e3:.3f}"])
    return rows


def main(case_file, checkpoint, increment, stiffness, steps, settings, quick) -> None:
    comm = MPI.COMM_WORLD
    rank0 = comm.rank == 0
    case = load_case(case_file, ["output.fields=false", *settings])
    problem, _ = build_problem(case, stream=io.StringIO())
    setup = problem.setup
    if quick:  # pulled here, not read from a checkpoint
        for tension in (200.0, 500.0):
            setup.set("tension", tension)
            assert problem.solver.solve().converged
            problem.solver.commit()
    else:
        _, programme = setup_and_programme(case, lookup(case.load.kind))
        restart_from(problem, programme, read_checkpoint(checkpoint), checkpoint)
    start = setup.get("tension")
    setup.set("tension", start + increment)
    w0 = problem.solver.w.x.array.copy()
    lines = []
    stabiliser = Stabiliser(
        [],
        problem.model.strain_energy,
        comm,
        newton=problem.solver,
        relaxation=stiffness,
        length=problem.geometry.cable.largest_wire_diameter,
        relaxation_steps=steps,
        report=lambda line: lines.append(f"{time.strftime('%X')} {line}"),
    )
    t0 = time.perf_counter()
    result = stabiliser.relaxed_solve()
    seconds = time.perf_counter() - t0
    moves = layer_moves(problem, w0)
    if not rank0:
        return
    print(f"stamp: {stamp()}")
    print("\n".join(lines))
    print(
        f"{start:.6g} → {start + increment:.6g} N: "
        f"{'converged' if result.converged else 'FAILED'} after {len(lines)} pseudo-time "
        f"steps, {result.iterations} Newton iterations, {result.factorisations} LUs, "
        f"{seconds:.0f} s on {comm.size} rank(s) ({result.reason})"
    )
    print(
        table(
            moves,
            ["layer", "max|radial| µm", "max|hoop| µm", "max|axial| µm", "max|rotation| mrad"],
            plain=True,
        )
    )


if __name__ == "__main__":
    cli = parser(__doc__, "the quick 1+6 pulled to 500 N, relaxed to 1 kN")
    cli.add_argument("case", nargs="?", help="the case file of the checkpoint's run")
    cli.add_argument("checkpoint", nargs="?", help="its checkpoint.h5")
    cli.add_argument("--increment", type=float, default=17.8, help="N added to the tension")
    cli.add_argument("--stiffness", type=float, default=1e5, help="first springs, N/m")
    cli.add_argument("--steps", type=int, default=100, help="pseudo-time steps at most")
    add_settings(cli)
    args = cli.parse_args()
    if args.quick:
        args.case, args.increment, args.steps = str(ROOT / "cases/quick_1x6.toml"), 500.0, 20
    elif not (args.case and args.checkpoint):
        cli.error("give CASE and CHECKPOINT (or --quick)")
    main(
        args.case,
        args.checkpoint,
        args.increment,
        args.stiffness,
        args.steps,
        args.settings,
        args.quick,
    )
