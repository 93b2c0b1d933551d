"""Run any structure of rigid bodies on MuJoCo under a blast load and record it.

One path for every structure (:func:`simulate_structure`): N free bodies on a rigid ground
(:func:`~.model.structure_scene`), explicit contact pairs ground-base and between adjacent
bodies (then every body with the ground and with every other body, for falling drums), a
:class:`~.loads.LoadStrategy` giving one wrench per body per step from the current poses,
recorded as a :class:`~.results.Response3D` (xarray). The single block is the one-body case
of that path (its planar view: :mod:`blastscale.analysis.block3d_similarity`).

Time: the structure stands at rest (settled on its soft contacts) until the load's first
arrival; the run integrates ``duration`` seconds from there, and ``time`` in the results is the
time after first arrival (attribute ``first_arrival_time_s``).

The pieces: :mod:`.reference` (the reference units, the one place where absolute size is
removed), :mod:`.model` (the MuJoCo scene), :mod:`.initial` (initial tilt and velocity),
:mod:`.integrate` (the integration loop and how a step's blast impulse enters, ``blast_mode``),
:mod:`.record` (the recorded states as a :class:`~.results.Response3D`). This module is the
entry: the checks of the inputs, the defaults, the warnings, and the call sequence.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from .._validate import BlastscaleInputError, check_choice, check_finite, check_positive, check_range
from ..constants import STANDARD_GRAVITY
from .contact import (
    MAX_TIMESTEP_FRACTION,
    SOFT_CONTACT_FACTOR,
    ContactSettings,
    default_contact,
    structure_length,
)
from .initial import body_velocities, rigid_rocking_velocity
from .integrate import BLAST_MODES, integrate
from .model import Scene
from .record import response_from_states
from .reference import reference_scene
from .results import Response3D
from .shapes import BoxShape

__all__ = [
    "ENGINE_LENGTH_RANGE",
    "ENGINE_MASS_RANGE",
    "check_simulable",
    "pivot_friction_threshold",
    "simulate_structure",
]

#: Lengths [m] the engine accepts (every dimension of the structure): below 0.1 mm the
#: inertia of a stone body (~rho L^5) falls towards MuJoCo's mjMINVAL (1e-15) and the
#: solver's tolerances; above 1 km nothing in this library applies.
ENGINE_LENGTH_RANGE = (1e-4, 1e3)
#: Body masses [kg] the engine accepts (a lighter body crashed MuJoCo with mjMINVAL errors).
ENGINE_MASS_RANGE = (1e-6, 1e12)


def _lengths(structure) -> dict:
    """The structure's lengths by parameter name [m] (``describe()`` keys ending in "_m")."""
    out = {}
    for k, v in structure.describe().items():
        if k.endswith("_m") and v is not None:
            vals = np.atleast_1d(np.asarray(v, dtype=float))
            vals = vals[vals != 0.0]  # an optional length left at 0 (a pier, an overhang) is no length
            if vals.size:
                out[k[:-2].replace("_", " ")] = float(vals.min())
    return out


def check_simulable(structure, contact: ContactSettings, gravity: float) -> None:
    """Raise :class:`BlastscaleInputError` (one line naming the parameter, its value and the
    valid range) unless the engine can run ``structure`` with ``contact``.

    * every length in [1e-4, 1e3] m (:data:`ENGINE_LENGTH_RANGE`);
    * every body mass in [1e-6, 1e12] kg (:data:`ENGINE_MASS_RANGE`);
    * the time step at most ``MAX_TIMESTEP_FRACTION * sqrt(L / g)`` (L the structure's height):
      a step beyond it resolves neither the rocking nor the impacts (semi-implicit Euler), and
      ``ContactSettings`` already demands ``time_constant >= 2 timestep`` (MuJoCo's stability).
    """
    if not hasattr(structure, "bodies") or not hasattr(structure, "describe"):
        raise BlastscaleInputError(f"structure = {structure!r} is not a structure (blastscale.structures)")
    if not isinstance(contact, ContactSettings):
        raise BlastscaleInputError(f"contact = {contact!r} is not a ContactSettings")
    lo, hi = ENGINE_LENGTH_RANGE
    for name, v in _lengths(structure).items():
        check_range(name, v, lo, hi, "m")
    lo, hi = ENGINE_MASS_RANGE
    for b in structure.bodies:
        check_range(f"mass of body {b.name}", b.mass, lo, hi, "kg")
    L = structure_length(structure)
    dt_max = MAX_TIMESTEP_FRACTION * math.sqrt(L / gravity)
    if contact.timestep > dt_max * (1 + 1e-12):
        raise BlastscaleInputError(
            f"timestep = {contact.timestep:.6g} s is out of range: valid range is (0, {dt_max:.6g}] s "
            f"({MAX_TIMESTEP_FRACTION:g} x sqrt(L/g), L = {L:.6g} m)"
        )


