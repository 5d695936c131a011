"""Command line: ``strand run`` (for now the roll-up demo; the Cardinal case comes with issue 5)."""

from __future__ import annotations

import argparse
import runpy
from pathlib import Path

DEMOS = Path(__file__).resolve().parents[1] / "demos"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="strand", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run the main job (currently: the cantilever roll-up demo)")
    run.add_argument("case", nargs="?", help="case file (TOML); not used yet")
    args = parser.parse_args(argv)
    if args.command == "run":
        if args.case:
            parser.error("case files arrive with the Cardinal case; run without one for now")
        runpy.run_path(str(DEMOS / "demo_cantilever_rollup.py"), run_name="__main__")
    return 0
