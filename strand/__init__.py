"""strand: wire-by-wire FEniCSx simulation of spiral strand cables.

Units are SI throughout: m, N, Pa, rad (contact stiffnesses in N/m).

Two layers. The library, ``strand`` outside ``strand.app``, is what a FEniCSx script imports:
contact between beams (``strand.contact``), the nonlinear problem and load stepping
(``strand.solver``), what any beam run needs (MPI helpers, distribution, field output:
``strand.beam``), cables, their geometry and meshes (``strand.cable``), the model of a strand
(``strand.model``) and its test set-ups (``strand.setups``), the analytical references
(``strand.analytical``) and the fatigue physics (``strand.fatigue``); the beam forms are the
package ``forms``. The application, ``strand.app``, runs a case file into a folder of results
(``strand run``); the library never imports it.

The library's public API is importable from here, ``from strand import beam_space,
NonlinearProblem``: each name is loaded from its module on first use (``_API``), so that
``import strand``, which must come before dolfinx, stays light.
"""

from __future__ import annotations

import importlib
import importlib.util
import sys
from pathlib import Path
from typing import TYPE_CHECKING

try:  # the PyPI wheel of dolfinx must load its MPI/PETSc libraries first
    import dolfinx_solver  # noqa: F401
except ImportError:  # conda/apt dolfinx: nothing to do
    pass


def _check_forms() -> None:
    """Raise ``ImportError`` in one line when ``import forms`` would not load strand's beam
    forms, the package ``forms`` beside ``strand``, but a user's own ``forms.py`` (the obvious
    name for a file of UFL forms) earlier on ``sys.path``: every module of strand that imports
    the beam forms would otherwise fail on a name missing from it."""
    try:
        spec = importlib.util.find_spec("forms")
    except (ImportError, ValueError):  # a module without a spec: leave it to the import
        return
    ours = Path(__file__).resolve().parent.parent / "forms"
    if spec is None or ours.is_dir() and spec.origin is None and "forms" not in sys.modules:
        # none, or a bare folder named forms (a namespace package, which an editable install's
        # finder would let win over strand's): load strand's own under its name
        _load_ours(ours)
        return
    if spec.origin is None:
        return
    found = Path(spec.origin).resolve()
    if found != ours / "__init__.py":
        shadow = found.parent if found.name == "__init__.py" else found
        raise ImportError(
            f"{shadow} shadows strand's beam forms (the package 'forms', {ours}): rename it, "
            f"e.g. to my_{shadow.name}, and import it under its new name"
        )


def _load_ours(ours: Path) -> None:
    """Import strand's package ``forms`` from ``ours`` (its folder) as ``forms``."""
    init = ours / "__init__.py"
    if not init.exists():
        return
    spec = importlib.util.spec_from_file_location(
        "forms", init, submodule_search_locations=[str(ours)]
    )
    assert spec is not None and spec.loader is not None  # a .py file that exists: always
    module = importlib.util.module_from_spec(spec)
    sys.modules["forms"] = module
    spec.loader.exec_module(module)


_check_forms()

__version__ = "0.1.0"

