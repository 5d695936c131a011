"""Where each layer's pressure goes, in a run's summary and figure: per helical layer, at the
tensioned state and at the largest cycle load, the radial load on the crossings below, the share
its same-layer ring carries, the fibre model's pressure and the state of its gap
(``strand.model.layer_pressure``; ``RunResult.tensioned_layers`` and ``peak_layers``). Units:
N/m (per metre of strand), N, µm."""

from __future__ import annotations

from pathlib import Path

import numpy as np

__all__ = ["layer_pressure_lines", "layer_pressure_figure"]


def _table(title: str, layers) -> list[str]:
    lines = [
        title,
        f"  layer {'fibre':>7}  {'crossings below':>15}  {'ring (hoop H)':>16}  "
        f"{'gap | bounding pairs':>22}  gap",
    ]
    for p in layers:
        share = p.crossings_below / p.fibre if p.fibre else np.nan
        gap = "closed" if p.gap_closed else "open"
        if np.isnan(p.gap_min):
            gap_text = f"{'no same-layer pairs':>22}"
        else:
            gap_text = (
                f"{p.gap_force:7.0f} | {p.bounding[0]:6.0f} {p.bounding[1]:6.0f}  "
                f"{gap} ({1e6 * p.gap_min:+.2f} µm)"
            )
        lines.append(
            f"  {p.layer:5d} {p.fibre:7.0f}  {p.crossings_below:7.0f} ({100 * share:3.0f} %)  "
            f"{p.ring:7.0f} ({p.hoop:6.0f})  {gap_text}"
        )
    return lines


def layer_pressure_lines(result, peak_text: str = "") -> list[str]:
    """The summary's table of where each layer's pressure goes (N/m of strand, middle half), at
    the tensioned state and at the largest cycle load (``peak_text``: that load, as the kind
    writes it); none without the tensioned state."""
    if not result.tensioned_layers:
        return []
    lines = [
        "where each layer's pressure goes, N/m of strand over the middle half: fibre model "
        "n T sin²α/(r cos α), radial load on the crossings below, same-layer ring's",
        "  (hoop force H per m of strand, ring ≈ 2π H), line force across the layer's gap "
        "and its two bounding contacts; equilibrium: fibre + the layer above's = below + ring",
    ]
    lines += _table("  tensioned state:", result.tensioned_layers)
    if result.peak_layers:
        lines += _table(
            f"  at the largest load{' ' + peak_text if peak_text else ''}:", result.peak_layers
        )
    return lines


def layer_pressure_figure(result, title: str, peak_text: str = "", note: str = "") -> Path | None:
    """``layer_pressure.png``: per layer, bars of the crossings below, the same-layer ring and
    the fibre model (N/m of strand), at the tensioned state and at the largest load; None
    without the tensioned state."""
    if not result.tensioned_layers:
        return None
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .plots import save_figure

    states = [("tensioned state", result.tensioned_layers)]
    if result.peak_layers:
        states.append((f"largest load {peak_text}".strip(), result.peak_layers))
    fig, axes = plt.subplots(
        1, len(states), figsize=(5.5 * len(states), 4.2), squeeze=False, sharey=True
    )
    width = 0.27
    for ax, (name, layers) in zip(axes[0], states, strict=True):
        x = np.arange(len(layers))
        values = [
            ("crossings below", "tab:blue", [p.crossings_below for p in layers]),
            ("same-layer ring", "tab:orange", [p.ring for p in layers]),
            ("fibre model", "0.6", [p.fibre for p in layers]),
        ]
        for k, (label, colour, v) in enumerate(values):
            ax.bar(x + (k - 1) * width, np.asarray(v) / 1e3, width, color=colour, label=label)
        for i, p in enumerate(layers):
            if not np.isnan(p.gap_min):
                ax.annotate(
                    "gap closed" if p.gap_closed else "gap open",
                    (i, 0),
                    fontsize=7,
                    xytext=(0, -22),
                    textcoords="offset points",
                    ha="center",
                )
        ax.set_xticks(x, [f"layer {p.layer}" for p in layers])
        ax.set_title(name)
        ax.grid(alpha=0.3, axis="y")
    axes[0, 0].set_ylabel("radial load per metre of strand (kN/m)")
    axes[0, 0].legend(fontsize=8)
    fig.suptitle(f"{title}: where each layer's pressure goes (middle half)")
    return save_figure(fig, Path(result.folder) / "layer_pressure.png", note)
