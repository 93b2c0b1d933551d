"""3D rigid-body response on MuJoCo: any structure of rigid bodies (blocks, multi-drum columns)
rocking, sliding, wobbling and lifting off.

* :func:`simulate_structure` -> :class:`Response3D` (xarray) -- the one engine;
  :func:`default_contact` -- scale-consistent contact defaults.

* :class:`ContactSettings` -- contact, time step and solver in physical terms, ``.scaled(lambda)``.
* :func:`block_scene` / :func:`build_scene` -- the MuJoCo model built from the geometry.
* :func:`step_forces` -- the paper's Method A blast force, exact impulse per time step.
* :mod:`.loads` -- the load interface (:class:`LoadStrategy`), :class:`MethodA`, :func:`make_load`.
* :class:`Block3DSimulator` / :func:`simulate_block` -- run and record; :class:`Block3DResult`.
* :func:`pivot_friction_threshold` -- least friction for pivoting without slip under an impulse.

MuJoCo is imported lazily, inside the functions that need it.
"""

from .blast_force import step_forces
from .contact import CONES, SOLVERS, ContactSettings, default_contact
from .load_methods import LOAD_METHODS, make_load, register_load_method
from .loads import LoadStrategy, MethodA, PerturbedLoad
from .model import BodySpec, BoxShape, FrontFace, PrismShape, Scene, block_scene, build_scene, structure_scene
from .results import Block3DResult, Response3D, quaternion_to_matrix, tilt_angle
from .simulate import (
    SETTLE_TIME_CONSTANTS,
    Block3DSimulator,
    check_simulable,
    pivot_friction_threshold,
    simulate_block,
    simulate_structure,
)

__all__ = [
    "Block3DResult",
    "Block3DSimulator",
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
    "register_load_method",
    "simulate_block",
    "simulate_structure",
    "step_forces",
    "structure_scene",
    "tilt_angle",
]