#: the public API: name → the module it is loaded from
_API = {
    # contact between beams
    "BeamNodes": "strand.contact",
    "ContactError": "strand.contact",
    "ElasticSlip": "strand.contact",
    "FrictionLaw": "strand.contact",
    "HertzLineLaw": "strand.contact",
    "HertzPointLaw": "strand.contact",
    "LinePenaltyLaw": "strand.contact",
    "Mindlin": "strand.contact",
    "MindlinDeresiewicz": "strand.contact",
    "NodeChains": "strand.contact",
    "NodePairs": "strand.contact",
    "NormalLaw": "strand.contact",
    "PenaltyLaw": "strand.contact",
    "SlidingGroup": "strand.contact",
    "SlidingWindowError": "strand.contact",
    "beam_nodes": "strand.contact",
    "candidate_pairs": "strand.contact",
    "candidate_stencils": "strand.contact",
    "contact_terms": "strand.contact",
    "dof_values": "strand.contact",
    "hertz_laws": "strand.contact",
    "hertz_mindlin": "strand.contact",
    "locate_nodes": "strand.contact",
    "node_pairs": "strand.contact",
    "resolve_normal": "strand.contact",
    "sliding_terms": "strand.contact",
    "ContactGroup": "strand.contact.element",
    # the nonlinear problem, load stepping and displacement control
    "NonlinearProblem": "strand.solver",
    "PairTerms": "strand.solver",
    "NodalLoad": "strand.solver",
    "HistoryState": "strand.solver",
    "InternalVariables": "strand.solver",
    "NewtonOptions": "strand.solver",
    "NewtonResult": "strand.solver",
    "NewtonConvergence": "strand.solver",
    "LoadStepper": "strand.solver",
    "ErrorControl": "strand.solver",
    "StepRecord": "strand.solver",
    "RampState": "strand.solver",
    "LoadStepFailure": "strand.solver",
    "RunInterrupted": "strand.solver",
    "Interrupt": "strand.solver",
    "DisplacementControl": "strand.solver.displacement_control",
    # cables, their geometry, meshes and pictures
    "Cable": "strand.cable.description",
    "Wire": "strand.cable.description",
    "Layer": "strand.cable.description",
    "CableError": "strand.cable.description",
    "load_cable": "strand.cable.description",
    "built_in_cables": "strand.cable.description",
    "built_in_cable": "strand.cable.description",
    "cardinal": "strand.cable.description",
    "judge120": "strand.cable.description",
    "StrandGeometry": "strand.cable.geometry",
    "build_geometry": "strand.cable.geometry",
    "polyline_mesh": "strand.cable.mesh",
    "straight_beam_mesh": "strand.cable.mesh",
    "beam_space": "strand.cable.mesh",
    "CableMesh": "strand.cable.mesh",
    "cable_mesh": "strand.cable.mesh",
    "write_centrelines": "strand.cable.mesh",
    "geometry_to_gmsh": "strand.cable.mesh",
    "mesh_from_gmsh": "strand.cable.mesh",
    "offscreen_plotter": "strand.cable.pictures",
    "tubes": "strand.cable.pictures",
    "strand_picture": "strand.cable.pictures",
    # the model of a strand, its load programmes and results
    "StrandModel": "strand.model.model",
    "ContactSettings": "strand.model.contact_settings",
    "StrandProblem": "strand.model.problem",
    "LoadProgramme": "strand.model.programme",
    "Stage": "strand.model.programme",
    "cycle_stages": "strand.model.programme",
    "run_programme": "strand.model.programme",
    "section_resultants": "strand.model.cell_results",
    # the analytical references a run is compared with
    "fibre_model": "strand.analytical.fibre",
    "bending_stiffness_bounds": "strand.analytical.fibre",
    # what any beam run needs: field output, distribution, MPI helpers
    "FieldWriter": "strand.beam.fields",
    "slab_partitioner": "strand.beam.partition",
    "is_root": "strand.beam.parallel",
    "serial_only": "strand.beam.parallel",
    "abort_on_error": "strand.beam.parallel",
    # test set-ups
    "TestSetup": "strand.setups",
    "PenaltyLinks": "strand.setups",
    "SaddleTest": "strand.setups",
    "UniformBendingTest": "strand.setups",
    "TensionCycleTest": "strand.setups.tension_cycle",
    "FairleadTest": "strand.setups.fairlead",
}

__all__ = ["__version__", *_API]


def __getattr__(name: str):
    """The public name ``name``, loaded from its module (``_API``) on first use."""
    try:
        module = _API[name]
    except KeyError:
        raise AttributeError(f"module 'strand' has no attribute {name!r}") from None
    value = globals()[name] = getattr(importlib.import_module(module), name)
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_API})


