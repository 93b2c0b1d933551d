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

How the blast impulse enters a step (``blast_mode``)
----------------------------------------------------
``"force"``: the step's exact impulse is applied as a constant force (``xfrc_applied``). The
constraint solver then sees the blast acceleration (hundreds of g). While a contact *sticks*
(a rocking block's pivot) this is exactly right. While a contact *slides*, MuJoCo's convex
cone couples the normal to the tangential constraint error (Lorentz-cone complementarity:
zero force only when the normal acceleration error exceeds mu times the tangential one), so
the blast's tangential acceleration produces a spurious normal impulse of order (lost
tangential momentum)/mu: a 1 m block pushed to 1.8 m/s loses 12% of its velocity and hops
4.4 mm (docs/sim3d.md).

``"kick"``: the step's impulse is added to the velocity before the step (the same momentum);
the solver then only sees the slip *velocity*. Exact for a sliding contact, but a sticking
pivot must then cancel the slip through the soft reference dynamics and slips ~v/b_f.

``"auto"`` (default for a single body): every load step is first classified with ``mj_forward`` under the
force; if any contact force lies on its friction-cone boundary (sliding), that step is taken
as a kick, otherwise as a force. For a rigid block loaded through its centre of mass the
impulsive rigid-body problem admits stick-and-rock about the rear edge only if
mu >= mu* = (4b^2+h^2)/(3bh); below mu* the only solution is pure slip with no impulsive
normal force, so "auto" is exact in both regimes away from mu*. Checked against plain force
mode with a hard contact (tau = 20 us << t_o, dt = 2 us), where force mode is accurate: the
velocity after the pulse agrees within 0.5% at mu = 0.7 (squat and slender blocks), and the
paper's block's peak rotation within 1% for mu <= 0.93 mu* and mu >= 1.06 mu* (identical, no
kick, above). Near mu* the classification,
made on the soft contact's force at the start of a step, kicks 1-3 steps that a hard contact
would take as sticking, and the peak rotation comes out up to 3% low (mu = 1.58-1.65 for
mu* = 1.60): a warning is issued for 0.9 mu* < mu < 1.1 mu*; use ``blast_mode="force"`` with a
hard contact there (docs/sim3d.md).

For several bodies (columns) the default is ``"force"``: the all-stick / all-slip argument
behind "auto" holds for one box loaded through its centre of mass only, and the column
settings of DESIGN.md (1 ms contact, no separate friction time constant) were measured with
the blast as a force.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import fields, is_dataclass, replace

import numpy as np

from .._validate import BlastscaleInputError, check_finite, check_positive, check_range
from ..structures.block import STANDARD_GRAVITY
from .contact import (
    MAX_TIMESTEP_FRACTION,
    REFERENCE_GRAVITY,
    REFERENCE_LENGTH,
    SOFT_CONTACT_FACTOR,
    ContactSettings,
    default_contact,
    reference_contact,
    structure_length,
)
from .initial import rigid_rocking_velocity
from .model import BoxShape, Scene, structure_scene
from .results import Response3D, response_from_states

__all__ = [
    "BLAST_MODES",
    "ENGINE_LENGTH_RANGE",
    "ENGINE_MASS_RANGE",
    "SETTLE_TIME_CONSTANTS",
    "check_simulable",
    "pivot_friction_threshold",
    "reference_factors",
    "simulate_structure",
]

#: Ways of applying a step's blast impulse (see the module docstring).
BLAST_MODES = ("auto", "force", "kick")

#: Settling before the blast arrives, in contact time constants: the soft contact starts
#: with zero penetration and relaxes to its static value (~1 um); with critical damping the
#: transient has decayed by exp(-20) after 20 tau. It scales with the time constant, so
#: prototype and model settle identically.
SETTLE_TIME_CONSTANTS = 20.0

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
            f"({MAX_TIMESTEP_FRACTION:g} x sqrt(L/g), L = {L:.6g} m)")


