"""The benchmark scripts stay runnable: each compiles, imports, names itself in its ``Run:`` line
and in docs/benchmarks.md's table of scripts; those with an argument parser answer ``--help``;
the ``--quick`` modes run (slow). And the harness they share (``benchmarks/harness.py``): its
stamp line, tables, peak memory and variants run each in a process of its own."""

from __future__ import annotations

import importlib.util
import os
import py_compile
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
BENCHMARKS = ROOT / "benchmarks"
SCRIPTS = sorted(p for p in BENCHMARKS.glob("*.py") if p.name != "harness.py")
#: the scripts whose options an argparse parser reads
WITH_PARSER = ["stick_bending.py", "wire_count.py", "freed_memory.py", "stabilisation.py"]


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
    listed = set(re.findall(r"^\| `(\w+\.py)", table, re.M))
    assert listed == {p.name for p in SCRIPTS}


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_the_script_compiles_and_imports(script, harness, tmp_path):
    py_compile.compile(str(script), cfile=str(tmp_path / "script.pyc"), doraise=True)
    spec = importlib.util.spec_from_file_location(f"benchmark_{script.stem}", script)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)  # imports only: the runs are under ``__main__``
    assert callable(getattr(module, "main", None) or getattr(module, "run", None))
    run_line = module.__doc__.split("Run:", 1)[1].splitlines()[0]
    assert f"benchmarks/{script.name}" in run_line


@pytest.mark.parametrize("name", WITH_PARSER)
def test_the_script_answers_help(name, tmp_path):
    done = _run([str(BENCHMARKS / name), "--help"], tmp_path, 120)
    assert done.stdout.startswith("usage:")


@pytest.mark.slow
def test_window_quick_runs(tmp_path):
    """The main job's window at 0.1 m, today's default on 1 rank: the stamp and one row."""
    args = [str(BENCHMARKS / "window.py"), "--quick", "--ranks", "1", "default"]
    done = _run(args, tmp_path, 600)
    lines = done.stdout.splitlines()
    assert re.match(r"stamp: \d{4}-\d\d-\d\d \d\d:\d\d, commit \w+", lines[0])
    head = next(i for i, line in enumerate(lines) if line.startswith("variant"))
    row = lines[head + 1].split()
    assert row[0] == "default" and int(row[3]) > 0 and int(row[4]) > 0  # steps, iterations
    assert "FAILED" not in done.stdout
    assert (tmp_path / "results" / "benchmark_window" / "default.npz").exists()


@pytest.mark.slow
def test_speed_quick_runs(tmp_path):
    """The default case at 0.05 m to +0.5 kN with every output, one variant: the stamp, its row and
    its outputs' times."""
    variant = "default: cp line search"
    done = _run([str(BENCHMARKS / "speed.py"), "--quick", variant], tmp_path, 600)
    lines = done.stdout.splitlines()
    assert lines[0].startswith("stamp: ") and "'default: cp line search'`" in lines[0]
    head = next(i for i, line in enumerate(lines) if line.startswith("variant"))
    assert lines[head + 1].startswith(variant) and "FAILED" not in done.stdout
    assert f"outputs of '{variant}' (s): " in done.stdout


@pytest.mark.slow
def test_wire_count_quick_runs(tmp_path):
    """The 7-wire strand over 0.06 m on 1 rank: the stamp and the run's row."""
    args = ["--quick", "--wires", "7", "--ranks", "1", "--no-analysis"]
    done = _run([str(BENCHMARKS / "wire_count.py"), *args], tmp_path, 600)
    assert re.search(r"Wire count: \d{4}-\d\d-\d\d \d\d:\d\d, commit \w+", done.stdout)
    assert re.search(r"^\| 7 \| 1 \| \d+ \|", done.stdout, re.M)
    assert "FAILED" not in done.stdout


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


@pytest.mark.slow
def test_layer_states_quick_runs(tmp_path):
    """Two layer states on 0.1 m of Cardinal, one process: the stamp and a row each, with a
    first-step secant, moments beside the law in brackets and the cost."""
    done = _run(
        [str(BENCHMARKS / "layer_states.py"), "--quick", "packed", "nominal"], tmp_path, 600
    )
    lines = done.stdout.splitlines()
    assert re.match(r"\d{4}-\d\d-\d\d \d\d:\d\d, commit \w+", lines[0])
    rows = [line for line in lines if line.startswith(("| packed", "| nominal"))]
    assert len(rows) == 2, done.stdout
    for line in rows:
        cells = [c.strip() for c in line.strip("|").split("|")]
        assert float(cells[1]) > 0  # the first step's secant over EI_max
        assert re.match(r"\d+\.\d \(\d+\.\d\)", cells[3])  # M at 0.0083 (the law's)
        assert re.match(r"\d+ s, \d+ \+ \d+ its, \d+ LUs", cells[-1])


@pytest.mark.slow
def test_freed_memory_quick_runs(tmp_path):
    """0.05 m on 1 rank, glibc's defaults and freed memory kept: the stamp, a row each, and the
    same deflections to round-off (malloc's policy changes no arithmetic; measured 0 m on 1 rank,
    2.5e-18 m on 2)."""
    done = _run([str(BENCHMARKS / "freed_memory.py"), "--quick"], tmp_path, 600)
    assert done.stdout.startswith("stamp: ") and "FAILED" not in done.stdout
    assert re.search(r"^glibc defaults +[\d.]+ +\d+", done.stdout, re.M)
    assert re.search(r"^freed memory kept +[\d.]+ +\d+", done.stdout, re.M)
    gap = re.search(r"largest difference (\S+) m", done.stdout)
    assert gap and float(gap.group(1)) <= 1e-12
