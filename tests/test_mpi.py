"""Distributed runs give the serial run's answer: the same steps (Newton iterations equal), wire
axial forces, moment–curvature and contact forces on 1, 2 and 3 ranks, for small and large
sliding, the saddle and the uniform bending test; output and errors once, not once per rank.

Each run is a subprocess (``mpirun`` from the dolfinx wheel's environment: mpich's hydra, which
oversubscribes the 2 cores of CI without complaint)."""

from __future__ import annotations

import csv
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from strand.beam.partition import DistributionError, owned_rows, slab_destinations
from strand.cable.centring import ring_centres
from strand.cable.description import cardinal
from strand.cable.geometry import build_geometry
from strand.model.contact_settings import ContactSettings
from strand.model.model import strand_stencils
from strand_cases import MPIRUN, SEVEN_WIRE, needs_mpirun

#: relative agreement (to each column's largest value) required of a distributed run
RTOL = 1e-8
#: columns that are not results: wall time, and the final residual (round-off, rank-dependent)
NOT_RESULTS = {"stage", "seconds", "residual_N"}


def strand_run(ranks: int, args: list[str], cwd: Path) -> subprocess.CompletedProcess:
    cmd = [sys.executable, "-m", "strand.app", *args]
    if ranks > 1:
        cmd = [str(MPIRUN), "-n", str(ranks), *cmd]
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=600)


def table(path: Path) -> tuple[list[str], np.ndarray]:
    with open(path) as f:
        rows = list(csv.reader(f))
    keep = [i for i, name in enumerate(rows[0]) if name not in NOT_RESULTS]
    return [rows[0][i] for i in keep], np.array([[float(r[i]) for i in keep] for r in rows[1:]])


def assert_same_results(serial: Path, parallel: Path, counts=("iterations", "cuts")) -> float:
    """Every table of ``parallel`` equals ``serial``'s to ``RTOL``; returns the largest relative
    difference. The ``counts`` columns of steps.csv must be equal."""
    worst = 0.0
    for name in ("steps.csv", "axial_forces.csv", "moment_curvature.csv", "slip.csv"):
        head, a = table(serial / name)
        head_b, b = table(parallel / name)
        assert head == head_b and a.shape == b.shape, name
        if name == "steps.csv":
            for col in counts:
                j = head.index(col)
                assert np.array_equal(a[:, j], b[:, j]), f"{name}: {col} differ"
        scale = np.maximum(np.abs(a).max(axis=0), 1e-300)
        rel = np.abs(a - b) / scale
        if name == "steps.csv":  # Newton effort not asked to agree is no result
            effort = {"iterations", "failed_iterations", "factorisations", "cuts"} - set(counts)
            rel[:, [j for j, col in enumerate(head) if col in effort]] = 0.0
        j = int(np.argmax(rel.max(axis=0)))
        assert rel.max() <= RTOL, f"{name}: column {head[j]} differs by {rel.max():.2e}"
        worst = max(worst, float(rel.max()))
    return worst


@pytest.fixture(scope="module")
def seven_wire(tmp_path_factory):
    folder = tmp_path_factory.mktemp("mpi")
    (folder / "seven.toml").write_text(SEVEN_WIRE)
    return folder


def _run_and_compare(
    folder: Path, case: list[str], ranks=(2, 3), tag: str = "", counts=("iterations", "cuts")
) -> None:
    outputs = {}
    for n in (1, *ranks):
        out = folder / f"{tag}{n}"
        done = strand_run(
            n, ["run", *case, "--out", str(out), "--set", "output.plots=false"], folder
        )
        assert done.returncode == 0, done.stderr[-3000:]
        steps = sum(1 for _ in open(out / "steps.csv")) - 1
        # progress printed once: one line per step, whatever the number of ranks
        assert done.stdout.count("Newton its") == steps, done.stdout[-2000:]
        assert done.stdout.count("done:") == 1
        outputs[n] = out
    for n in ranks:
        assert_same_results(outputs[1], outputs[n], counts)
    return outputs


