"""The benchmark scripts stay runnable: each compiles, imports, names itself in its ``Run:`` line
and in docs/benchmarks.md's table of scripts, answers ``--help``, and runs ``--quick`` to the end
of its table (slow). And the harness they share (``benchmarks/harness.py``): its stamp line,
tables, peak memory and variants run each in a process of its own."""

from __future__ import annotations

import importlib.util
import os
import py_compile
import re
import subprocess
import sys
import textwrap
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
BENCHMARKS = ROOT / "benchmarks"
SCRIPTS = sorted(p for p in BENCHMARKS.glob("*.py") if p.name != "harness.py")


@pytest.fixture
def harness(monkeypatch):
    monkeypatch.syspath_prepend(str(BENCHMARKS))
    import harness

    return harness


def _env() -> dict[str, str]:
    """This tree first on the path of a script run as its own process."""
    return dict(
        os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])
    )


def _run(args: list[str], cwd: Path, timeout: float) -> subprocess.CompletedProcess:
    done = subprocess.run(
        [sys.executable, *args],
        cwd=cwd,
        env=_env(),
        capture_output=True,
        text=True,
        timeout=timeout,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return done


def test_every_script_is_in_the_docs_table_of_scripts():
    docs = (ROOT / "docs" / "benchmarks.md").read_text()
    table = docs.split("## The scripts", 1)[1].split("\n## ", 1)[0]
    rows = dict(re.findall(r"^\| `(\w+\.py)(.*)$", table, re.M))
    assert set(rows) == {p.name for p in SCRIPTS}
    assert all("--quick" in row.split("|")[0] for row in rows.values()), rows


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_the_script_compiles_and_imports(script, harness, tmp_path):
    py_compile.compile(str(script), cfile=str(tmp_path / "script.pyc"), doraise=True)
    spec = importlib.util.spec_from_file_location(f"benchmark_{script.stem}", script)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)  # imports only: the runs are under ``__main__``
    assert callable(getattr(module, "main", None) or getattr(module, "run", None))
    run_line = module.__doc__.split("Run:", 1)[1].splitlines()[0]
    assert f"benchmarks/{script.name}" in run_line


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_the_script_answers_help(script, tmp_path):
    """Its parser (``harness.parser``): the usage with ``--quick``, and the docstring."""
    done = _run([str(script), "--help"], tmp_path, 120)
    assert done.stdout.startswith(f"usage: {script.name} [-h] [--quick]")
    assert re.search(rf"^Run: .*benchmarks/{script.name}", done.stdout, re.M)


def _window(done: subprocess.CompletedProcess, folder: Path) -> None:
    """Today's default on 1 rank: a row with steps and iterations, and its results kept."""
    lines = done.stdout.splitlines()
    assert re.match(r"stamp: \d{4}-\d\d-\d\d \d\d:\d\d, commit \w+", lines[0])
    head = next(i for i, line in enumerate(lines) if line.startswith("variant"))
    row = lines[head + 1].split()
    assert row[0] == "default" and int(row[3]) > 0 and int(row[4]) > 0  # steps, iterations
    assert (folder / "results" / "benchmark_window" / "default.npz").exists()


def _speed(done: subprocess.CompletedProcess, folder: Path) -> None:
    """One variant with every output: its name in the stamp, and its outputs' times."""
    first = done.stdout.splitlines()[0]
    assert first.startswith("stamp: ") and "'default: cp line search'`" in first
    assert "outputs of 'default: cp line search' (s): " in done.stdout


def _layer_states(done: subprocess.CompletedProcess, folder: Path) -> None:
    """A row per state, with a first-step secant, moments beside the law and the cost."""
    rows = [line for line in done.stdout.splitlines() if line.startswith(("| packed", "| nominal"))]
    assert len(rows) == 2, done.stdout
    for line in rows:
        cells = [c.strip() for c in line.strip("|").split("|")]
        assert float(cells[1]) > 0  # the first step's secant over EI_max
        assert re.match(r"\d+\.\d \(\d+\.\d\)", cells[3])  # M at 0.0083 (the law's)
        assert re.match(r"\d+ s, \d+ \+ \d+ its, \d+ LUs", cells[-1])


def _freed_memory(done: subprocess.CompletedProcess, folder: Path) -> None:
    """glibc's defaults beside freed memory kept, and the same deflections to round-off (malloc's
    policy changes no arithmetic; measured 0 m on 1 rank, 2.5e-18 m on 2)."""
    assert re.search(r"^glibc defaults +[\d.]+ +[1-9]\d* ", done.stdout, re.M), done.stdout
    gap = re.search(r"largest difference (\S+) m", done.stdout)
    assert gap and float(gap.group(1)) <= 1e-12


def _wire_count(done: subprocess.CompletedProcess, folder: Path) -> None:
    """The table's own stamp line."""
    assert re.search(r"Wire count: \d{4}-\d\d-\d\d \d\d:\d\d, commit \w+", done.stdout)


