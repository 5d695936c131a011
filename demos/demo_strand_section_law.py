# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: light
#       format_version: '1.5'
# ---

# # Your section law in a strand: a layer that softens in tension
#
# The section-law tutorial put a law of one's own into a single beam. Here it goes into every
# wire of a strand run by strand's application: `run_case(case, folder, beam=...)` builds each
# wire's beam by calling `beam(w, section)`, with the strand's unknown `w` and the layers'
# section, whose cell-wise `layer` index (0 the core) lets a law act on one layer only.
#
# **The law.** The wires of layer 1 soften in tension: their axial force follows the initial
# slope $EA$ up to a strain $\varepsilon_s$, then a slope $s\,EA$ ($s < 1$), smoothly,
#
# $$N(\varepsilon) = EA\,\big[s\,\varepsilon + (1 - s)\,\varepsilon_s
#   \tanh(\varepsilon/\varepsilon_s)\big], \qquad
# \psi(\varepsilon) = EA\,\big[\tfrac12 s\,\varepsilon^2 + (1 - s)\,\varepsilon_s^2
#   \ln\cosh(\varepsilon/\varepsilon_s)\big],$$
#
# with $N = \psi'$: a nonlinear elastic law (it unloads along the same curve; the plastic-bending
# tutorial keeps a history). Shear, torsion and bending, and the core, stay linear elastic.
#
# **The closed form.** Pulled by $T$ with its ends held against rotation, a straight strand
# stretches by $\varepsilon$, its core by $\varepsilon$ and each of the $n$ wires of layer 1,
# laid at $\alpha$, by $\varepsilon\cos^2\alpha$ (the fibre model, `strand.fibre_model`, wires as
# helical bars). The wire forces balance the tension along the axis:
#
# $$T = EA_0\,\varepsilon + n\cos\alpha\; N_1(\varepsilon\cos^2\alpha),$$
#
# an increasing function of $\varepsilon$, whose root gives both wire forces. With the linear law
# it is the fibre model, $\varepsilon = T / \sum n EA\cos^3\alpha$. Units: SI.
#
# The script runs on any number of processes (`mpirun -n 2 python demo_strand_section_law.py`)
# with the same result: process 0 prints and draws.

# +
import strand  # noqa: F401  (loads the dolfinx wheel's MPI library first)

# isort: split

from functools import partial
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import ufl
from dolfinx import fem

from forms import ReissnerBeam
from strand import fibre_model, is_root
from strand.app.case import case_from_dict
from strand.app.run import run_case

rank0 = is_root()


def say(*text):
    """``print`` on process 0 only."""
    if rank0:
        print(*text)


# -

# ## The law, on one layer
#
# The subclass of `ReissnerBeam` replaces the axial part of the energy density where the cell's
# `layer` is the softened one, and the axial force `N[0]` with it, so that the run's tables and
# figures read the law's forces. Its parameters are `Constant`s: changing them compiles no new
# kernel. The law does not give Navier's elastic stresses, so it leaves `elastic_stresses`
# undeclared and the case switches the fatigue outputs off (strand would refuse it otherwise).


class SoftLayer(ReissnerBeam):
    """Reissner beams whose wires of layer ``layer`` soften in tension as N(ε) above: initial
    slope EA, final slope ``ratio`` EA past the strain ``eps_s``."""

    def __init__(self, w, section, layer=1, ratio=0.3, eps_s=3e-4):
        super().__init__(w, section)
        mesh = w.function_space.mesh
        self.ratio, self.eps_s = fem.Constant(mesh, ratio), fem.Constant(mesh, eps_s)
        #: 1 on the cells of the softened layer, 0 elsewhere
        self.soft = ufl.conditional(
            ufl.eq(self.section.layer, fem.Constant(mesh, float(layer))), 1.0, 0.0
        )

    def axial_force(self, e):
        s, e_s, EA = self.ratio, self.eps_s, self.section.EA
        softened = EA * (s * e + (1 - s) * e_s * ufl.tanh(e / e_s))
        return self.soft * softened + (1 - self.soft) * EA * e

    def axial_energy(self, e):
        s, e_s, EA = self.ratio, self.eps_s, self.section.EA
        softened = EA * (0.5 * s * e**2 + (1 - s) * e_s**2 * ufl.ln(ufl.cosh(e / e_s)))
        return self.soft * softened + (1 - self.soft) * 0.5 * EA * e**2

    @property
    def N(self):
        G, GA = self.Gamma, self.section.GA
        return ufl.as_vector([self.axial_force(G[0]), GA * G[1], GA * G[2]])

    def strain_energy_density(self):
        G, GA = self.Gamma, self.section.GA
        shear = 0.5 * GA * (G[1] ** 2 + G[2] ** 2)
        return self.axial_energy(G[0]) + shear + 0.5 * ufl.dot(self.K, self.M)