@needs_mpirun
@pytest.mark.slow
def test_seven_wire_saddle_is_the_same_on_1_2_and_3_ranks(seven_wire):
    out = _run_and_compare(seven_wire, ["seven.toml"], tag="saddle")
    # the fatigue histories and the fields, written from rank 0 and collectively
    from strand.app.history import read_history

    for n in (2, 3):
        a, b = (read_history(out[k] / "contact_pairs.h5") for k in (1, n))
        assert a["force"].shape == b["force"].shape
        assert np.abs(a["force"] - b["force"]).max() <= 1e-6 * np.abs(a["force"]).max()  # float32
        assert (out[n] / "fields.h5").stat().st_size > 0 and (out[n] / "fatigue.txt").exists()


#: the 1+6 in the uniform bending set-up, to 0.5 1/m
BENDING = [
    "--set",
    'load.kind="bending"',
    "--set",
    "load.zone=0.04",
    "--set",
    "load.curvature=0.5",
    "--set",
    "steps.curvature=0.1",
    "--set",
    "steps.curvature_max=0.2",
]


@needs_mpirun
@pytest.mark.slow
def test_seven_wire_bending_and_large_sliding_are_the_same_on_3_and_2_ranks(seven_wire):
    _run_and_compare(seven_wire, ["seven.toml", *BENDING], ranks=(3,), tag="bending")
    large = ["--set", 'contact.model="large"']
    _run_and_compare(seven_wire, ["seven.toml", *large], ranks=(2,), tag="large")


#: converged to 1e-7 N on a fixed load path (no step growth)
FIXED_PATH = [
    "--set",
    "steps.balance=0",
    "--set",
    "steps.tolerance=1e-7",
    "--set",
    "steps.max_iterations=20",
    "--set",
    "steps.growth=1.0",
]
#: the 1+6 with its same-layer pairs touching, on that path
TOUCHING = ["--set", 'contact.same_layer="nominal"', *FIXED_PATH]


@needs_mpirun
@pytest.mark.slow
def test_same_layer_pairs_are_the_same_on_1_and_2_ranks(seven_wire):
    """The 1+6's equal wires touch their neighbours: every same-layer pair is closed and pressed,
    and its three-node stencils are kept whole on the rank that evaluates them.

    The touching ring leaves a soft mode: at the default balance tolerance two identical 2-rank
    runs differ by 5e-5 in deflection (MUMPS's parallel round-off, amplified within the
    tolerance). So the runs converge to 1e-7 N on a fixed load path (no step growth); their
    last iterations then reach the round-off floor, so the iteration counts may differ by one
    and are not compared (measured: results within 2e-12)."""
    _run_and_compare(
        seven_wire, ["seven.toml", *TOUCHING], ranks=(2,), tag="same_layer", counts=("cuts",)
    )


@needs_mpirun
@pytest.mark.slow
def test_a_vaulted_core_held_on_its_axis_is_the_same_on_1_and_2_ranks(seven_wire):
    """The 1+6 vaulted over its core (``first_layer = "ring"``) in the bending set-up: the
    springs that hold its core on the ring's axis (``CoreCentring``: the core node and layer
    1's twelve nodes about its z) are kept whole on the rank owning the core node; the touching
    ring's fixed load path and tolerance."""
    ring = [*BENDING, *TOUCHING, "--set", 'contact.first_layer="ring"']
    _run_and_compare(seven_wire, ["seven.toml", *ring], ranks=(2,), tag="ring", counts=("cuts",))


@needs_mpirun
@pytest.mark.slow
def test_facing_pairs_are_the_same_on_1_and_2_ranks(seven_wire):
    """The same on facing stations (``same_layer_stencil = "facing"``): the six shifted lattices
    of stations, wire 0's receivers and the core's node at each of their z, the two-node
    stencils [c, a] kept whole on the rank owning c; the same fixed load path and tolerance."""
    facing = [*TOUCHING, "--set", 'contact.same_layer_stencil="facing"']
    _run_and_compare(
        seven_wire, ["seven.toml", *facing], ranks=(2,), tag="facing", counts=("cuts",)
    )