def _stick_bending(done: subprocess.CompletedProcess, folder: Path) -> None:
    """Its row says so when a run stops (``stopped: …``): none did."""
    assert " stopped: " not in done.stdout, done.stdout


def _newton_iteration(done: subprocess.CompletedProcess, folder: Path) -> None:
    """The tension is reached as a run reaches it, and the parts add up to the total."""
    assert re.search(r"tension steps \[\d+(, \d+)*\]", done.stdout)
    share = re.search(r"contact share of a Newton iteration: (\S+) %", done.stdout)
    assert share and 0 < float(share.group(1)) < 100


def _converged_relaxation(done: subprocess.CompletedProcess) -> None:
    """The quick step (nothing buckles) comes to rest: the relaxation converged, the springs'
    force falling, its last under 1 N."""
    assert re.search(
        r"^500 → 1000 N: converged after [1-9]\d* pseudo-time steps", done.stdout, re.M
    )
    forces = [float(f) for f in re.findall(r"their force (\S+) N", done.stdout)]
    assert forces and forces[-1] < 1.0 and forces[-1] < forces[0]


@dataclass(frozen=True)
class Quick:
    """A script's quick run: its arguments after ``--quick``, the head of the table it prints
    and a row under it (regular expressions, each matching a whole line), and any checks of its
    own (``check(done, folder)``: the finished process and the folder it ran in)."""

    head: str
    row: str
    args: tuple[str, ...] = ()
    check: Callable[[subprocess.CompletedProcess, Path], None] | None = None


#: every script's quick run (``test_every_script_has_a_quick_run``)
QUICK = {
    "beam_newton.py": Quick(r"measure +value", r"Newton iterations \(20 N pull\) +[1-9]\d* \(.*"),
    "bending_compliance.py": Quick(
        r"variant +M/κ₀ / EI_max .* time s +its",
        r"Hertz \+ Mindlin +\d\.\d{3} .* \d+ +[1-9]\d*",
    ),
    "cardinal.py": Quick(r"stage +steps +Newton its +iterations per step", r"leg 1 +\d+ +\d+ .*"),
    "contact_normals.py": Quick(
        r"normal +tension its +lateral its +cuts +time s .*", r"frozen +\[\d.*\] +\[\d.*"
    ),
    "fatigue_outputs.py": Quick(
        r"output +s per step +MB per step", r"wire sections \(h5\) +\d+\.\d{3} +\d+\.\d\d"
    ),
    "freed_memory.py": Quick(
        r"variant +time \(s\) +steps +its +LUs +s/it +page faults +peak MiB",
        r"freed memory kept +[\d.]+ +[1-9]\d* +\d+ .*",
        check=_freed_memory,
    ),
    "layer_states.py": Quick(
        r"\| state \| M/κ / EI_max \| M at 0\.0035 \|.*",
        r"\| nominal \| .*",
        ("packed", "nominal"),
        _layer_states,
    ),
    "length_scaling.py": Quick(
        r" *L \(m\) +unknowns +steps +its +\+failed +time \(s\) +s/it +LU share +peak MiB",
        r" +0\.10 +\d+ +[1-9]\d* +[1-9]\d* .*",
    ),
    "lu_fill.py": Quick(
        r"\| same-layer pairs \| matrix entries \| ordering \| LU operations \| factor entries \| s \|",
        r"\| node to segment \(built\) \| \S+ \| METIS \| \S+ \| \S+ \| \S+ \|",
    ),
    "mesh_build.py": Quick(r"best of 1 +time \(s\)", r"total +\d+\.\d{4} .*"),
    "newton_iteration.py": Quick(
        r"part +s / iteration +share",
        r"total +\d+\.\d{3} +100\.0 %",
        check=_newton_iteration,
    ),
    "newton_levers.py": Quick(
        r"\| variant \| lateral \(N\) \| converged \| iterations \| LUs \| solves \| s \| .*",
        r"\| reuse_lu: all steps \| \| \| \d+ \| \d+ \| \d+ \| .*",
    ),
    "parallel.py": Quick(
        r"variant +time \(s\) +steps +its +cuts +s/it +LU share +peak memory per rank \(MiB\)",
        r"Cardinal 0\.05 m, 2 ranks +[\d.]+ +[1-9]\d* .*",
    ),
    "relaxation.py": Quick(
        r"layer +max\|radial\| µm +max\|hoop\| µm +max\|axial\| µm +max\|rotation\| mrad",
        r"1 +\d+\.\d\d +\d+\.\d\d +\d+\.\d\d +\d+\.\d{3}",
        check=lambda done, folder: _converged_relaxation(done),
    ),
    "sliding_comparison.py": Quick(
        r"model +steps +cuts +Newton its +time s .*", r"large +[1-9]\d* +\d+ +[1-9]\d* .*"
    ),
    "speed.py": Quick(
        r"variant +time \(s\) +steps +its +\+failed +LUs +s/LU +s/it +output s +peak MiB",
        r"default: cp line search +\d+ +[1-9]\d* .*",
        ("default: cp line search",),
        _speed,
    ),
    "stabilisation.py": Quick(
        r"\| k \(N/m\) \| reached \| steps \| its \+ failed \| LUs \| s \| held \| energy \| .*",
        r"\| 10000 \| 2000 N \| \d+ \| .*",
        ("1e3", "1e4"),  # without springs (0) the vaulted ring stops: a FAILED row
    ),
    "state_changes.py": Quick(
        r"stage +its +interface +pairs +open/close +stick/slip +open@end +slip@end",
        r"leg 1 +[1-9]\d* +\d\|\d +\d+ .*",
    ),
    "stencils.py": Quick(
        r"peak: run +deflection µm +end µm .*", r"  facing, h/2 +-?\d+\.\d{3} +-?\d+\.\d{4} .*"
    ),
    "stick_bending.py": Quick(
        r"\| strand \| slip \| same layer \| estimate \| M/κ / EI_max \| .*",
        r"\| 1\+6\+12, 0\.1 m, 10 kN \| surface \| packed \| \d\.\d{3} \| \d\.\d{3} \| .*",
        check=_stick_bending,
    ),
    "sweep.py": Quick(
        r" +A \(N\) +sweep steps/its +alone steps/its +sweep s +alone s",
        r" +1000 +[1-9]\d*/[1-9]\d* +[1-9]\d*/[1-9]\d* .*",
    ),
    "window.py": Quick(
        r"variant +time \(s\) +/first +steps +its .*",
        r"default +\d+ .*",
        ("--ranks", "1", "default"),
        _window,
    ),
    "wire_count.py": Quick(
        r"\| wires \| ranks \| unknowns \| pairs \| .*",
        r"\| 7 \| 1 \| \d+ \| .*",
        ("--wires", "7", "--ranks", "1", "--no-analysis"),
        _wire_count,
    ),
}