# The softened layer and the law's parameters, and the closed form for the same law in numpy:

soft_layer, ratio, eps_s = 1, 0.3, 3e-4


def wire_force(e, EA, s=ratio, e_s=eps_s):
    """N(ε) of a softened wire of axial stiffness EA (N); s = 1 is the linear law."""
    return EA * (s * e + (1 - s) * e_s * np.tanh(e / e_s))


def closed_form(cable, T, layer=soft_layer, s=ratio, e_s=eps_s):
    """The strand's strain and each layer's wire force (N) at the tension T (N), the wires of
    ``layer`` softened, by bisection on T(ε) above."""
    laws = [
        (lay.wires or 1, np.cos(lay.alpha), lay.wire.E * lay.wire.area, i == layer)
        for i, lay in enumerate(cable.layers)
    ]

    def forces(eps):
        return [wire_force(eps * c**2, EA, s if soft else 1.0, e_s) for n, c, EA, soft in laws]

    def tension(eps):
        return sum(n * c * f for (n, c, _, _), f in zip(laws, forces(eps), strict=True))

    low, high = 0.0, 10 * T / sum(n * c**3 * EA for n, c, EA, _ in laws) / min(s, 1.0)
    for _ in range(200):
        mid = 0.5 * (low + high)
        low, high = (mid, high) if tension(mid) < T else (low, mid)
    return mid, forces(mid)


# ## The case and the run
#
# The README's quick case, `cases/quick_1x6.toml`: 0.3 m of a 1+6 steel strand (Cardinal's
# core) pulled to 10 kN, here in eight equal steps (`growth = 1`) and without its saddle cycle
# (`cycle = [0.0]`: the cycle's only target is the tensioned state). The same tables in a TOML
# file give the same case. `run_case` takes the law as its `beam` factory, called with
# `(w, section)`: the law's own parameters go in by `functools.partial` (or a lambda).

wire = {"diameter": 3.34e-3, "nu": 0.3}
cable = {
    "name": "1+6 steel (Cardinal's core)",
    "core": {**wire, "E": 210e9, "friction": 0.3},
    "layer": [{**wire, "E": 180e9, "wires": 6, "lay_angle": 6.06, "lay": "S", "friction": 0.5}],
}
settings = {
    "cable": cable,
    "mesh": {"length": 0.3, "h_max": 4e-3},
    "load": {"tension": 10e3, "cycle": [0.0]},
    "steps": {"tension": 1250.0, "growth": 1.0},
    "fatigue": {"outputs": False},
    "output": {"fields": False},
}
case = case_from_dict(settings, source="demo")
folder = Path("results/demo_strand_section_law")
law = partial(SoftLayer, layer=soft_layer, ratio=ratio, eps_s=eps_s)
result = run_case(case, folder, overwrite=True, beam=law)

# The run's summary compares the wire forces with the linear fibre model: the core carries
# far more, layer 1 less. The law's own closed form accounts for both.

# ## Against the closed form
#
# The wire forces in the middle third of the span (away from the ends' clamps), per layer,
# against the closed form with the law, and against the linear fibre model.