@needs_mpirun
@pytest.mark.slow
def test_reuse_lu_is_the_same_on_1_and_2_ranks(seven_wire):
    """GMRES on a kept LU (``[steps] iteration = "reuse_lu"``) on distributed matrices: its
    directions differ by the ranks' round-off, and so may the GMRES iteration counts that
    decide when the LU is renewed; on a fixed load path solved to 1e-7 N the results agree
    all the same (the iteration counts are not compared)."""
    reuse = ["--set", 'steps.iteration="reuse_lu"', *FIXED_PATH]
    _run_and_compare(
        seven_wire, ["seven.toml", *reuse], ranks=(2,), tag="reuse_lu", counts=("cuts",)
    )


@needs_mpirun
@pytest.mark.slow
def test_a_cardinal_piece_with_friction_is_the_same_on_1_2_and_3_ranks(tmp_path):
    """Crossings only: with the default same-layer contact (packed layers) the touching rings
    leave soft modes, and the ranks agree to the balance tolerance, not to round-off (measured
    1.6e-6 in deflection on this piece); ``test_same_layer_pairs_are_the_same_on_1_and_2_ranks``
    compares same-layer pairs at a tight tolerance. Tables only: the fields and the fatigue
    histories on N ranks are ``test_seven_wire_saddle_is_the_same_on_1_2_and_3_ranks``'s."""
    case = [
        "cardinal",
        "--set",
        "mesh.length=0.1",
        "--set",
        "load.lateral=1000.0",
        "--set",
        "steps.lateral=250.0",
        "--set",
        "steps.lateral_max=250.0",
        "--set",
        'contact.same_layer="off"',
        "--set",
        "output.fields=false",
        "--set",
        "fatigue.outputs=false",
    ]
    out = _run_and_compare(tmp_path, case, tag="cardinal")
    mk = np.loadtxt(out[1] / "moment_curvature.csv", delimiter=",", skiprows=1)
    slipped = np.loadtxt(out[1] / "slip.csv", delimiter=",", skiprows=1)[:, 2:]
    assert len(mk) >= 4 and slipped.max() > 0  # the comparison covers slipping pairs


