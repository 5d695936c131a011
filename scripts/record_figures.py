"""Record the results the docs show, so that building them runs nothing.

* ``python scripts/record_figures.py [demo_name ...]`` runs each demo (default: all of
  ``demos/``) serially, one code cell after the other in a fresh interpreter, and keeps in
  ``docs/_static/tutorials/<demo>/`` what each cell prints (``outputs.json``) and the figures the
  demo draws (the PNG files its code names). The tutorial pages show them under their cells
  (``docs/_ext/strand_docs.py``).
* ``python scripts/record_figures.py --outputs`` runs ``cases/quick_1x6.toml`` and keeps its
  figures in ``docs/_static/outputs/`` for the outputs reference.
* ``python scripts/record_figures.py --mooring`` runs the mooring case cheaply (``MOORING``: 0.05
  m on a coarse mesh, with a three-class spectrum, about a minute) and keeps in
  ``docs/_static/mooring/`` the spectrum's figure and those of its member at the case's own
  cycle, with ``stamp.txt`` (date, commit, command, wall time) for docs/mooring.md's captions.

Figures are stored as 256-colour PNGs (a few tens of kB each). Run it again after changing a
demo: ``tests/test_docs.py`` fails while a recorded cell is no longer in its demo.
"""

from __future__ import annotations

import argparse
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).parents[1]
DEMOS = ROOT / "demos"
STATIC = ROOT / "docs" / "_static"

#: runs a demo's code cells in order in one namespace, keeping what each prints
CELLS = r"""
import contextlib, io, json, sys
import jupytext

demo, out = sys.argv[1], sys.argv[2]
scope = {"__name__": "__main__", "__file__": demo}
cells = []
for cell in jupytext.read(demo).cells:
    if cell.cell_type == "code":
        printed = io.StringIO()
        with contextlib.redirect_stdout(printed):
            exec(compile(cell.source, demo, "exec"), scope)
        cells.append({"code": cell.source, "output": printed.getvalue()})
with open(out, "w") as f:
    json.dump(cells, f, indent=1, ensure_ascii=False)
    f.write("\n")
"""


def figure_names(demo: Path) -> list[str]:
    """The PNG files a demo draws: those its code (not its prose) names."""
    import jupytext

    code = "\n".join(c.source for c in jupytext.read(demo).cells if c.cell_type == "code")
    return sorted(set(re.findall(r"([\w.-]+\.png)\b", code)))


def small_png(source: Path, target: Path) -> None:
    """``source`` as a 256-colour PNG at ``target`` (plots and renders keep their look)."""
    from PIL import Image

    with Image.open(source) as image:
        image.convert("RGB").quantize(256, dither=Image.Dither.NONE).save(target, optimize=True)


def record_demo(demo: Path) -> None:
    target = STATIC / "tutorials" / demo.stem
    with tempfile.TemporaryDirectory() as tmp:
        outputs = Path(tmp) / "outputs.json"
        subprocess.run([sys.executable, "-c", CELLS, str(demo), str(outputs)], cwd=tmp, check=True)
        shutil.rmtree(target, ignore_errors=True)
        target.mkdir(parents=True)
        shutil.copy(outputs, target / "outputs.json")
        for name in figure_names(demo):
            drawn = sorted(Path(tmp).glob(f"results/**/{name}"))
            if len(drawn) != 1:
                raise SystemExit(f"{demo.name}: {name} drawn {len(drawn)} times, not once")
            small_png(drawn[0], target / name)
    print(f"{demo.stem}: {', '.join(figure_names(demo))} and outputs.json in {target}")


def record_outputs() -> None:
    target = STATIC / "outputs"
    with tempfile.TemporaryDirectory() as tmp:
        run = [sys.executable, "-m", "strand.app", "run", str(ROOT / "cases" / "quick_1x6.toml")]
        subprocess.run([*run, "--out", f"{tmp}/run"], cwd=tmp, check=True)
        shutil.rmtree(target, ignore_errors=True)
        target.mkdir(parents=True)
        for png in sorted(Path(tmp, "run").glob("*.png")):
            small_png(png, target / png.name)
            print(target / png.name)


#: the mooring page's run: run A of docs/mooring.md (0.05 m, h_max 10 mm, the 50 kN first tension
#: step that a short piece takes) with the page's spectrum
MOORING = [
    "cases/mooring_judge120.toml",
    "--set",
    "mesh.length=0.05",
    "--set",
    "mesh.h_max=1e-2",
    "--set",
    "steps.tension=50e3",
    "--set",
    "output.fields=false",
    "--set",
    "fatigue.spectrum=[[90.15e3,4e6],[180.3e3,1e6],[270.45e3,1e5]]",
]
#: the member whose figures the page shows: the case's own cycle, ±5 % MBS
MOORING_MEMBER = "tension_swing_180300"
MOORING_FIGURES = ("stress_range.png", "fretting_map.png", "deformed_axial_force.png")


def _commit() -> str:
    """The checkout's commit, "+changes" where its tracked files outside docs/_static (what
    this script writes) differ from it."""
    git = ["git", "-C", str(ROOT)]
    head = subprocess.run([*git, "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
    dirty = subprocess.run([*git, "diff", "--quiet", "HEAD", "--", ".", ":!docs/_static"])
    dirty = dirty.returncode
    return head.stdout.strip() + ("+changes" if dirty else "")


def record_mooring() -> None:
    import time
    from datetime import date

    target = STATIC / "mooring"
    with tempfile.TemporaryDirectory() as tmp:
        run = [sys.executable, "-m", "strand.app", "run", *MOORING, "--out", f"{tmp}/run"]
        t0 = time.perf_counter()
        subprocess.run(run, cwd=ROOT, check=True)
        seconds = time.perf_counter() - t0
        shutil.rmtree(target, ignore_errors=True)
        target.mkdir(parents=True)
        pngs = [Path(tmp, "run", "spectrum.png")]
        pngs += [Path(tmp, "run", MOORING_MEMBER, name) for name in MOORING_FIGURES]
        for png in pngs:
            small_png(png, target / png.name)
            print(target / png.name)
    command = "strand run " + shlex.join(MOORING)
    (target / "stamp.txt").write_text(
        f"date: {date.today().isoformat()}\ncommit: {_commit()}\ncommand: {command}\n"
        f"member: {MOORING_MEMBER}\nwall time: {seconds:.0f} s on 1 rank\n"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("demos", nargs="*", help="demo names (default: every demo)")
    parser.add_argument("--outputs", action="store_true", help="the quick case's run figures")
    parser.add_argument("--mooring", action="store_true", help="the mooring page's figures")
    args = parser.parse_args()
    if args.outputs:
        record_outputs()
    if args.mooring:
        record_mooring()
    if args.demos or not (args.outputs or args.mooring):
        names = args.demos or [p.stem for p in sorted(DEMOS.glob("demo_*.py"))]
        for name in names:
            record_demo(DEMOS / f"{name.removesuffix('.py')}.py")


if __name__ == "__main__":
    main()
