"""Report a finished spectrum sweep again with other [fatigue] settings (mean stress, a design
fatigue factor), from its members' histories: no physics is computed again.

    python scripts/report_again.py <sweep folder> --set fatigue.mean_stress='"swt"' ...

Prints each member's largest wire damage per cycle (whole strand and free span) and the
spectrum's text, with the case's settings changed by --set."""

from __future__ import annotations

import argparse
from dataclasses import dataclass
from pathlib import Path

import numpy as np

import strand.app.kinds  # noqa: F401  (registers the built-in kinds)
from strand.app.case import load_case
from strand.app.fatigue.report import fatigue_report
from strand.app.fatigue.spectrum import spectrum_report
from strand.app.kind_registry import lookup


@dataclass
class _Member:
    """What ``spectrum_report`` reads of a member's run."""

    fatigue: object
    interrupted: bool = False
    failure: str | None = None


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", type=Path, help="the sweep's folder (holds tension/ and members)")
    parser.add_argument("--set", action="append", default=[], help="section.key=value")
    args = parser.parse_args()
    case = load_case(args.folder / "tension" / "case.toml", args.set)
    kind = lookup(case.load.kind)
    members = []
    for amplitude in case.load.sweep:
        folder = args.folder / f"{kind.parameter}_{amplitude:g}"
        if not (folder / "summary.txt").is_file():
            print(f"{folder.name}: not run to its end; no spectrum")
            return
        report = fatigue_report(folder, case.cable, case.load.tension, case.fatigue, write=False)
        whole, free = report.wires.whole.damage, report.wires.free_span.damage
        check = report.tension_check
        print(
            f"{folder.name}: largest wire damage per cycle {np.nanmax(whole):.3g}, free span "
            f"{np.nanmax(free):.3g}; DNV-OS-E301 {check.dnv:.3g}, API RP 2SK {check.api:.3g}"
        )
        members.append(_Member(report))
    print(spectrum_report(case, members, kind.parameter, "N").text)


if __name__ == "__main__":
    main()