@needs_mpirun
def test_mesh_and_bad_input_speak_once_under_mpirun(tmp_path):
    done = strand_run(
        2,
        ["mesh", "--no-picture", "--set", "mesh.length=0.05", "--out", str(tmp_path / "mesh")],
        tmp_path,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.count("interface  type") == 1 and "2 MPI ranks" in done.stdout
    bad = strand_run(2, ["run", "cardinal", "--set", "mesh.length=-1"], tmp_path)
    assert bad.returncode == 2
    lines = [line for line in bad.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("strand: error:"), bad.stderr
    # a folder that is not a run's: refused on every rank, said once, nothing written
    other = tmp_path / "other"
    other.mkdir()
    (other / "notes.txt").write_text("mine")
    refused = strand_run(
        2, ["run", "cardinal", "--set", "mesh.length=0.05", "--out", str(other)], tmp_path
    )
    assert refused.returncode == 2 and refused.stderr.count("strand: error:") == 1
    assert sorted(p.name for p in other.iterdir()) == ["notes.txt"]


@pytest.mark.parametrize("first_layer", ["on_core", "ring"])
@pytest.mark.parametrize("nparts", [2, 3, 5])
def test_slab_partition_keeps_every_stencil_whole_on_its_anchors_owners(nparts, first_layer):
    """Whichever rank owns a pair's node a (one of the owners of a cell touching it) holds every
    cell touching the pair's nodes, and each wire's neighbouring cells (one of overlap); with a
    vaulted first layer, also every core node's ring centre (``ring_centres``)."""
    g = build_geometry(cardinal(), 0.05, 4e-3)
    stencils = strand_stencils(g, ContactSettings(first_layer=first_layer))
    owner, ghosts = slab_destinations(g.points[:, 2], g.cells, nparts, stencils)
    counts = np.bincount(owner, minlength=nparts)
    assert counts.max() - counts.min() <= 1  # equal slabs
    holds = [set(np.flatnonzero(owner == r)) for r in range(nparts)]
    for c, gs in enumerate(ghosts):
        for r in gs:
            holds[r].add(c)
    node_cells = [[] for _ in g.points]
    for c, (i, j) in enumerate(g.cells):
        node_cells[i].append(c)
        node_cells[j].append(c)
    if first_layer == "ring":  # the core's ring centres are among them
        assert any(np.array_equal(st, ring_centres(g).stencils) for st in stencils)
    for st in stencils:
        for row in st:
            needed = {c for n in row for c in node_cells[n]}
            for r in {owner[c] for c in node_cells[row[0]]}:
                assert needed <= holds[r]


def test_owned_rows_refuses_a_stencil_missing_on_its_anchors_rank():
    stencils = np.array([[0, 5], [7, 2], [-1, 3], [2, 1]])
    assert owned_rows(stencils, 4).tolist() == [0, 3]  # 7 is a ghost, −1 absent
    with pytest.raises(DistributionError, match="1 terms have their anchor"):
        owned_rows(np.array([[0, 5], [1, -1]]), 4)


ROOT = Path(__file__).parents[1]
SERIAL_ONLY = [ROOT / "benchmarks" / "mesh_build.py"]  # the demos run on N ranks: test_demos.py


@needs_mpirun
@pytest.mark.parametrize("script", SERIAL_ONLY, ids=[p.stem for p in SERIAL_ONLY])
def test_serial_scripts_refuse_mpirun_in_one_line(script, tmp_path):
    """The benchmarks (which compare variants in one process) stop before computing, with one
    line and exit code 2, instead of hanging."""
    done = subprocess.run(
        [str(MPIRUN), "-n", "2", sys.executable, str(script)],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
    )
    lines = [line for line in done.stderr.splitlines() if line.strip()]
    assert done.returncode == 2 and len(lines) == 1, done.stderr[-2000:]
    assert "start it without mpirun" in lines[0] and not list(tmp_path.iterdir())


COLLECTIVE_API = """
import strand
import numpy as np
from mpi4py import MPI
from strand.contact import ContactError, candidate_pairs, dof_values, locate_nodes
from strand.cable.mesh import beam_space, polyline_mesh
from strand.cable.pictures import tubes
from strand.solver import NodalLoad, NonlinearProblem
from forms import CircularSection, ReissnerBeam
from dolfinx import fem

comm = MPI.COMM_WORLD
out = open(f"rank{comm.rank}.txt", "w")
say = lambda *words: print(*words, file=out, flush=True)
n, r = 16, 1e-3
s = np.linspace(0.0, 0.1, n + 1)
x_a, x_b = s[:, None] * [1.0, 0, 0], (s - 0.05)[:, None] * [0, 1.0, 0] + [0.05, 0, 2 * r]
cells = np.vstack([np.c_[0:n, 1 : n + 1], np.c_[0:n, 1 : n + 1] + n + 1])
V = beam_space(polyline_mesh(comm, np.vstack([x_a, x_b]), cells))
a, b = locate_nodes(V, x_a), locate_nodes(V, x_b)
owned = np.count_nonzero(np.concatenate([a, b]) < V.dofmap.index_map.size_local)
say("located", comm.allreduce(owned))
try:
    locate_nodes(V, [0.5, 0.0, 0.0])
except ValueError as e:
    say("absent:", e)
try:
    candidate_pairs(V, a, b, r, r, 1e-4)
except ContactError as e:
    say("split:", e)
# one beam of 2n cells, cut between the ranks: the node at the cut is a ghost on one of them
x = np.linspace(0.0, 0.2, 2 * n + 1)[:, None] * [1.0, 0, 0]
V = beam_space(polyline_mesh(comm, x, np.c_[0 : 2 * n, 1 : 2 * n + 1]))
nodes = locate_nodes(V, x)
say("ghosts", comm.allreduce(int(np.count_nonzero(nodes >= V.dofmap.index_map.size_local))))
w = fem.Function(V)
load = NodalLoad(nodes, np.tile([0.0, 0.0, 1.0, 0.0, 0.0, 0.0], (len(nodes), 1)), factor=1.0)
problem = NonlinearProblem(ReissnerBeam(w, CircularSection(2 * r, 2e11, 0.3)).residual(), w,
                           terms=[load])
say("load", comm.allreduce(float(problem.unconstrained_residual()[:, 2].sum())))
# every node's value, the ghost's once; a DG0 function's at the cells' midpoints
w.interpolate(lambda p: np.vstack([p[0], 2 * p[0], 0 * p, 0 * p[:1]]))
say("nodes", np.array_equal(dof_values(w, x)[:, :2], np.c_[x[:, 0], 2 * x[:, 0]]))
m = 0.5 * (x[1:] + x[:-1])
c = fem.Function(fem.functionspace(V.mesh, ("DG", 0)))
c.interpolate(lambda p: p[0])
say("cells", np.array_equal(dof_values(c, m)[:, 0], m[:, 0]))
try:
    dof_values(c, x[:1])
except ValueError as e:
    say("no dof:", e)
tube = tubes(V, scalars=c.x.array, name="x", radius=r)
say("tube", None if tube is None else [round(v, 9) for v in tube.bounds[:2]])
"""


@needs_mpirun
def test_the_contact_api_is_collective_on_2_ranks(tmp_path):
    """Two crossed beams on 2 ranks with dolfinx's default partitioner (a beam per rank):
    ``locate_nodes`` finds each node once as owned, a point far from every node is refused on
    both ranks, ``candidate_pairs`` refuses the pair split between the ranks on both, naming the
    partitioner. One beam cut between the ranks: ``NodalLoad`` given every node the rank holds,
    the ghost at the cut included, loads each node once (the residual sums to minus the 33
    nodes' unit forces); ``dof_values`` reads every node and cell once, on both ranks, and
    refuses a point where no dof is; ``tubes`` gives rank 0 the whole beam, rank 1 nothing."""
    script = tmp_path / "api.py"
    script.write_text(COLLECTIVE_API)
    done = subprocess.run(
        [str(MPIRUN), "-n", "2", sys.executable, str(script)],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    lines = [line for r in (0, 1) for line in (tmp_path / f"rank{r}.txt").read_text().splitlines()]
    assert lines.count("located 34") == 2 and lines.count("ghosts 1") == 2, lines
    assert sum("absent: point [0.5, 0.0, 0.0] is" in line for line in lines) == 2, lines
    assert (
        sum(
            "split: candidate_pairs: 1 of 1 pairs" in line and "slab_partitioner" in line
            for line in lines
        )
        == 2
    ), lines
    assert lines.count("load -33.0") == 2, lines
    assert lines.count("nodes True") == 2 and lines.count("cells True") == 2, lines
    assert sum("no dof: point [0.0, 0.0, 0.0] is 0.00313 m" in line for line in lines) == 2, lines
    assert lines.count("tube [0.0, 0.2]") == 1 and lines.count("tube None") == 1, lines


@needs_mpirun
def test_an_error_on_one_rank_ends_every_rank(tmp_path):
    """An exception that escapes on rank 0 alone (as in what rank 0 alone writes) ends the run
    on both ranks with its traceback and a non-zero exit, instead of leaving rank 1 waiting at
    its next collective call for ever."""
    script = tmp_path / "fails_on_root.py"
    script.write_text(
        "import strand\nfrom mpi4py import MPI\nfrom strand.beam.parallel import abort_on_error\n"
        "abort_on_error()\n"
        "if MPI.COMM_WORLD.rank == 0:\n    raise KeyError('only on rank 0')\n"
        "MPI.COMM_WORLD.barrier()\n"
    )
    done = subprocess.run(
        [str(MPIRUN), "-n", "2", sys.executable, str(script)],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode != 0
    assert "KeyError: 'only on rank 0'" in done.stderr


@needs_mpirun
@pytest.mark.slow
def test_the_readme_run_command_gives_the_serial_numbers_on_2_ranks(tmp_path, quick_run):
    """``make run`` (the README's first command) starts a case on every core, NP MPI ranks: on
    the quick case NP=2 takes the serial run's steps (``quick_run``, the same case in one
    process), and its results agree within what the packed ring's soft mode leaves between runs
    (the balance tolerance: ``test_same_layer_pairs_…``)."""
    root = Path(__file__).resolve().parents[1]
    out = tmp_path / "np2"
    args = f"--out {out} --set output.plots=false --set output.fields=false"
    done = subprocess.run(
        ["make", "-s", "-C", str(root), "run", "CASE=cases/quick_1x6.toml", "NP=2", f"ARGS={args}"],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    assert done.stdout.count("done:") == 1 and "2 MPI ranks" in done.stdout
    serial = quick_run["folder"]
    head, a = table(serial / "steps.csv")
    head_b, b = table(out / "steps.csv")
    assert head == head_b and a.shape == b.shape
    j = head.index("deflection_m")
    assert np.abs(a[:, j] - b[:, j]).max() <= 1e-4 * np.abs(a[:, j]).max()
    _, na = table(serial / "axial_forces.csv")
    _, nb = table(out / "axial_forces.csv")
    assert np.abs(na[:, -1] - nb[:, -1]).max() <= 1e-4 * np.abs(na[:, -1]).max()


@needs_mpirun
@pytest.mark.slow
def test_a_stabilised_start_is_the_same_on_1_and_2_ranks(tmp_path):
    """The vaulted 1+6+12 (``test_stabilisation``) over 0.5 m to 5 kN: the same steps, the same
    first step held, its springs' energy fraction (summed over the ranks) and the axial forces
    alike. Packed rings leave soft modes, so the ranks agree to the balance tolerance, not to
    round-off (``test_a_cardinal_piece_with_friction_is_the_same_on_1_2_and_3_ranks``)."""
    from test_stabilisation import _ring_19

    from strand.app.case import case_from_dict
    from strand.app.case_toml import case_toml

    ring = _ring_19(1e4)
    ring["load"]["tension"] = 5e3
    (tmp_path / "ring.toml").write_text(case_toml(case_from_dict(ring)))
    out = {}
    for n in (1, 2):
        out[n] = tmp_path / f"ring{n}"
        done = strand_run(n, ["run", "ring.toml", "--out", str(out[n])], tmp_path)
        assert done.returncode == 0, done.stderr[-3000:]
        assert done.stdout.count("held by the springs:") == 1, done.stdout[-2000:]
    (head, a), (_, b) = (table(out[n] / "steps.csv") for n in (1, 2))
    for col in ("iterations", "cuts"):
        assert np.array_equal(a[:, head.index(col)], b[:, head.index(col)]), col
    held = head.index("stabilisation")
    assert a[0, held] > 0 and np.all(a[1:, held] == 0)
    hold = head.index("hold")  # the springs alone carried it
    assert a[0, hold] == b[0, hold] == 1 and not a[1:, hold].any() and not b[1:, hold].any()
    assert b[:, held] == pytest.approx(a[:, held], rel=1e-4)
    (_, Na), (_, Nb) = (table(out[n] / "axial_forces.csv") for n in (1, 2))
    assert np.abs(Na - Nb).max() <= 1e-5 * np.abs(Na).max()
