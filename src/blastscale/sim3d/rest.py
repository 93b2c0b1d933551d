"""At rest before the blast: a structure under gravity alone over its own rest time.

A 3D run starts the blast on a structure that has settled on its soft contacts for
:func:`~.integrate.settle_time_constants` contact time constants (milliseconds): whether it would
*stay* at rest without the blast is not seen there. :func:`rest_check` runs the structure (same
contact settings, same gravity) under gravity alone for its **rest time**

.. math:: T_{rest} = N_{rest} \\sqrt{H / g},\\qquad N_{rest} = 3

(:data:`REST_NATURAL_TIMES`; H the structure's height, ``describe()["height_m"]``: 2.2 s for a 5.3 m
arch, 3.0 s for a 10 m column, 0.68 s for its 1/20 specimen). A rest time in natural units is the same
number of engine steps at every size (the steps scale with sqrt(H/g), docs/sim3d.md), so it needs no floor
or cap in seconds: a prototype and its specimen are checked over corresponding times. Three natural
times take a mechanism well into its motion (an arch at t/R = 0.105, below the minimum thickness 0.1075,
moves at 5e-2 sqrt(g H) after one natural time and has fallen after three) and keep the engine's own creep
(the soft contacts, on standing arches at t/R 0.12-0.16: docs/assemblies.md) at 5-6e-5 H.

The check gives (:func:`rest_state`, the ``rest`` block of a 3D summary):

* ``creep_m``: the largest residual displacement of a centre of mass at the end of the rest time [m],
  ``creep_rel_height`` the same over H [-];
* ``final_speed_rel_sqrt_gh``: the largest body speed (``|v_com| + |omega| h_k / 2``) over the last
  tenth of the rest time, over sqrt(g H) [-] (:func:`~.results.stability_of`'s figure);
* ``equilibrium``: False when a body fell (the fall rule, :func:`~.record.fallen_flags`) or the
  structure **keeps accelerating**: still moving at the end (faster than at rest,
  :data:`~.results.REST_SPEED_FRACTION` sqrt(g H)) and its largest displacement grew in the second half
  of the rest time by more than :data:`ACCELERATING_RATIO` times its growth in the first half (a creep
  at constant speed grows by as much, 1x; a motion from rest at constant acceleration by 3x; a settling
  by less);
* ``duration_s``: the rest time [s].

The step: the check integrates as the run integrates free motion after the blast, at the step after the load
(:func:`~.integrate.step_factor_after_load`: twice the step for a stack, at most half of every contact time
constant; a single body keeps its step): on the arch t/R = 0.16 (R = 5 m, 20 voussoirs, friction 0.8) the
creep over the rest time is 4.695e-5 H against 4.690e-5 H at the run's step (+0.1 %), the t/R = 0.105 arch is
not in equilibrium either way, at a third of the wall time (2.9 s against 8.9 s).

Prototype and specimen: a specimen and its prototype compile to the same MuJoCo model in the engine's
reference units (:mod:`.reference`; up to a uniform density factor, which gravity alone does not see), so the
check is cached on that model (:func:`model_key`): the second system, every point of a sweep or an ensemble
over the same structure and contact settings, and a repeated run in the same process reuse the first run's
dimensionless figures.
"""

from __future__ import annotations

import hashlib
import math
import re
import threading
from dataclasses import replace

import numpy as np

from .._validate import check_positive
from ..constants import STANDARD_GRAVITY
from .contact import MAX_TIMESTEP_FRACTION, ContactSettings, default_contact, structure_length
from .integrate import step_factor_after_load
from .reference import reference_scene
from .results import REST_SPEED_FRACTION, body_heights, final_speed_rel
from .simulate import simulate_structure

__all__ = [
    "ACCELERATING_RATIO",
    "REST_NATURAL_TIMES",
    "REST_RECORDS",
    "model_key",
    "rest_check",
    "rest_contact",
    "rest_state",
    "rest_time",
]

#: The rest time in natural times sqrt(H / g) of the structure [-] (module docstring).
REST_NATURAL_TIMES = 3.0
#: Keeps accelerating: displacement growth over the second half of the rest time above this multiple of the
#: first half's [-] (a creep at constant speed: 1; a motion from rest at constant acceleration: 3).
ACCELERATING_RATIO = 2.0
#: States recorded over a rest check (about; the recording interval in steps is derived from it).
REST_RECORDS = 300
#: The rest checks already run in this process: SHA-256 of the reference MJCF and the rest time in natural
#: times -> the dimensionless figures (``creep_rel_height``, ``final_speed_rel_sqrt_gh``, ``equilibrium``).
_CACHE: dict = {}
_CACHE_MAX = 256
_LOCKS: dict = {}
_LOCKS_GUARD = threading.Lock()
#: The MJCF attributes that carry a mass (normalised out of the cache key, :func:`model_key`).
_MASSIVE = re.compile(r'\b(mass|density|diaginertia|fullinertia)="([^"]*)"')


def model_key(scene) -> str:
    """The cache key of an engine model under gravity alone: the SHA-256 of its MJCF text with every mass, density
    and inertia divided by the total mass (12 significant digits). Under gravity alone a uniform factor on the
    densities changes no motion (MuJoCo's contacts are mass-normalised: the contact forces scale with the masses,
    the accelerations do not), so a specimen of another material at its prototype's exact scale shares the check."""
    total = sum(b.mass for b in scene.bodies if b.mass) or 1.0

    def norm(m):
        return f'{m.group(1)}="{" ".join(f"{float(x) / total:.12g}" for x in m.group(2).split())}"'

    return hashlib.sha256(_MASSIVE.sub(norm, scene.xml).encode()).hexdigest()


