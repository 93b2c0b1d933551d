"""3D rigid-body response on MuJoCo: any structure of rigid bodies (blocks, multi-drum columns)
rocking, sliding, wobbling and lifting off.

* :func:`simulate_structure` -> :class:`Response3D` (xarray) -- the one engine (:mod:`.simulate`:
  the entry; :mod:`.integrate`: the loop and ``BLAST_MODES``; :mod:`.record`: states to the
  response); a single block is its one-body case (its planar view:
  :mod:`blastscale.analysis.block3d_similarity`); initial tilt and velocity: :mod:`.initial`.
* :func:`reference_factors` -- the engine's reference units (10 m, 9.81 m/s^2), the one place
  where a structure's absolute size is removed (:mod:`.reference`);
  :func:`default_contact` -- scale-consistent contact defaults.
* :class:`ContactSettings` -- contact, time step and solver in physical terms, ``.scaled(factors)``.
* :func:`structure_scene` / :func:`block_scene` / :func:`build_scene` -- the MuJoCo model built
  from the geometry (optionally tilted onto a base edge).
* :func:`step_forces` -- the paper's Method A blast force, exact impulse per time step.
* :mod:`.loads` -- the load interface (:class:`LoadStrategy`), :class:`MethodA`,
  :class:`PerturbedLoad`; :mod:`.load_methods` -- :func:`make_load` (A, B, C by name).
* :func:`pivot_friction_threshold` -- least friction for pivoting without slip under an impulse.
* :func:`check_simulable` -- the engine's ranges of lengths, masses and time steps.
* :func:`quaternion_to_matrix`, :func:`tilt_angle` -- rotations of recorded bodies.

The engine writes no files (:func:`blastscale.io.histories.write_netcdf` does).

MuJoCo is imported lazily, inside the functions that need it.
"""

from .blast_force import step_forces
from .contact import ContactSettings, default_contact
from .contact_ranges import CONES, SOLVERS
from .integrate import BLAST_MODES, SETTLE_TIME_CONSTANTS
from .load_methods import LOAD_METHODS, make_load, register_load_method
from .loads import LoadStrategy, MethodA, PerturbedLoad
from .model import BodySpec, Scene, block_scene, build_scene, structure_scene
from .reference import reference_factors
from .results import Response3D
from .rotations import quaternion_to_matrix, tilt_angle
from .shapes import BoxShape, FrontFace, PrismShape
from .simulate import check_simulable, pivot_friction_threshold, simulate_structure

__all__ = [
    "BLAST_MODES",
    "BodySpec",
    "BoxShape",
    "CONES",
    "ContactSettings",
    "FrontFace",
    "PrismShape",
    "Response3D",
    "LOAD_METHODS",
    "LoadStrategy",
    "MethodA",
    "PerturbedLoad",
    "SETTLE_TIME_CONSTANTS",
    "SOLVERS",
    "Scene",
    "block_scene",
    "build_scene",
    "check_simulable",
    "default_contact",
    "pivot_friction_threshold",
    "make_load",
    "quaternion_to_matrix",
    "reference_factors",
    "register_load_method",
    "simulate_structure",
    "step_forces",
    "structure_scene",
    "tilt_angle",
]
