"""Checkpoints: a converged state of a run, from which a run continues as if never stopped.

What a step starts from is more than the unknowns w. Frictional contact carries history: each
pair's traction, normal and normal force at the last converged step (the return map starts from
them), its friction history (slip, sliding, dissipated energy), and, in large sliding, the
segments its closest points sit on. The load stepper carries the increment it tries next and the
secant predictor's last increments. A ``Checkpoint`` holds all of it, with the loads and the
position in the load programme (``programme.Position``), in the geometry's order (points, pairs),
so that it does not depend on how a mesh was distributed: a state saved on 2 ranks continues on
1 or 3.

``capture`` (collective) takes one from a problem, ``restore`` puts it back; ``write_checkpoint``
stores it in one HDF5 file (rank 0 writes; every rank reads), replaced atomically so that a
crash while writing keeps the previous one. adios4dolfinx, the field's checkpoint library, needs
ADIOS2's Python bindings built with MPI, which the dolfinx wheel this project installs does not
ship; the state here is nodal values and per-pair arrays, which plain HDF5 holds as well.
Units: SI (m, rad, N, J).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import h5py
import numpy as np
import numpy.typing as npt
from mpi4py import MPI

from ..beam.parallel import is_root
from ..solver import RampState
from .programme import Position

__all__ = [
    "Checkpoint",
    "CheckpointError",
    "capture",
    "restore",
    "write_checkpoint",
    "read_checkpoint",
]

Array = npt.NDArray[np.float64]

#: bump when the file layout changes
VERSION = 1


@dataclass
class Checkpoint:
    """A converged state: step ``number`` (steps so far) at programme ``time``, the set-up's
    ``loads`` by parameter, the position in the programme (the ``stage`` under way, the ramp's
    next increment ``step`` and last ``load_increment``, None at none), the nodal unknowns ``w``
    (N, 6) and the ramp's last increment of them ``dw`` (N, 6, or None) in the geometry's point
    order, and the contact history ``pairs`` (per name, arrays over the geometry's pairs) and
    ``same_layer`` (likewise over the same-layer pairs, ``strand.model.same_layer``; empty without),
    and the state's unconstrained ``residual`` (N, 6; the supports' reactions, None if not kept):
    the converged iterate's, which the committed contact history does not give back exactly
    (committing projects each friction traction onto the new tangent plane)."""

    number: int
    time: float
    loads: dict[str, float]
    stage: int
    step: float | None
    load_increment: float | None
    w: Array
    dw: Array | None
    pairs: dict[str, np.ndarray] = field(default_factory=dict)
    same_layer: dict[str, np.ndarray] = field(default_factory=dict)
    residual: Array | None = None


def _block_points(model) -> npt.NDArray[np.int64]:
    """Input point of every local dof block (owned and ghost)."""
    out = np.full(len(model.nodal), -1, dtype=np.int64)
    present = np.flatnonzero(model.i2b >= 0)
    out[model.i2b[present]] = present
    return out


def capture(
    problem, number: int, time: float, position: Position, residual: Array | None = None
) -> Checkpoint:
    """The problem's current (converged, committed) state. Collective. ``residual``: its
    unconstrained residual in the geometry's point order, if already gathered (else computed)."""
    model, setup = problem.model, problem.setup
    ramp = position.ramp
    dw = None
    if ramp is not None and ramp.previous is not None:
        dw = model.gather_nodes(ramp.previous[1].reshape(-1, 6))
    return Checkpoint(
        number,
        time,
        {p: setup.get(p) for p in setup.parameters},
        position.stage,
        None if ramp is None else ramp.step,
        None if ramp is None or ramp.previous is None else ramp.previous[0],
        model.node_values(),
        dw,
        model.gather_pairs([g.history_arrays() for g in model.contact]),
        model.same_layer_history(),
        model.gather_nodes(problem.solver.unconstrained_residual())
        if residual is None
        else residual,
    )