def _warn_if_soft(contact: ContactSettings, structure, load, gravity: float) -> None:
    """One-line RuntimeWarning when an explicit contact is soft relative to the blast."""
    if load is None:
        return
    pulse_t = float(load.end_time - load.first_arrival)
    if contact.time_constant <= SOFT_CONTACT_FACTOR * pulse_t:  # below the bound whatever the default: not derived
        return
    ref = default_contact(structure, contact.friction, gravity).time_constant
    bound = SOFT_CONTACT_FACTOR * max(pulse_t, ref)
    if contact.time_constant > bound:
        warnings.warn(
            f"contact time constant = {contact.time_constant:.3g} s is soft relative to the blast "
            f"(load duration {pulse_t:.3g} s, scale-consistent default {ref:.3g} s): the response will depend on it; "
            "use contact=None (scale-consistent defaults) or a time constant <= "
            f"{bound:.3g} s",
            RuntimeWarning,
            stacklevel=3,
        )


def _check_common(duration, gravity, record_every, blast_mode):
    T = float(check_positive("duration", duration, "s"))
    g = float(check_positive("gravity", gravity, "m/s^2"))
    check_range("record_every", record_every, 1, math.inf)
    if not float(record_every).is_integer():
        raise BlastscaleInputError(f"record_every = {record_every!r} is out of range: must be a whole number >= 1")
    if blast_mode is not None:
        check_choice("blast_mode", blast_mode, BLAST_MODES)
    return T, g


def simulate_structure(
    structure,
    load=None,
    duration: float = 8.0,
    *,
    contact: ContactSettings | None = None,
    gravity: float = STANDARD_GRAVITY,
    record_every: int = 1,
    blast_mode: str | None = None,
    settle: bool = True,
    initial_rotation: float = 0.0,
    initial_angular_velocity: float = 0.0,
    initial_velocity=(0.0, 0.0, 0.0),
    initial_body_velocities=None,
) -> Response3D:
    """Simulate any structure of rigid bodies on a rigid ground under a blast load.

    Parameters
    ----------
    structure : structure
        :class:`~blastscale.structures.RectangularBlock`,
        :class:`~blastscale.structures.MultiDrumColumn`, or anything with the same interface.
    load : LoadStrategy or None
        E.g. ``make_load("A", structure, blast_parameters(W, R))`` or
        :class:`~.loads.MethodA`; None for gravity alone.
    duration : float
        Simulated time after the load's first arrival [s], > 0.
    contact : ContactSettings, optional
        None (default): the scale-consistent defaults of :func:`~.contact.default_contact`
        (derived from the structure's height and gravity). An explicit setting much softer
        than the blast gets a RuntimeWarning; one whose time step exceeds
        ``0.01 sqrt(L/g)`` an error.
    gravity : float
        g [m/s^2], > 0.
    record_every : int
        Keep one state every ``record_every`` steps (the first and last are always kept).
    blast_mode : {"auto", "force", "kick"}, optional
        How a step's impulse is applied (:mod:`.integrate`); default "auto" for one body,
        "force" for several. A block in "auto" mode with mu within 10 % of its pivoting
        threshold (:func:`pivot_friction_threshold`) gets a one-line RuntimeWarning.
    settle : bool
        Let the structure settle on its soft contacts for :func:`~.integrate.settle_time_constants` time
        constants before the first arrival (not when it starts tilted).
    initial_rotation : float
        Initial tilt theta_0 [rad], |theta_0| < pi/2: the whole structure turned rigidly about
        its lowest body's base edge (the +x edge when > 0), top towards +x when > 0
        (:func:`~.initial.tilt_bodies`; a block's free rocking from theta_0).
    initial_angular_velocity : float
        Initial rocking velocity omega_0 [rad/s] about that edge (the +x edge when omega_0 >= 0
        and theta_0 = 0), every body moving rigidly (:func:`~.initial.rigid_rocking_velocity`).
    initial_velocity : tuple of float
        Extra initial velocity of every centre of mass [m/s], (3,).
    initial_body_velocities : array (nbody, 6), optional
        Added per body: centre-of-mass velocity [m/s] and angular velocity [rad/s], world frame
        (:func:`~.initial.body_velocities`; a mechanism such as the rocking frame's).

    Returns
    -------
    Response3D
    """
    T, g = _check_common(duration, gravity, record_every, blast_mode)
    th0 = float(check_finite("initial rotation", initial_rotation, "rad"))
    om0 = float(check_finite("initial angular velocity", initial_angular_velocity, "rad/s"))
    v0 = check_finite("initial velocity", initial_velocity, "m/s")
    if v0.shape != (3,):
        raise BlastscaleInputError(f"initial velocity must have 3 components, got shape {v0.shape}")
    if load is not None and not (hasattr(load, "step_wrenches") and hasattr(load, "first_arrival")):
        raise BlastscaleInputError(f"load = {load!r} is not a LoadStrategy (see blastscale.sim3d.loads)")
    explicit = contact is not None
    if not explicit:
        if not hasattr(structure, "bodies"):
            raise BlastscaleInputError(f"structure = {structure!r} is not a structure (blastscale.structures)")
        contact = default_contact(structure, gravity=g)
    check_simulable(structure, contact, g)
    if explicit:
        _warn_if_soft(contact, structure, load, g)
    mode = blast_mode or ("auto" if len(structure.bodies) == 1 else "force")
    # the one place where absolute size is removed (.reference)
    scene, (a, b) = reference_scene(structure, contact if explicit else None, g, rotation=th0)
    _warn_near_pivot_threshold(scene, contact.friction, load, mode)
    st = integrate(
        scene,
        load,
        T,
        record_every=record_every,
        blast_mode=mode,
        settle=settle and th0 == 0.0,
        factors=(a, b),
        initial_velocity=_both(
            rigid_rocking_velocity(scene, th0, om0, v0, (a, b)), body_velocities(initial_body_velocities, scene, (a, b))
        ),
    )
    return response_from_states(structure, st, _settings(contact, g, T, mode, st, load, explicit))


