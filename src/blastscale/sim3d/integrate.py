"""The one integration loop of the 3D engine: settle, load, step, record (in reference units).

Time: the structure stands at rest (settled on its soft contacts for
:func:`settle_time_constants` contact time constants) until the load's first arrival; the loop
integrates ``duration`` seconds from there, and the recorded ``time`` is the time after first
arrival. The scene is in the engine's reference units (:mod:`.reference`); the load is
evaluated, and the states returned, in physical units.

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
settings of docs/design.md (1 ms contact, no separate friction time constant) were measured with
the blast as a force.
"""

from __future__ import annotations

import copy
import math

import numpy as np

from .contact import ContactSettings
from .model import Scene

__all__ = [
    "BLAST_MODES",
    "KINETIC_SETTLE_TIME_CONSTANTS",
    "MAX_STEP_FACTOR_AFTER_LOAD",
    "SETTLE_TIME_CONSTANTS",
    "integrate",
    "settle_steps",
    "settle_time_constants",
    "step_factor_after_load",
]

#: Ways of applying a step's blast impulse (see the module docstring).
BLAST_MODES = ("auto", "force", "kick")

#: Settling before the blast arrives, in contact time constants: the soft contact starts
#: with zero penetration and relaxes to its static value (~1 um); with critical damping the
#: transient has decayed by exp(-20) after 20 tau. It scales with the time constant, so
#: prototype and model settle identically.
SETTLE_TIME_CONSTANTS = 20.0
#: Kinetic settling (``ContactSettings.settling = "kinetic"``, stacks on level beds of more than 10 bodies), in contact time
#: constants. A tall stack's lowest (axial) mode is lightly damped by contacts critically damped one by one: plainly
#: settled for 20 time constants the 40-course wall still moves at 8.7e-3 m/s (reference) and its outcome under a
#: blast is 1.07 % off its settled stack's (which it reaches after 400). Zeroing the velocities at every peak of the
#: kinetic energy (kinetic damping, dynamic relaxation: Otter 1966; Underwood 1983) brings the 40-course wall and the
#: 200-block wall to that state, outcome within 1e-9 of the 400-time-constant one, in 80 (docs/performance.md).
KINETIC_SETTLE_TIME_CONSTANTS = 80.0


def settle_time_constants(c: ContactSettings) -> float:
    """Contact time constants of ``c``'s settling before the first arrival [-]: :data:`SETTLE_TIME_CONSTANTS`
    ("plain"), :data:`KINETIC_SETTLE_TIME_CONSTANTS` ("kinetic")."""
    return KINETIC_SETTLE_TIME_CONSTANTS if c.settling == "kinetic" else SETTLE_TIME_CONSTANTS


def settle_steps(c: ContactSettings, timestep: float | None = None) -> float:
    """Steps of ``c``'s settling before the first arrival [-]: :func:`settle_time_constants` x the contact time
    constant [s] over ``timestep`` [s] (default ``c.timestep``; a size estimate may step otherwise). Not rounded:
    the engine takes its ceiling, an estimate the value."""
    return settle_time_constants(c) * c.time_constant / (c.timestep if timestep is None else timestep)


#: The longest step after the load, in time steps (``step_after_load = "double"``), chosen by the convergence study of
#: benchmarks/bench_step_after_load.py (docs/performance.md): x2 moves the columns' and the wall's first peaks by
#: < 1 %, outcomes unchanged; x4 would put the columns' 1 ms contact below MuJoCo's 2 steps, which it clamps.
MAX_STEP_FACTOR_AFTER_LOAD = 2.0