T = case.load.tension
strain, exact = closed_form(case.cable, T)
linear = fibre_model(case.cable, T)["wire_force"]
t = result.tensioned
middle = np.abs(t.z - case.mesh.length / 2) < case.mesh.length / 6
model = [t.axial[middle & (t.layer == i)].mean() for i in range(len(exact))]
for i in range(len(exact)):
    say(f"layer {i}: {model[i]:.1f} N, closed form {exact[i]:.1f} N, linear {linear[i]:.1f} N")
    assert abs(model[i] / exact[i] - 1) < 2e-3
assert abs(linear[soft_layer] / exact[soft_layer] - 1) > 0.1  # the law changes the shares
say(
    f"strand strain: {1e6 * strain:.0f} µε, linear {1e6 * T / fibre_model(case.cable, T)['EA']:.0f} µε"
)

# ## Picture
#
# Left, the law of a softened wire, with each tension step's wire strain
# $\varepsilon\cos^2\alpha$ ($\varepsilon$ the stretch of the strand's end over its length) and
# mean wire force; right, both layers' wire forces against the tension. Process 0 reads the
# run's tables, `steps.csv` and `axial_forces.csv`, and draws.

if rank0:
    steps = np.genfromtxt(folder / "steps.csv", delimiter=",", names=True, dtype=None)
    forces = np.genfromtxt(folder / "axial_forces.csv", delimiter=",", names=True)
    mid = np.abs(forces["z_m"] - case.mesh.length / 2) < case.mesh.length / 6
    per_step = np.array(
        [
            [
                forces["N_N"][mid & (forces["step"] == k) & (forces["layer"] == i)].mean()
                for i in (0, 1)
            ]
            for k in steps["step"]
        ]
    )
    lay = case.cable.layers[soft_layer]
    c2, EA1 = np.cos(lay.alpha) ** 2, lay.wire.E * lay.wire.area
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    e = np.linspace(0.0, 1.1 * strain * c2, 100)
    ax1.plot(1e6 * e, EA1 * e, "k:", label="linear, EA")
    ax1.plot(1e6 * e, wire_force(e, EA1), "k-", label="softened law N(ε)")
    ax1.plot(
        1e6 * steps["end_displacement_m"] / case.mesh.length * c2,
        per_step[:, soft_layer],
        "o",
        label=f"strand, layer {soft_layer}",
    )
    title = f"the law of layer {soft_layer}"
    ax1.set(xlabel="wire strain ε cos²α (µε)", ylabel="wire force (N)", title=title)
    ax1.legend()
    tensions = np.linspace(0.0, T, 50)
    curves = np.array([closed_form(case.cable, x)[1] for x in tensions])
    lines = np.array([fibre_model(case.cable, x)["wire_force"] for x in tensions])
    for i, colour, name in ((0, "C0", "core"), (1, "C1", "layer 1")):
        ax2.plot(tensions / 1e3, curves[:, i], "-", color=colour, label=f"{name}, closed form")
        ax2.plot(tensions / 1e3, lines[:, i], ":", color=colour, label=f"{name}, linear law")
        ax2.plot(steps["tension_N"] / 1e3, per_step[:, i], "o", color=colour)
    ax2.set(xlabel="tension T (kN)", ylabel="wire force (N)", title="wire forces: strand (dots)")
    ax2.legend()
    fig.tight_layout()
    fig.savefig(folder / "strand_section_law.png", dpi=110)
    print("picture:", folder / "strand_section_law.png")

# ## Exercises
#
# 1. **Softer still.** Set `ratio = 0.1` (`soft_layer, ratio, eps_s`). Predict layer 1's wire
#    force at 10 kN from the closed form, then run.
#    *Answer:* **846** N by strand and **846** N by the closed form (1141 N with 0.3); the core
#    takes what the layer sheds, **4954** N.
# 2. **Soften the core instead.** Set `soft_layer = 0`.
#    *Answer:* the core carries **924** N, and layer 1 **1521** N, more than the **1399** N of
#    the linear fibre model: the helical wires now take the share the core gives up.
