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
# This demo runs a short version of strand's main job: a 0.4 m piece of the Cardinal ACSR
# conductor (61 wires in five layers), pulled to 40 kN, then bent back and forth by a saddle load
# at midspan. Every wire is a geometrically exact Reissner beam; wires touch at fixed node pairs
# (small sliding), the seed paper's element, here with the contact compliance of contact mechanics:
# a Hertz normal force (crossed cylinders, or cylinders side by side between the core and layer 1)
# and Coulomb friction whose stick stiffness is Mindlin's.
#
# Units are SI (m, N, Pa, rad). The demo also runs distributed, `mpirun -n 2 python
# demo_strand_bending.py`: every rank runs the script on its slab of the strand, and rank 0 prints
# and draws (`say` and `rank0` below).

# +
import strand  # noqa: F401  (loads the dolfinx wheel's libraries before mpi4py/petsc4py)

# isort: split

import tomllib
from importlib import resources

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from strand import bending_stiffness_bounds, fibre_model, is_root
from strand.app.case import case_from_dict
from strand.app.run import run_case

rank0 = is_root()


def say(*text):
    """``print`` on rank 0 only."""
    if rank0:
        print(*text)


# -

# ## The case
#
# A case is a handful of settings over strand's defaults (`strand run --help` lists them all).
# Here: the built-in Cardinal cable, a 0.4 m span, and a lateral cycle of ±1.5 kN, with contact
# between the layers' crossings only: strand's default also presses the neighbouring wires of
# each layer against each other (`[contact] same_layer = "packed"`), which stiffens the strand in
# stick and costs several times as many Newton iterations. The same table in a TOML file gives
# the same run from the command line: `strand run my_case.toml`.

settings = {
    "cable": "cardinal",
    "mesh": {"length": 0.4},
    "load": {"tension": 40e3, "lateral": 1500.0, "cycle": [1.0, 0.0, -1.0, 0.0]},
    "steps": {"lateral": 250.0, "lateral_max": 400.0},
    "contact": {"same_layer": "off"},
}
case = case_from_dict(settings, source="demo")
say(case.contact)

# ## Run
#
# The runner builds the strand mesh (a node at every contact point), the contact pairs, the end
# conditions (clamped at z = 0; at z = L a rigid section under the tension force) and the saddle
# load, then ramps the loads with Newton's method. One line per converged load step shows the
# progress; results are written as the run goes.

result = run_case(case, "results/demo_strand_bending", overwrite=True)

# ## Tension: the fibre model
#
# After tensioning, the wire forces agree with the classical fibre model (wires as helical bars
# stretched by ε cos²α) to within about 7 %. The fibre model takes the contacts as rigid; here the
# aluminium crossings flatten by a few µm (Hertz), the outer layers settle inwards and shed a
# little load to the steel core and layer 1, which carry more than the fibre model says.

reference = fibre_model(case.cable, case.load.tension)
t = result.tensioned
middle = np.abs(t.z - 0.2) < 0.1
for layer, expected in enumerate(reference["wire_force"]):
    model = t.axial[middle & (t.layer == layer)].mean()
    say(f"layer {layer}: {model:7.1f} N (fibre model {expected:7.1f} N)")
    assert abs(model / expected - 1) < 0.08
    if layer < 2:  # steel: more than with rigid contacts
        assert model > expected

# ## Bending: stick, slip and hysteresis
#
# On a span this short the layers barely slip at 1.5 kN with the cable's friction coefficients
# (μ = 0.3 and 0.5): the cycle is nearly elastic. Friction decides it: the same case with μ = 0.1
# slips, its bending stiffness falls as it is loaded, and a deflection remains when the load comes
# back to zero: a hysteresis loop. This run writes no fields and no fatigue histories: its tables
# and figures are all we look at.

cable = tomllib.loads((resources.files("strand.cable.data") / "cardinal.toml").read_text())
for table in (cable["core"], *cable["layer"]):
    table["friction"] = 0.1
