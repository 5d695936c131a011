"""The closing summary of a run (``summary.txt``): its effort, the tensioned state against the
fibre model, the set-up kind's own lines (``SetupKind.summary_lines``, which the runner hands
in), the bending stiffness bounds, the strand's end reactions (tension, torque, bending moments;
Costello's torque beside them after tension), and any warning or failure. Units: N, N m, N/m,
µε, MPa, s."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..analytical.fibre import bending_stiffness_bounds, fibre_model
from ..cable.geometry import LINE
from ..model.layer_pressure import in_middle_half, layer_wire_forces
from ..model.pair_results import PairResults
from .run_result import RunResult
from .settings import Case

__all__ = [
    "summarize",
    "effort_line",
    "tension_lines",
    "reaction_lines",
    "contact_force_line",
    "layer_stresses",
    "wire_stress_line",
    "yield_warnings",
]

Array = np.ndarray


def summarize(case: Case, result: RunResult, problem, kind_lines: Sequence[str]) -> str:
    """The closing summary: effort, key results, and the tension stage against the fibre model;
    ``kind_lines``: the set-up kind's own (``SetupKind.summary_lines``), after the reactions."""
    lines = [effort_line(result)]
    lines += tension_lines(case, result, problem.model.geometry)
    lines += reaction_lines(case, result)
    lines += kind_lines
    ei_min, ei_max = bending_stiffness_bounds(case.cable)
    lines.append(f"bending stiffness bounds: EI_min {ei_min:.1f} N m², EI_max {ei_max:.0f} N m²")
    for w in result.warnings:
        lines.append(f"warning: {w}")
    if result.failure:
        lines.append(f"{'stopped' if result.interrupted else 'failure'}: {result.failure}")
    return "\n".join(lines) + "\n"


def effort_line(result: RunResult) -> str:
    """The outcome, steps, Newton iterations (converged and failed, the attempts of a step
    that failed included), wall times and folder."""
    its, failed, lus = result.iterations, result.failed_iterations, result.factorisations
    cuts = sum(s.cuts for s in result.steps)
    outcome = "INTERRUPTED" if result.interrupted else "FAILED" if result.failure else "done"
    per_iteration = result.seconds / max(its + failed, 1)
    held = [s for s in result.steps if s.hold in (1, 2)]
    widened = sum(s.hold == 2 for s in held)
    relaxed = sum(s.hold == 3 for s in result.steps)
    stabilised = (
        f", {len(held)} step{'s' * (len(held) > 1)} stabilised"
        f"{f' ({widened} with the wider onset)' if widened else ''} (stabilisation energy "
        f"at most {max(s.stabilisation for s in held):.1e} of the strain energy)"
        if held
        else ""
    )
    if relaxed:
        stabilised += f", {relaxed} step{'s' * (relaxed > 1)} relaxed to rest"
    return (
        f"{outcome}: {len(result.steps)} steps, {its} Newton iterations (+ {failed} in failed "
        f"attempts, {cuts} step cut{'s' * (cuts != 1)}), {lus} LUs{stabilised}, {result.seconds:.0f} s ({per_iteration:.2f} s "
        f"per iteration, set-up {result.setup_seconds:.0f} s); results in {result.folder}"
    )


def tension_lines(case: Case, result: RunResult, geometry) -> list[str]:
    """The last converged tension (the target, or where a failed run stopped) against the fibre
    model: strain and wire forces per layer over the middle half, and the contact forces, at the
    tension's last step (before a load the set-up then holds, such as ``tension_cycle``'s)."""
    t = result.tension_end
    tension_rows = [s for s in result.steps if s.parameter == "tension"]
    if t is None or not tension_rows:
        return []
    tension = tension_rows[-1].load
    ref = fibre_model(case.cable, tension)
    L = case.mesh.length
    strain = tension_rows[-1].state.end_displacement / L
    lines = [
        f"after tension ({tension / 1e3:g} kN)   model    fibre model  diff",
        f"  strain (µε)              {1e6 * strain:8.0f}  {1e6 * ref['strain']:8.0f}  "
        f"{100 * (strain / ref['strain'] - 1):+6.1f} %",
    ]
    forces = layer_wire_forces(t.layer, t.z, t.axial, L, core=True)
    for i, (f, f_ref) in enumerate(zip(forces, ref["wire_force"], strict=True)):
        name = "core" if i == 0 else f"layer {i}"
        lines.append(
            f"  wire force {name:8s} (N)  {f:8.0f}  {f_ref:8.0f}  {100 * (f / f_ref - 1):+6.1f} %"
        )
    lines.append(wire_stress_line(case.cable, t, L))
    lines.append(contact_force_line(geometry, result.tension_end_pairs))
    return lines


