"""Where the time of one Newton iteration goes at Cardinal size (1 m, 61 wires, ~7,400 pairs).

Run: .venv/bin/python benchmarks/newton_iteration.py [normal] [length_m]
Contacts use the seed paper's penalty compliance (compliance = "penalty"), as in the README table.
Pulls the strand to 40 kN, then measures the Newton iterations of two lateral steps (250 N each,
friction on, so the contact is in a mixed stick/slip state) and prints the time per iteration split
into beam assembly, contact kernels, insertion into PETSc objects and the LU solve. The last line
reads ``contact share of a Newton iteration: X %``.
"""

import strand  # noqa: F401

# isort: split

import sys
import time

from harness import peak_mib, stamp

from strand.cable.description import cardinal
from strand.cable.geometry import build_geometry
from strand.model.contact_settings import ContactSettings
from strand.model.problem import StrandProblem
from strand.setups import SaddleTest
from strand.solver import LoadStepper, NewtonOptions


def main(normal: str = "director", length: float = 1.0) -> None:
    print(f"stamp: {stamp()}\n")
    t0 = time.perf_counter()
    geometry = build_geometry(cardinal(), length, 4e-3)
    problem = StrandProblem(
        geometry,
        ContactSettings(normal=normal, compliance="penalty"),
        NewtonOptions(atol=1e-3),
        setup=SaddleTest,
    )
    t_setup = time.perf_counter() - t0
    stepper = LoadStepper(problem.solver, 10e3, 100.0)
    stepper.ramp(problem.setup.set_tension, 0.0, 40e3, "tension")
    solver = problem.solver
    solver.timings = dict.fromkeys(solver.timings, 0.0)
    its = 0
    for P in (250.0, 500.0):
        problem.setup.set_lateral(P)
        result = solver.solve()
        assert result.converged, result.reason
        solver.commit()
        its += result.iterations
    # SNES evaluates the residual once more than the Jacobian: per iteration, count both
    tm = {k: v / its for k, v in solver.timings.items()}
    contact = tm["terms"] + tm["insert"]
    beam = tm["residual"] + tm["jacobian"] - contact
    lu = tm["solve"] - tm["residual"] - tm["jacobian"]
    total = tm["solve"]
    peak = peak_mib()
    n_pairs = sum(len(g) for g in problem.contact)
    nnz = solver.A.getInfo()["nz_used"]
    print(
        f"Cardinal, L = {length} m, {problem.w.x.array.size} unknowns, {n_pairs} pairs, "
        f"normal = {normal}, matrix non-zeros {nnz:.3g}; set-up {t_setup:.1f} s, "
        f"tension steps {[r.iterations for r in stepper.history]}, {its} lateral iterations"
    )
    print(f"{'part':28s} {'s / iteration':>14s} {'share':>7s}")
    rows = [
        ("beam assembly (F and J)", beam),
        ("contact kernels", tm["terms"]),
        ("insertion into PETSc", tm["insert"]),
        ("LU factorisation + solve", lu),
        ("total", total),
    ]
    for name, value in rows:
        print(f"{name:28s} {value:14.3f} {100 * value / total:6.1f} %")
    print(f"peak memory {peak:.0f} MiB")
    print(f"contact share of a Newton iteration: {100 * contact / total:.1f} %")


if __name__ == "__main__":
    from strand.beam.parallel import serial_only

    serial_only("this benchmark (benchmarks/parallel.py measures distributed runs)")
    main(*(sys.argv[1:2] or ["director"]), *[float(a) for a in sys.argv[2:3]])