quiet = {"output": {"fields": False}, "fatigue": {"outputs": False}}
slippery = run_case(
    case_from_dict({**settings, "cable": cable, **quiet}, source="demo, μ = 0.1"),
    "results/demo_strand_bending/low_friction",
    overwrite=True,
)

fig, ax = plt.subplots(figsize=(6, 4.5))
for run, label in ((result, "μ = 0.3 / 0.5 (Cardinal)"), (slippery, "μ = 0.1")):
    lateral = run.cycle_steps
    ax.plot(
        [0.0] + [1e3 * s.state.deflection for s in lateral],
        [0.0] + [s.load / 1e3 for s in lateral],
        "o-",
        ms=3,
        label=label,
    )
    residual = [1e3 * s.state.deflection for s in run.unloaded_steps]
    peak = max(1e3 * abs(s.state.deflection) for s in lateral)
    say(f"{label}: peak {peak:.3f} mm, back at P = 0: {residual[0]:+.3f}, {residual[1]:+.3f} mm")
ax.set_xlabel("midspan deflection (mm)")
ax.set_ylabel("lateral load (kN)")
ax.legend()
ax.grid(alpha=0.3)
if rank0:
    fig.savefig("results/demo_strand_bending/loops.png", dpi=110)

lateral = slippery.cycle_steps
assert abs(lateral[-1].state.deflection) > 0.05 * max(abs(s.state.deflection) for s in lateral)
assert not result.failure and not slippery.failure

# ## Softening between the stiffness bounds
#
# A strand's bending stiffness lies between two bounds: EI_min, every wire bending about its own
# axis (all layers slipping), and EI_max, the strand bending as one section (all stuck). The
# midspan's moment and curvature (`moment_curvature.csv`, here the run's records) give the
# secant stiffness M/κ. Along the first leg of the μ = 0.1 cycle it stays between the bounds
# and falls at every step as slip spreads; at the reversal the layers stick again (Masing), so
# the first unloading step is stiffer than the last loading one by more than half again.

ei_min, ei_max = bending_stiffness_bounds(case.cable)
measures = [row.measures for row in slippery.bending]
P = np.array([m.lateral for m in measures])
kappa = np.array([m.curvature for m in measures])
M = np.array([m.moment for m in measures])
peak = int(np.argmax(P))  # the end of the first leg, at +1.5 kN
secant = M[: peak + 1] / kappa[: peak + 1]
unloading = (M[peak] - M[peak + 1]) / (kappa[peak] - kappa[peak + 1])
last_loading = (M[peak] - M[peak - 1]) / (kappa[peak] - kappa[peak - 1])
say(
    f"M/κ along the first leg: {secant[0]:.0f} → {secant[-1]:.0f} N m² (bounds {ei_min:.1f}, "
    f"{ei_max:.0f}); at the reversal {unloading:.0f} N m² against {last_loading:.0f} before it"
)
assert np.all((secant > ei_min) & (secant < ei_max)), secant
assert np.all(np.diff(secant) < 0), secant
assert unloading > 1.5 * last_loading

# The pictures are in `results/demo_strand_bending/`: `loops.png` above, and for each run
# `load_deflection.png`, `moment_curvature.png`, `axial_force_sectors.png`,
# `axial_force_change.png` and `deformed_axial_force.png`; the fields of the first run are in
# `fields.xdmf` for ParaView.

# ## Exercises
#
# 1. **The quick case's bounds.** What are the bending stiffness bounds of the README's quick
#    case, the 1+6 steel strand of `cases/quick_1x6.toml`? Use `bending_stiffness_bounds`.
#    *Answer:* $EI_{min}$ = **7.9** N m² and $EI_{max}$ = **59.8** N m²: stuck, the strand is
#    almost eight times stiffer than its wires bending each about its own axis.
# 2. **Who carries the tension?** With the fibre model, what share of Cardinal's 40 kN do its
#    seven steel wires carry (core and layer 1)? Sum $n\cos\alpha\,F$ over the two layers.
#    *Answer:* **28.3** %, for 7 of the 61 wires: steel is three times as stiff as aluminium.