def _warn_if_soft(contact: ContactSettings, structure, load, gravity: float) -> None:
    """One-line RuntimeWarning when an explicit contact is soft relative to the blast."""
    if load is None:
        return
    pulse_t = float(load.end_time - load.first_arrival)
    ref = default_contact(structure, contact.friction, gravity).time_constant
    bound = SOFT_CONTACT_FACTOR * max(pulse_t, ref)
    if contact.time_constant > bound:
        warnings.warn(
            f"contact time constant = {contact.time_constant:.3g} s is soft relative to the blast "
            f"(load duration {pulse_t:.3g} s, scale-consistent default {ref:.3g} s): the response will depend on it; "
            "use contact=None (scale-consistent defaults) or a time constant <= "
            f"{bound:.3g} s", RuntimeWarning, stacklevel=3)


def _any_contact_slides(m, d, c: ContactSettings) -> bool:
    """Classify the current step: does any contact force lie on its friction-cone boundary?

    Runs ``mj_forward`` (with the step's applied forces in place) and compares each contact's
    tangential force with mu times its normal force (elliptic: Euclidean norm; pyramidal: the
    pyramid's |f1| + |f2|), within 0.1%.
    """
    import mujoco

    mujoco.mj_forward(m, d)
    f = np.zeros(6)
    for i in range(d.ncon):
        mujoco.mj_contactForce(m, d, i, f)
        fn = f[0]
        if fn <= 0.0:
            continue
        ft = math.hypot(f[1], f[2]) if c.cone == "elliptic" else abs(f[1]) + abs(f[2])
        if ft >= (1.0 - 1e-3) * c.friction * fn:
            return True
    return False


def _kick(m, d, wrench_impulses: np.ndarray) -> None:
    """Add to qvel the velocity change of world-frame impulses (nbody, 6) (linear [N*s],
    angular [N*m*s]) applied at each body's centre of mass: dv = M^-1 sum_b J_b^T I_b."""
    import mujoco

    jacp = np.zeros((3, m.nv))
    jacr = np.zeros((3, m.nv))
    gen = np.zeros(m.nv)
    for k, w in enumerate(wrench_impulses):
        if not np.any(w):
            continue
        mujoco.mj_jacBodyCom(m, d, jacp, jacr, k + 1)
        gen += jacp.T @ w[0:3] + jacr.T @ w[3:6]
    dq = np.zeros((1, m.nv))
    mujoco.mj_solveM(m, d, dq, gen.reshape(1, -1))
    d.qvel[:] += dq[0]


def reference_factors(structure, gravity: float) -> tuple:
    """Length and time factors (a, b) from a structure's own units to the engine's reference units.

    The engine always integrates the structure geometrically scaled to the reference height
    ``REFERENCE_LENGTH`` (10 m) under ``REFERENCE_GRAVITY`` (9.81 m/s^2), same density:

    .. math:: a = L_{ref} / L,\\qquad b = \\sqrt{a\\, g / g_{ref}},

    lengths x a, times x b, velocities x a/b, angular velocities / b, forces x a^4/b^2, moments
    x a^5/b^2. This is the exact similitude of rigid bodies under gravity, so the equations of
    motion are unchanged; what it removes is MuJoCo's *absolute* thresholds (mjMINVAL on masses
    and inertias, collision tolerances in metres), which otherwise make a 1/100 model and its
    prototype differ by ~1e-8 of the response after the first contact transitions (growing to
    ~1e-3 of the peak over 8 s), and crash for bodies of a few milligrams. A structure of 10 m
    under 9.81 m/s^2 runs with a = b = 1 exactly.
    """
    L = structure_length(structure)
    a = REFERENCE_LENGTH / L
    return a, math.sqrt(a * gravity / REFERENCE_GRAVITY)


#: Significant digits of a structure's parameters in reference units (:func:`_to_reference`).
REFERENCE_DIGITS = 12