def restore(problem, checkpoint: Checkpoint) -> Position:
    """Put ``checkpoint``'s state into ``problem`` (every rank takes its points and pairs);
    returns the position to continue from, its predictor increments on this rank's blocks."""
    model, setup = problem.model, problem.setup
    if problem.solver.history:
        raise CheckpointError(
            f"the beam law {type(model.beam).__name__} has a state of its own (its history), "
            "which a checkpoint or a kept state does not hold: run it from the start, "
            "without a restart or a [load] sweep"
        )
    points = _block_points(model)
    w = checkpoint.w[points].ravel()
    model.w.x.array[:] = w
    for name, value in checkpoint.loads.items():
        setup.set(name, value)
    for g in model.contact:
        g.restore_history({k: v[g.index] for k, v in checkpoint.pairs.items()}, model.nodal)
    same_layer = model.contact_settings.same_layer != "off"
    if same_layer != bool(checkpoint.same_layer):
        raise CheckpointError(
            "the checkpoint was written with a different [contact] same_layer setting "
            f"(this case: {model.contact_settings.same_layer!r}); give the one it was written with"
        )
    for g in model.same_layer:
        g.restore_history({k: v[g.index] for k, v in checkpoint.same_layer.items()}, model.nodal)
    problem.solver.commit()  # the state rollback returns to (the groups' history is set)
    c = checkpoint
    if c.residual is not None:
        problem.solver.keep_residual(c.residual[points[: model.n_owned]])
    if c.step is None:
        return Position(c.stage, None)
    previous = None
    if c.load_increment is not None and c.dw is not None:
        previous = (c.load_increment, c.dw[points].ravel())
    return Position(c.stage, RampState(c.step, previous))


def write_checkpoint(path: str | Path, checkpoint: Checkpoint, comm=MPI.COMM_WORLD) -> None:
    """Store ``checkpoint`` in ``path`` (HDF5, float64), replacing any earlier one atomically."""
    if not is_root(comm):
        return
    path = Path(path)
    tmp = path.with_name(path.name + ".tmp")
    c = checkpoint
    with h5py.File(tmp, "w") as f:
        f.attrs["strand_checkpoint"] = VERSION
        for k in ("number", "time", "stage"):
            f.attrs[k] = getattr(c, k)
        for k in ("step", "load_increment"):
            f.attrs[k] = np.nan if getattr(c, k) is None else getattr(c, k)
        loads = f.create_group("loads")
        for k, v in c.loads.items():
            loads.attrs[k] = v
        f.create_dataset("w", data=c.w)
        if c.dw is not None:
            f.create_dataset("dw", data=c.dw)
        for name, arrays in (("pairs", c.pairs), ("same_layer", c.same_layer)):
            group = f.create_group(name)
            for k, v in arrays.items():
                group.create_dataset(k, data=v)
        if c.residual is not None:
            f.create_dataset("residual", data=c.residual)
    tmp.replace(path)


class CheckpointError(ValueError):
    """A file that is not a strand checkpoint, or not of this strand."""


def read_checkpoint(path: str | Path) -> Checkpoint:
    """Read a file written by ``write_checkpoint`` (every rank reads it)."""
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise CheckpointError(f"{path}: cannot read the checkpoint ({e})") from None
    with f:
        if f.attrs.get("strand_checkpoint") != VERSION:
            raise CheckpointError(f"{path}: not a strand checkpoint (version {VERSION})")

        def optional(name):
            v = float(f.attrs[name])
            return None if np.isnan(v) else v

        return Checkpoint(
            int(f.attrs["number"]),
            float(f.attrs["time"]),
            {k: float(v) for k, v in f["loads"].attrs.items()},
            int(f.attrs["stage"]),
            optional("step"),
            optional("load_increment"),
            f["w"][()],
            f["dw"][()] if "dw" in f else None,
            {k: v[()] for k, v in f["pairs"].items()},
            {k: v[()] for k, v in f["same_layer"].items()} if "same_layer" in f else {},
            f["residual"][()] if "residual" in f else None,
        )
