"""A case written back as a case file: every setting of every section, the cable inline.

``case_toml`` gives the ``case.toml`` each run writes first into its folder: valid TOML that
``strand.app.case.load_case`` reads back to the same ``Case`` (so ``strand run <folder>/case.toml``
repeats the run), headed by comments naming the strand version and the case it came from.
"""

from __future__ import annotations

import json
import math
from dataclasses import fields

from ..cable.description import Cable
from .settings import SECTIONS, Case

__all__ = ["case_toml", "cable_table", "strand_version"]


def strand_version() -> str:
    """strand's version (``strand.__version__``, the one place it is written)."""
    from .. import __version__

    return __version__


def _value(v) -> str:
    """``v`` as a TOML value: floats in Python's shortest exact repr (read back bitwise)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, tuple | list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    raise TypeError(f"no TOML form for {v!r}")


def cable_table(cable: Cable) -> dict:
    """``cable`` as a case file's ``[cable]`` table (name, core, layers), the form
    ``strand.cable.description.cable_from_dict`` reads."""
    core, *layers = cable.layers

    def wire(layer) -> dict:
        w = layer.wire
        out = {"diameter": w.diameter, "E": w.E, "nu": w.nu}
        if w.yield_stress is not None:
            out["yield_stress"] = w.yield_stress
        if w.tensile_strength is not None:
            out["tensile_strength"] = w.tensile_strength
        return out

    return {
        "name": cable.name,
        "core": {**wire(core), "friction": core.friction},
        "layer": [
            {
                "wires": lay.wires,
                **wire(lay),
                "lay_angle": lay.lay_angle,
                "lay": lay.lay,
                "friction": lay.friction,
            }
            for lay in layers
        ],
    }


def _section_items(case: Case, name: str) -> list[tuple[str, object]]:
    section = getattr(case, name)
    if hasattr(section, "by_kind"):
        return section.items()
    return [(f.name, getattr(section, f.name)) for f in fields(section)]


def case_toml(case: Case, folder: str | None = None, restart: str | None = None) -> str:
    """The whole effective ``case`` as a case file; ``folder``: the results folder the run
    writes into (``[output] folder``; default the case's); ``restart``: the checkpoint it
    continued from (a comment: a restart is a command-line choice, not a setting)."""
    lines = [
        f"# strand {strand_version()}: the whole case of this run, every setting written out.",
        f"# From: {case.source}.",
        "# Run it again: strand run <this file> --out <new folder>",
    ]
    if restart is not None:
        lines.append(f"# This run continued from the checkpoint {restart} (--restart).")
    table = cable_table(case.cable)
    lines += ["", "[cable]", f"name = {_value(table['name'])}", "", "[cable.core]"]
    lines += [f"{k} = {_value(v)}" for k, v in table["core"].items()]
    for layer in table["layer"]:
        lines += ["", "[[cable.layer]]"] + [f"{k} = {_value(v)}" for k, v in layer.items()]
    for name in SECTIONS:
        lines += ["", f"[{name}]"]
        for key, value in _section_items(case, name):
            if name == "output" and key == "folder" and folder is not None:
                value = str(folder)
            lines.append(f"{key} = {_value(value)}")
    return "\n".join(lines) + "\n"