def rest_time(structure, gravity: float = STANDARD_GRAVITY, natural_times: float = REST_NATURAL_TIMES) -> float:
    """The structure's rest time ``natural_times * sqrt(H / g)`` [s] (H its height [m], g [m/s^2])."""
    h = float(check_positive("structure height", structure_length(structure), "m"))
    g = float(check_positive("gravity", gravity, "m/s^2"))
    return float(check_positive("natural_times", natural_times)) * math.sqrt(h / g)


def rest_contact(
    structure, contact: ContactSettings | None = None, gravity: float = STANDARD_GRAVITY
) -> ContactSettings:
    """The contact settings of the check at rest: ``contact`` (None: the engine's scale-consistent defaults) at the
    run's step after the load (:func:`~.integrate.step_factor_after_load`: x2 for a stack), within the engine's
    bound on the step (``MAX_TIMESTEP_FRACTION`` sqrt(H / g); a user's coarse step stays as it is); its
    ``timestep`` [s] is the step of the check (:func:`rest_check`; the run's size, :mod:`blastscale.study.memory`)."""
    g = float(check_positive("gravity", gravity, "m/s^2"))
    c = default_contact(structure, gravity=g) if contact is None else contact
    h = structure_length(structure)
    longer = min(
        step_factor_after_load(c, len(structure.bodies)), MAX_TIMESTEP_FRACTION * math.sqrt(h / g) / c.timestep
    )
    return replace(c, timestep=c.timestep * max(1.0, longer))


def rest_state(response, structure_height: float, gravity: float) -> dict:
    """The dimensionless rest figures of a gravity-alone :class:`~.results.Response3D` (module docstring).

    Parameters
    ----------
    response : Response3D
        A run under gravity alone from the settled state.
    structure_height : float
        H [m].
    gravity : float
        g [m/s^2].

    Returns
    -------
    dict
        ``creep_rel_height`` (largest residual displacement of a centre of mass at the end / H),
        ``final_speed_rel_sqrt_gh`` (largest body speed over the last tenth / sqrt(g H)), ``equilibrium``
        (no body fell and it does not keep accelerating).
    """
    ds = response.dataset
    h = float(structure_height)
    v_rel = final_speed_rel(ds, body_heights(response.structure), h, gravity)
    disp = np.linalg.norm(ds["com_displacement"].values, axis=2).max(axis=1)  # largest over the bodies, per time
    t = ds["time"].values
    mid = disp[int(np.searchsorted(t, 0.5 * t[-1]))]
    accelerating = v_rel > REST_SPEED_FRACTION and (disp[-1] - mid) > ACCELERATING_RATIO * (mid - disp[0])
    fell = bool(ds["fallen"].values.any()) or bool(ds.attrs.get("collapsed", 0))
    return {
        "creep_rel_height": float(ds["residual_displacement"].values.max() / h),
        "final_speed_rel_sqrt_gh": v_rel,
        "equilibrium": not (fell or bool(accelerating)),
    }


def _lock(key) -> threading.Lock:
    with _LOCKS_GUARD:
        return _LOCKS.setdefault(key, threading.Lock())


def rest_check(
    structure,
    contact: ContactSettings | None = None,
    gravity: float = STANDARD_GRAVITY,
    *,
    natural_times: float = REST_NATURAL_TIMES,
) -> dict:
    """The structure under gravity alone over its rest time: the ``rest`` block of a 3D summary.

    Parameters
    ----------
    structure : structure
        Any structure of :mod:`blastscale.structures`, in its own units.
    contact : ContactSettings or None
        The run's contact settings (None: the engine's scale-consistent defaults, as
        :func:`~.simulate.simulate_structure`), stepped at the run's step after the load
        (:func:`~.integrate.step_factor_after_load`: x2 for a stack; module docstring).
    gravity : float
        g [m/s^2].
    natural_times : float
        The rest time in natural times sqrt(H / g) [-] (default :data:`REST_NATURAL_TIMES`; shorter only to
        test).

    Returns
    -------
    dict
        ``creep_m`` [m], ``creep_rel_height`` [-], ``final_speed_rel_sqrt_gh`` [-], ``equilibrium`` (bool),
        ``duration_s`` (the rest time [s]) (module docstring). Cached on the reference model: the same
        structure and settings (or its exactly scaled specimen) run once per process.
    """
    g = float(check_positive("gravity", gravity, "m/s^2"))
    T = rest_time(structure, g, natural_times)
    h = structure_length(structure)
    c = rest_contact(structure, contact, g)
    scene, (_, b) = reference_scene(structure, c, g)
    key = (model_key(scene), float(natural_times))
    with _lock(key):
        figures = _CACHE.get(key)
        if figures is None:
            steps = T * b / scene.contact.timestep  # the engine's steps over the rest time (reference units)
            resp = simulate_structure(
                structure, None, T, contact=c, gravity=g, record_every=max(1, int(steps // REST_RECORDS))
            )
            figures = rest_state(resp, h, g)
            if len(_CACHE) >= _CACHE_MAX:
                _CACHE.pop(next(iter(_CACHE)))
            _CACHE[key] = figures
    return {
        "creep_m": figures["creep_rel_height"] * h,
        "creep_rel_height": figures["creep_rel_height"],
        "final_speed_rel_sqrt_gh": figures["final_speed_rel_sqrt_gh"],
        "equilibrium": figures["equilibrium"],
        "duration_s": T,
    }