if TYPE_CHECKING:  # the same names, for type checkers and editors (``X as X``: re-exported)
    from .analytical.fibre import bending_stiffness_bounds as bending_stiffness_bounds
    from .analytical.fibre import fibre_model as fibre_model
    from .beam.fields import FieldWriter as FieldWriter
    from .beam.parallel import abort_on_error as abort_on_error
    from .beam.parallel import is_root as is_root
    from .beam.parallel import serial_only as serial_only
    from .beam.partition import slab_partitioner as slab_partitioner
    from .cable.description import Cable as Cable
    from .cable.description import CableError as CableError
    from .cable.description import Layer as Layer
    from .cable.description import Wire as Wire
    from .cable.description import built_in_cable as built_in_cable
    from .cable.description import built_in_cables as built_in_cables
    from .cable.description import cardinal as cardinal
    from .cable.description import judge120 as judge120
    from .cable.description import load_cable as load_cable
    from .cable.geometry import StrandGeometry as StrandGeometry
    from .cable.geometry import build_geometry as build_geometry
    from .cable.mesh import CableMesh as CableMesh
    from .cable.mesh import beam_space as beam_space
    from .cable.mesh import cable_mesh as cable_mesh
    from .cable.mesh import geometry_to_gmsh as geometry_to_gmsh
    from .cable.mesh import mesh_from_gmsh as mesh_from_gmsh
    from .cable.mesh import polyline_mesh as polyline_mesh
    from .cable.mesh import straight_beam_mesh as straight_beam_mesh
    from .cable.mesh import write_centrelines as write_centrelines
    from .cable.pictures import offscreen_plotter as offscreen_plotter
    from .cable.pictures import strand_picture as strand_picture
    from .cable.pictures import tubes as tubes
    from .contact import BeamNodes as BeamNodes
    from .contact import ContactError as ContactError
    from .contact import ElasticSlip as ElasticSlip
    from .contact import FrictionLaw as FrictionLaw
    from .contact import HertzLineLaw as HertzLineLaw
    from .contact import HertzPointLaw as HertzPointLaw
    from .contact import LinePenaltyLaw as LinePenaltyLaw
    from .contact import Mindlin as Mindlin
    from .contact import MindlinDeresiewicz as MindlinDeresiewicz
    from .contact import NodeChains as NodeChains
    from .contact import NodePairs as NodePairs
    from .contact import NormalLaw as NormalLaw
    from .contact import PenaltyLaw as PenaltyLaw
    from .contact import SlidingGroup as SlidingGroup
    from .contact import SlidingWindowError as SlidingWindowError
    from .contact import beam_nodes as beam_nodes
    from .contact import candidate_pairs as candidate_pairs
    from .contact import candidate_stencils as candidate_stencils
    from .contact import contact_terms as contact_terms
    from .contact import dof_values as dof_values
    from .contact import hertz_laws as hertz_laws
    from .contact import hertz_mindlin as hertz_mindlin
    from .contact import locate_nodes as locate_nodes
    from .contact import node_pairs as node_pairs
    from .contact import resolve_normal as resolve_normal
    from .contact import sliding_terms as sliding_terms
    from .contact.element import ContactGroup as ContactGroup
    from .model.cell_results import section_resultants as section_resultants
    from .model.contact_settings import ContactSettings as ContactSettings
    from .model.model import StrandModel as StrandModel
    from .model.problem import StrandProblem as StrandProblem
    from .model.programme import LoadProgramme as LoadProgramme
    from .model.programme import Stage as Stage
    from .model.programme import cycle_stages as cycle_stages
    from .model.programme import run_programme as run_programme
    from .setups import PenaltyLinks as PenaltyLinks
    from .setups import SaddleTest as SaddleTest
    from .setups import TestSetup as TestSetup
    from .setups import UniformBendingTest as UniformBendingTest
    from .setups.fairlead import FairleadTest as FairleadTest
    from .setups.tension_cycle import TensionCycleTest as TensionCycleTest
    from .solver import ErrorControl as ErrorControl
    from .solver import HistoryState as HistoryState
    from .solver import InternalVariables as InternalVariables
    from .solver import Interrupt as Interrupt
    from .solver import LoadStepFailure as LoadStepFailure
    from .solver import LoadStepper as LoadStepper
    from .solver import NewtonConvergence as NewtonConvergence
    from .solver import NewtonOptions as NewtonOptions
    from .solver import NewtonResult as NewtonResult
    from .solver import NodalLoad as NodalLoad
    from .solver import NonlinearProblem as NonlinearProblem
    from .solver import PairTerms as PairTerms
    from .solver import RampState as RampState
    from .solver import RunInterrupted as RunInterrupted
    from .solver import StepRecord as StepRecord
    from .solver.displacement_control import DisplacementControl as DisplacementControl