def test_every_script_has_a_quick_run():
    assert set(QUICK) == {p.name for p in SCRIPTS}


@pytest.mark.slow
@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_the_quick_run_prints_its_table(script, tmp_path):
    """``--quick`` runs to its end and prints the stamp, then the table the full run prints:
    its head, and under it a row of numbers; no run in it failed."""
    quick = QUICK[script.name]
    done = _run([str(script), "--quick", *quick.args], tmp_path, 900)
    out = done.stdout
    assert re.search(r"\d{4}-\d\d-\d\d \d\d:\d\d, commit \w+.*, \d+ cores, `", out), out
    head = re.search(rf"^{quick.head}$", out, re.M)
    assert head, out
    assert re.search(rf"^{quick.row}$", out[head.end() :], re.M), out
    assert "FAILED" not in out
    if quick.check is not None:
        quick.check(done, tmp_path)


def test_the_stamp_names_date_commit_cores_and_command(harness):
    line = harness.stamp(["python", "benchmarks/x.py", "--quick"])
    commit = subprocess.run(
        ["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True, text=True
    ).stdout.strip()
    assert re.fullmatch(
        rf"\d{{4}}-\d\d-\d\d \d\d:\d\d, commit {commit}( \(modified\))?, {os.cpu_count()} cores, "
        r"`python benchmarks/x.py --quick`",
        line,
    )


def test_tables_markdown_and_plain(harness):
    rows = [["a", 1, "2.50"], ["bbb", 10, "x"]]
    assert harness.table(rows, ["name", "n", "v"]).splitlines() == [
        "| name | n | v |",
        "|---|---|---|",
        "| a | 1 | 2.50 |",
        "| bbb | 10 | x |",
    ]
    assert harness.table(rows[:1], ["name", "n", "v"], head=False) == "| a | 1 | 2.50 |"
    assert harness.table(rows, ["name", "n", "v"], plain=True).splitlines() == [
        "name  n    v",
        "a     1 2.50",
        "bbb  10    x",
    ]
    with pytest.raises(ValueError, match="2 cells under 3 columns"):
        harness.table([["a", 1]], ["name", "n", "v"])


def test_peak_memory_is_this_process_in_mib(harness):
    assert 10 < harness.peak_mib() < 1e6


def test_variants_run_each_in_a_process_of_its_own(harness, tmp_path):
    script = tmp_path / "variants.py"
    script.write_text(
        textwrap.dedent("""\
        import os, sys
        from harness import print_result
        name = sys.argv[sys.argv.index("--one") + 1]
        if name == "bad":
            raise SystemExit("no good")
        print("noise first")
        print_result({"name": name, "args": sys.argv[1:-2], "pid": os.getpid()})
        """)
    )
    env = dict(os.environ, PYTHONPATH=str(BENCHMARKS))
    rows = harness.run_variants(script, ["a", "b"], ["--quick"], env=lambda name: env)
    assert [r["name"] for r in rows.values()] == ["a", "b"]
    assert rows["a"]["args"] == ["--quick"] and rows["a"]["pid"] != rows["b"]["pid"]
    with pytest.raises(SystemExit, match="bad: failed"):
        harness.run_variants(script, ["a", "bad"], env=lambda name: env)