def step_factor_after_load(c: ContactSettings, nbody: int = 2) -> float:
    """The largest step after the load, in time steps [-].

    1 for ``step_after_load = "same"`` and for one body; else :data:`MAX_STEP_FACTOR_AFTER_LOAD`, at most half of
    every contact time constant over the step (MuJoCo clamps a time constant below 2 steps: the contact would
    silently soften). The ``k`` steps between two recorded states are then taken as ``ceil(k / factor)`` equal
    steps: the recorded times do not move. One body keeps its step: the paper's non-slender block sliding at
    8.8 m/s rocked to 0.025 rad instead of 1e-4 with its step x1.67 after the load and slid 3 % less
    (docs/performance.md); a block's run is cheap anyway."""
    if c.step_after_load == "same" or nbody < 2:
        return 1.0
    taus = [c.time_constant] + ([] if c.friction_time_constant is None else [c.friction_time_constant])
    return max(1.0, min(MAX_STEP_FACTOR_AFTER_LOAD, min(taus) / (2.0 * c.timestep)))


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


def _kick(m, d, wrench_impulses: np.ndarray, body_ids) -> None:
    """Add to qvel the velocity change of world-frame impulses (nbody, 6) (linear [N*s],
    angular [N*m*s]) applied at the centre of mass of bodies ``body_ids`` (MuJoCo ids):
    dv = M^-1 sum_b J_b^T I_b."""
    import mujoco

    jacp = np.zeros((3, m.nv))
    jacr = np.zeros((3, m.nv))
    gen = np.zeros(m.nv)
    for k, w in zip(body_ids, wrench_impulses):
        if not np.any(w):
            continue
        mujoco.mj_jacBodyCom(m, d, jacp, jacr, int(k))
        gen += jacp.T @ w[0:3] + jacr.T @ w[3:6]
    dq = np.zeros((1, m.nv))
    mujoco.mj_solveM(m, d, dq, gen.reshape(1, -1))
    d.qvel[:] += dq[0]


def _kinetic_settle(m, d, steps: int) -> None:
    """Step ``steps`` times under gravity with kinetic damping: the velocities zeroed whenever the kinetic energy
    1/2 qvel' M qvel has passed a peak (it fell since the step before), so the structure loses the energy of its
    oscillation at each peak and comes to its static state (:data:`KINETIC_SETTLE_TIME_CONSTANTS`)."""
    import mujoco

    mv = np.empty(m.nv)
    last = 0.0
    for _ in range(steps):
        mujoco.mj_step(m, d)
        mujoco.mj_mulM(m, d, mv, d.qvel)
        energy = 0.5 * float(np.dot(d.qvel, mv))
        if energy < last:
            d.qvel[:] = 0.0
            last = 0.0
        else:
            last = energy


def _settled(scene: Scene):
    """MuJoCo's data of ``scene`` settled on its soft contacts (:func:`settle_time_constants` contact time
    constants at the settling tolerance, kinetically damped where ``settling = "kinetic"``, the residual velocity
    removed). Settling depends on the model alone (gravity,
    no load): a scene from :func:`~.reference.reference_scene`'s cache settles once and every later run of the same
    model starts from a copy of that state (bitwise the state it would reach itself: MuJoCo's whole data is copied)."""
    import mujoco

    store = scene.settled
    if store is not None and "data" in store:
        return copy.copy(store["data"])
    m, c = scene.mj_model, scene.contact
    d = mujoco.MjData(m)
    run_tolerance = m.opt.tolerance
    if c.settle_tolerance is not None:  # an assembly's settling tolerance (ContactSettings.settle_tolerance)
        m.opt.tolerance = c.settle_tolerance
    steps = int(math.ceil(settle_steps(c) - 1e-9))
    if c.settling == "kinetic":
        _kinetic_settle(m, d, steps)
    else:
        mujoco.mj_step(m, d, steps)  # native loop
    m.opt.tolerance = run_tolerance
    d.qvel[:] = 0.0  # remove the residual transient exactly (exp(-20)-small plainly; below a peak kinetically)
    if store is not None:
        store.setdefault("data", copy.copy(d))
    return d