def _both(first, second):
    """Apply two initial-velocity functions in turn (either may be None)."""
    if first is None or second is None:
        return first or second

    def initial(m, d):
        first(m, d)
        second(m, d)

    return initial


def _settings(c: ContactSettings, g, T, mode, st, load, explicit) -> dict:
    out = {
        **c.to_dict(),
        "contact_source": "explicit" if explicit else "scale-consistent default",
        "gravity_m_s2": g,
        "duration_s": T,
        "blast_mode": mode,
        "kick_steps": st["kicks"],
    }
    if load is not None and hasattr(load, "describe"):
        out.update(load.describe())
    return out


def _warn_near_pivot_threshold(scene: Scene, friction: float, load, mode: str):
    """mu* of a one-box scene (:func:`pivot_friction_threshold`, None for any other scene), with a
    one-line RuntimeWarning when a loaded run in "auto" mode has mu within 10 % of it
    (:mod:`.integrate`: "auto" may under-estimate the rocking there by up to ~3 %)."""
    shape = scene.bodies[0].shape
    if len(scene.bodies) != 1 or not isinstance(shape, BoxShape):
        return None
    mu_star = pivot_friction_threshold(shape.half_width, shape.half_height)
    if load is not None and mode == "auto" and 0.9 < friction / mu_star < 1.1:
        warnings.warn(
            f"friction = {friction:.4g} is within 10% of the pivoting threshold mu* = {mu_star:.4g}: "
            'blast_mode="auto" may under-estimate the rocking there by up to ~3%; compare with '
            'blast_mode="force" and a hard contact (time_constant ~ pulse duration / 50)',
            RuntimeWarning,
            stacklevel=3,
        )
    return mu_star


def pivot_friction_threshold(half_width: float, half_height: float) -> float:
    """Least friction coefficient for which an impulse at mid-height rotates a rectangular block
    about its rear base edge without slip.

    .. math:: \\mu^* = \\frac{4 b^2 + h^2}{3 b h} \\ge \\frac{4}{3}

    from the impulsive equations about the rear edge (J_o = 4/3 m r^2): the friction impulse is
    P (4b^2 + h^2) / (4 r^2) and the normal impulse 3 P h b / (4 r^2). Valid for a uniform,
    simultaneous load on the front face (Method A) of a block on a rigid base.

    Parameters
    ----------
    half_width, half_height : float
        b and h [m], > 0.

    Returns
    -------
    float
        mu* [-] (1.60 for the paper's block, alpha = 15 deg; 4/3 at its minimum, b = h/2).
    """
    b = float(check_positive("half width", half_width, "m"))
    h = float(check_positive("half height", half_height, "m"))
    return (4.0 * b * b + h * h) / (3.0 * b * h)
