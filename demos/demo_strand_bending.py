# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
#       format_version: '1.5'
# ---

# # A strand under tension and bending, wire by wire
#
# This demo runs a short version of strand's main job: a 0.2 m piece of the Cardinal ACSR
# conductor (61 wires in five layers), pulled to 40 kN, then bent back and forth by a saddle load
# at midspan. Every wire is a geometrically exact Reissner beam; wires touch at fixed node pairs
# (small sliding) with a penalty normal force and Coulomb friction, the seed paper's element.
#
# Units are SI (m, N, Pa, rad).

# +
import strand  # noqa: F401  (loads the dolfinx wheel's libraries before mpi4py/petsc4py)

# isort: split

import numpy as np

from strand.case import case_from_dict
from strand.post import fibre_model
from strand.run import run_case

# -

# ## The case
#
# A case is a handful of settings over strand's defaults (`strand run --help` lists them all).
# Here: the built-in Cardinal cable, a 0.2 m span, and a lateral cycle of ±1 kN. The same table
# in a TOML file gives the same run from the command line: `strand run my_case.toml`.

case = case_from_dict(
    {
        "cable": "cardinal",
        "mesh": {"length": 0.2},
        "load": {"tension": 40e3, "lateral": 1000.0, "cycle": [1.0, 0.0, -1.0, 0.0]},
        "steps": {"lateral": 250.0},
    },
    source="demo",
)
print(case.contact)

# ## Run
#
# The runner builds the strand mesh (a node at every contact point), the contact pairs, the end
# conditions (clamped at z = 0; at z = L a rigid section under the tension force) and the saddle
# load, then ramps the loads with Newton's method. One line per converged load step shows the
# progress; results are written as the run goes.

result = run_case(case, "results/demo_strand_bending")

# ## What came out
#
# After tensioning, the wire forces agree with the classical fibre model (wires as helical bars
# stretched by ε cos²α) to within a few per cent; the contact element adds the radial compliance
# of the contacts that the fibre model ignores.

reference = fibre_model(case.cable, case.load.tension)
t = result.tensioned
middle = np.abs(t.z - 0.1) < 0.05
for layer, expected in enumerate(reference["wire_force"]):
    model = t.axial[middle & (t.layer == layer)].mean()
    print(f"layer {layer}: {model:7.1f} N (fibre model {expected:7.1f} N)")
    assert abs(model / expected - 1) < 0.05

# The load–deflection curve is a loop: friction makes the strand stiffer when the load reverses
# than when it grows, and some deflection remains when the load returns to zero. Pictures are in
# `results/demo_strand_bending/`: `load_deflection.png`, `moment_curvature.png`,
# `axial_force_sectors.png`, `axial_force_change.png` and `deformed_axial_force.png`; the fields
# are in `fields.xdmf` for ParaView.

lateral = [s for s in result.steps if s["stage"] != "tension"]
at_zero = [s["deflection"] for s in lateral if s["lateral"] == 0.0]
print("deflection back at P = 0 (mm):", [f"{1e3 * d:+.3f}" for d in at_zero])
assert not result.failure