def _to_reference(structure, a: float):
    """The structure in reference units, its float parameters rounded to ``REFERENCE_DIGITS``
    significant digits (dataclass structures): a structure and its exactly scaled model then
    give bitwise the same bodies, faces and mesh vertices (their scaled inputs differ only by
    round-off), so MuJoCo integrates the same model. The rounding moves the geometry by
    < 5e-13 relative."""
    ref = structure if a == 1.0 else structure.scaled(a)
    if not is_dataclass(ref):
        return ref
    changes = {}
    for f in fields(ref):
        v = getattr(ref, f.name)
        if isinstance(v, float):
            changes[f.name] = float(f"{v:.{REFERENCE_DIGITS}g}")
        elif isinstance(v, tuple) and v and all(isinstance(x, float) for x in v):
            changes[f.name] = tuple(float(f"{x:.{REFERENCE_DIGITS}g}") for x in v)
    return replace(ref, **changes)


def _reference_contact(contact: ContactSettings | None, structure, a: float, b: float) -> ContactSettings:
    """The contact settings in reference units: the reference defaults themselves for
    ``contact=None`` (so that a structure and its scaled model get bitwise the same), else the
    explicit settings scaled by (a, b)."""
    if contact is None:
        return reference_contact(structure)
    return contact if (a == 1.0 and b == 1.0) else contact.scaled(a, b)


def _integrate(scene: Scene, load, duration: float, *, record_every: int, blast_mode: str, settle: bool,
               factors=(1.0, 1.0), initial_velocity=None) -> dict:
    """The one integration loop, in reference units (:func:`reference_factors`): settle, start at
    the load's first arrival, apply each step's wrenches (force or kick), step, record. The load
    is evaluated in physical units; returns the recorded states in physical units."""
    import mujoco

    a, b = factors
    fF, fM = a**4 / b**2, a**5 / b**2
    m, d = scene.model, mujoco.MjData(scene.model)
    c = scene.contact
    dt = c.timestep  # reference
    dtp = dt / b  # physical
    T = float(duration)
    nsteps = max(1, int(math.ceil(T / dtp - 1e-9)))
    nb = len(scene.bodies)
    if settle:
        for _ in range(int(math.ceil(SETTLE_TIME_CONSTANTS * c.time_constant / dt - 1e-9))):  # round-off safe
            mujoco.mj_step(m, d)
        d.qvel[:] = 0.0  # remove the (exp(-20)-small) residual transient exactly
    d.time = 0.0
    if initial_velocity is not None:
        initial_velocity(m, d)
    k = int(record_every)
    idx = np.unique(np.r_[np.arange(0, nsteps + 1, k), nsteps])
    nrec = idx.size
    qpos = np.empty((nrec, m.nq))
    qvel = np.empty((nrec, m.nv))
    ncon = np.empty(nrec, dtype=np.int32)
    mujoco.mj_forward(m, d)  # kinematics and contacts of the initial state (does not advance it)
    qpos[0], qvel[0], ncon[0] = d.qpos, d.qvel, d.ncon
    rec_mask = np.zeros(nsteps + 1, dtype=bool)
    rec_mask[idx] = True
    j = 1
    xfrc = d.xfrc_applied
    delivered = np.zeros((nb, 3))
    delivered_abs = np.zeros(nb)
    t_start = 0.0 if load is None else float(load.first_arrival)
    loading = False
    kicks = 0
    n = 0
    while n < nsteps:
        t0 = t_start + n * dtp
        if load is None or t0 > load.end_time:
            if loading:
                xfrc[:] = 0.0
                loading = False
            # free motion: advance to the next recorded state in one call (MuJoCo loops mj_step
            # in C: bitwise the same states, without a Python round trip per step)
            nxt = int(idx[j])
            mujoco.mj_step(m, d, nxt - n)
            qpos[j], qvel[j], ncon[j] = d.qpos, d.qvel, d.ncon
            j += 1
            n = nxt
            continue
        W = load.step_wrenches(t0, t0 + dtp, d.xipos[1:] / a, d.xmat[1:].reshape(nb, 3, 3))
        delivered += W[:, 0:3] * dtp
        delivered_abs += np.linalg.norm(W[:, 0:3], axis=1) * dtp
        xfrc[1:, 0:3] = W[:, 0:3] * fF
        xfrc[1:, 3:6] = W[:, 3:6] * fM
        loading = True
        if blast_mode == "kick" or (blast_mode == "auto" and np.any(W) and _any_contact_slides(m, d, c)):
            _kick(m, d, xfrc[1:] * dt)
            xfrc[1:] = 0.0
            kicks += 1
        mujoco.mj_step(m, d)
        n += 1
        if rec_mask[n]:
            qpos[j], qvel[j], ncon[j] = d.qpos, d.qvel, d.ncon
            j += 1
    qpos = qpos.reshape(nrec, nb, 7)
    qvel = qvel.reshape(nrec, nb, 6)
    qpos[:, :, 0:3] /= a
    qvel[:, :, 0:3] *= b / a
    qvel[:, :, 3:6] *= b
    return {"time": idx * dtp, "qpos": qpos.reshape(nrec, -1), "qvel": qvel.reshape(nrec, -1), "ncon": ncon,
            "delivered": delivered, "delivered_abs": delivered_abs, "kicks": kicks, "first_arrival": t_start,
            "duration": T}