def reaction_lines(case: Case, result: RunResult) -> list[str]:
    """The strand's reactions at both ends (``result.reactions``) after tension, with Costello's
    torque of the straight strand with its ends held against rotation beside them, and at the
    largest load of the cycle."""
    from ..analytical import held_end_torque

    tension = [s for s in result.steps if s.parameter == "tension"]
    lines = []
    if tension and tension[-1].number in result.reactions:
        r = result.reactions[tension[-1].number]
        torque = held_end_torque(case.cable, tension[-1].load)
        lines += [
            f"  end reactions: tension {r.end_tension_0 / 1e3:.3f} kN (z = 0), "
            f"{r.end_tension_L / 1e3:.3f} kN (z = L); torque about +z {r.end_torque_0:+.3f} N m "
            f"(z = 0), {r.end_torque_L:+.3f} N m (z = L)",
            f"  Costello, straight strand with ends held against rotation: torque {torque:+.3f} "
            f"N m at z = L ({100 * (r.end_torque_L / torque - 1):+.1f} %)"
            if torque
            else "  Costello: no tension–torque coupling (no helical layer)",
        ]
    peak = result.peak_step
    if peak is not None and peak.load != 0 and peak.number in result.reactions:
        r = result.reactions[peak.number]
        lines.append(
            f"end reactions at the largest {peak.parameter} (step {peak.number}): tension "
            f"{r.end_tension_0 / 1e3:.3f} / {r.end_tension_L / 1e3:.3f} kN, torque "
            f"{r.end_torque_0:+.3f} / {r.end_torque_L:+.3f} N m, moments about x "
            f"{r.end_moment_x_0:+.2f} / {r.end_moment_x_L:+.2f} N m, about y "
            f"{r.end_moment_y_0:+.2f} / {r.end_moment_y_L:+.2f} N m (z = 0 / z = L)"
        )
    return lines


def layer_stresses(cable, cells, length: float) -> Array:
    """Mean axial stress N/A (Pa) of each layer's wires over the middle half of the strand
    (``layer_pressure.layer_wire_forces``)."""
    forces = layer_wire_forces(cells.layer, cells.z, cells.axial, length, core=True)
    return np.array([f / lay.wire.area for f, lay in zip(forces, cable.layers, strict=True)])


def wire_stress_line(cable, cells, length: float) -> str:
    """The mean axial wire stress per layer (MPa) over the middle half of the strand."""
    stress = layer_stresses(cable, cells, length)
    parts = [f"{'core' if i == 0 else f'layer {i}'} {s / 1e6:.0f}" for i, s in enumerate(stress)]
    return "  mean wire stress, middle half (MPa): " + ", ".join(parts)


def yield_warnings(cable, cells) -> list[str]:
    """One warning per layer whose wires' axial stress N/A exceeds the ``yield_stress`` given
    with the cable (bending adds to it at the wire surface)."""
    out = []
    for i, lay in enumerate(cable.layers):
        limit = lay.wire.yield_stress
        mine = cells.layer == i
        if limit is None or not np.any(mine):
            continue
        stress = np.abs(cells.axial[mine]) / lay.wire.area
        k = int(np.argmax(stress))
        if stress[k] > limit:
            name = "core" if i == 0 else f"layer {i}"
            out.append(
                f"{name}: a wire's axial stress reaches {stress[k] / 1e6:.0f} MPa (wire "
                f"{cells.wire[mine][k]}, z = {cells.z[mine][k]:.3g} m), above its yield stress "
                f"{limit / 1e6:.0f} MPa: the elastic wires of the model no longer hold"
            )
    return out


def contact_force_line(geometry, pairs: PairResults) -> str:
    """Mean contact forces per interface over the middle half of the strand: line pairs per metre
    of layer-1 wire (N/m), crossings per crossing (N)."""
    p = geometry.pairs
    z = geometry.points[p.a, 2]
    middle = in_middle_half(z, geometry.length)
    parts = []
    for i in range(len(geometry.cable.layers) - 1):
        sel = middle & (p.interface == i)
        if not np.any(sel):
            continue
        line = p.kind[sel] == LINE
        if np.all(line):
            q = pairs.force[sel].sum() / p.tributary[sel].sum()
            parts.append(f"{i}|{i + 1} {q:.0f} N/m")
        else:
            parts.append(f"{i}|{i + 1} {pairs.force[sel].mean():.1f} N")
    return "  mean contact force, middle half: " + ", ".join(parts)