def integrate(
    scene: Scene,
    load,
    duration: float,
    *,
    record_every: int,
    blast_mode: str,
    settle: bool,
    factors=(1.0, 1.0),
    initial_velocity=None,
) -> dict:
    """The one integration loop (module docstring): settle, start at the load's first arrival,
    apply each step's wrenches (force or kick, :data:`BLAST_MODES`), step, record.

    Parameters
    ----------
    scene : Scene
        The structure's scene, in reference units.
    load : LoadStrategy or None
        Evaluated in physical units (positions / a).
    duration : float
        Physical time after the first arrival [s].
    record_every : int
        Keep one state every ``record_every`` steps (the first and last are always kept).
    blast_mode : {"auto", "force", "kick"}
        How a step's impulse is applied.
    settle : bool
        Settle on the soft contacts before the first arrival.
    factors : (float, float)
        (a, b) of :func:`~.reference.reference_factors`.
    initial_velocity : callable, optional
        ``initial_velocity(mj_model, data)`` sets the initial ``qvel`` after settling
        (:func:`~.initial.rigid_rocking_velocity`).

    Returns
    -------
    dict
        ``time`` (n,) [s], ``qpos`` (n, 7 nbody), ``qvel`` (n, 6 nbody), ``ncon`` (n,),
        ``delivered`` (nbody, 3) [N s], ``kicks``, ``first_arrival`` [s], ``duration`` [s], in
        physical units.
    """
    import mujoco

    a, b = factors
    fF, fM = a**4 / b**2, a**5 / b**2
    m = scene.mj_model
    c = scene.contact
    dt = c.timestep  # reference
    dtp = dt / b  # physical
    T = float(duration)
    nsteps = max(1, int(math.ceil(T / dtp - 1e-9)))
    nb = len(scene.bodies)
    ids = scene.body_ids  # MuJoCo's id of each body, in the structure's order
    d = _settled(scene) if settle else mujoco.MjData(m)
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
    t_start = 0.0 if load is None else float(load.first_arrival)
    loading = False
    kicks = 0
    n = 0
    longer = step_factor_after_load(c, nb) if load is not None else 1.0  # gravity alone, a free swing: one step
    while n < nsteps:
        t0 = t_start + n * dtp
        if load is None or t0 > load.end_time:
            if loading:
                xfrc[:] = 0.0
                loading = False
            # free motion: advance to the next recorded state in one call (MuJoCo loops mj_step
            # in C: bitwise the same states, without a Python round trip per step)
            nxt = int(idx[j])
            nsub = math.ceil((nxt - n) / longer - 1e-9)  # after a load: longer equal steps to the next state
            m.opt.timestep = dt if nsub == nxt - n else dt * (nxt - n) / nsub
            mujoco.mj_step(m, d, nsub)
            qpos[j], qvel[j], ncon[j] = d.qpos, d.qvel, d.ncon
            j += 1
            n = nxt
            continue
        W = load.step_wrenches(t0, t0 + dtp, d.xipos[ids] / a, d.xmat[ids].reshape(nb, 3, 3))
        delivered += W[:, 0:3] * dtp
        xfrc[ids, 0:3] = W[:, 0:3] * fF
        xfrc[ids, 3:6] = W[:, 3:6] * fM
        loading = True
        if blast_mode == "kick" or (blast_mode == "auto" and np.any(W) and _any_contact_slides(m, d, c)):
            _kick(m, d, xfrc[ids] * dt, ids)
            xfrc[1:] = 0.0
            kicks += 1
        mujoco.mj_step(m, d)
        n += 1
        if rec_mask[n]:
            qpos[j], qvel[j], ncon[j] = d.qpos, d.qvel, d.ncon
            j += 1
    m.opt.timestep = dt  # the scene's own step again
    qpos = qpos[:, scene.qpos_index()].reshape(nrec, nb, 7)  # the structure's body order
    qvel = qvel[:, scene.qvel_index()].reshape(nrec, nb, 6)
    qpos[:, :, 0:3] /= a
    qvel[:, :, 0:3] *= b / a
    qvel[:, :, 3:6] *= b
    return {
        "time": idx * dtp,
        "qpos": qpos.reshape(nrec, -1),
        "qvel": qvel.reshape(nrec, -1),
        "ncon": ncon,
        "delivered": delivered,
        "kicks": kicks,
        "first_arrival": t_start,
        "duration": T,
        "gravity_only": load is None,
    }