def _check_common(duration, gravity, record_every, blast_mode):
    T = float(check_positive("duration", duration, "s"))
    g = float(check_positive("gravity", gravity, "m/s^2"))
    check_range("record_every", record_every, 1, math.inf)
    if not float(record_every).is_integer():
        raise BlastscaleInputError(f"record_every = {record_every!r} is out of range: must be a whole number >= 1")
    if blast_mode is not None and blast_mode not in BLAST_MODES:
        raise BlastscaleInputError(f"blast_mode = {blast_mode!r} is not known: valid values are {', '.join(BLAST_MODES)}")
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
) -> Response3D:
    """Simulate any structure of rigid bodies on a rigid ground under a blast load.

    Parameters
    ----------
    structure : structure
        :class:`~blastscale.structures.RectangularBlock`,
        :class:`~blastscale.structures.MultiDrumColumn`, or anything with the same interface.
    load : LoadStrategy or None
        E.g. ``make_load("A", structure, charge_kg=..., standoff_m=...)`` or
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
        How a step's impulse is applied (module docstring); default "auto" for one body,
        "force" for several. A block in "auto" mode with mu within 10 % of its pivoting
        threshold (:func:`pivot_friction_threshold`) gets a one-line RuntimeWarning.
    settle : bool
        Let the structure settle on its soft contacts for ``SETTLE_TIME_CONSTANTS`` time
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
    a, b = reference_factors(structure, g)
    ref = _to_reference(structure, a)
    scene = structure_scene(ref, _reference_contact(contact if explicit else None, structure, a, b), REFERENCE_GRAVITY,
                            rotation=th0)
    _warn_near_pivot_threshold(scene, contact.friction, load, mode)
    st = _integrate(scene, load, T, record_every=record_every, blast_mode=mode, settle=settle and th0 == 0.0,
                    factors=(a, b), initial_velocity=rigid_rocking_velocity(scene, th0, om0, v0, (a, b)))
    return response_from_states(structure, st, _settings(contact, g, T, mode, st, load, explicit))


def _settings(c: ContactSettings, g, T, mode, st, load, explicit) -> dict:
    out = {**c.to_dict(), "contact_source": "explicit" if explicit else "scale-consistent default",
           "gravity_m_s2": g, "duration_s": T, "blast_mode": mode, "kick_steps": st["kicks"]}
    if load is not None and hasattr(load, "describe"):
        out.update(load.describe())
    return out


def _warn_near_pivot_threshold(scene: Scene, friction: float, load, mode: str):
    """mu* of a one-box scene (:func:`pivot_friction_threshold`, None for any other scene), with a
    one-line RuntimeWarning when a loaded run in "auto" mode has mu within 10 % of it (module
    docstring: "auto" may under-estimate the rocking there by up to ~3 %)."""
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
