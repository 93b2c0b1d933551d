"""Run a single rigid block on MuJoCo under a blast pulse (paper's Method A) and record it.

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

``"auto"`` (default): every load step is first classified with ``mj_forward`` under the
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

:class:`Block3DSimulator` is the solver object (settings stated once: contact, time step,
recording interval); :func:`simulate_block` is the one-call form.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from .._validate import BlastscaleInputError, check_finite, check_positive, check_range
from ..structures.block import STANDARD_GRAVITY, RectangularBlock
from .blast_force import step_forces
from .contact import ContactSettings
from .model import BoxShape, Scene, block_scene
from .results import Block3DResult, quaternion_to_matrix, tilt_angle

__all__ = ["Block3DSimulator", "simulate_block", "pivot_friction_threshold", "SETTLE_TIME_CONSTANTS", "BLAST_MODES"]

#: Ways of applying a step's blast impulse (see the module docstring).
BLAST_MODES = ("auto", "force", "kick")

#: Settling before the blast arrives, in contact time constants: the soft contact starts
#: with zero penetration and relaxes to its static value (~1 um); with critical damping the
#: transient has decayed by exp(-20) after 20 tau. It scales with the time constant, so
#: prototype and model settle identically.
SETTLE_TIME_CONSTANTS = 20.0


@dataclass(frozen=True)
class Block3DSimulator:
    """Simulate rectangular blocks on a rigid plane under a Method A blast load.

    Parameters
    ----------
    contact : ContactSettings
        Contact, time-step and solver settings (full scale by default; use
        ``contact.scaled(lambda)`` for a model).
    gravity : float
        g [m/s^2].
    record_every : int
        Keep one state every ``record_every`` steps (the first and last are always kept).
    blast_mode : {"auto", "force", "kick"}
        How each step's blast impulse is applied (module docstring); "auto" is right for
        sticking and for sliding contacts.
    shape_type : type
        Shape class built from the block (``from_block``); :class:`~.model.BoxShape` by default.
    settle : bool
        Let the upright block settle on its soft contact for ``SETTLE_TIME_CONSTANTS`` time
        constants before t = 0 (ignored when starting tilted).

    Notes
    -----
    Accuracy is set by ``contact.timestep`` (semi-implicit Euler, first order) and the contact
    time constant; see docs/sim3d.md for the measured errors against closed forms. Results are
    bitwise deterministic for given inputs.
    """

    contact: ContactSettings = ContactSettings()
    gravity: float = STANDARD_GRAVITY
    record_every: int = 1
    settle: bool = True
    blast_mode: str = "auto"
    shape_type: type = BoxShape

    def __post_init__(self):
        if self.contact is None:  # as simulate_block: None means the full-scale defaults
            object.__setattr__(self, "contact", ContactSettings())
        if not isinstance(self.contact, ContactSettings):
            raise BlastscaleInputError(f"contact = {self.contact!r} is not a ContactSettings")
        check_positive("gravity", self.gravity, "m/s^2")
        check_range("record_every", self.record_every, 1, math.inf)
        if not float(self.record_every).is_integer():
            raise BlastscaleInputError(f"record_every = {self.record_every!r} is out of range: must be a whole number >= 1")
        if self.blast_mode not in BLAST_MODES:
            raise BlastscaleInputError(
                f"blast_mode = {self.blast_mode!r} is not known: valid values are {', '.join(BLAST_MODES)}"
            )

    def run(
        self,
        block: RectangularBlock,
        pulse=None,
        duration: float = 5.0,
        *,
        initial_rotation: float = 0.0,
        initial_angular_velocity: float = 0.0,
        initial_velocity: tuple[float, float, float] = (0.0, 0.0, 0.0),
    ) -> Block3DResult:
        """Run one block.

        Parameters
        ----------
        block : RectangularBlock
            The block; the blast loads its -x face (area 2h x 2w) towards +x.
        pulse : blastscale.blast.pulses.Pulse or None
            Reflected pressure pulse, t = 0 at shock arrival; None for no blast.
        duration : float
            Simulated time after arrival [s].
        initial_rotation : float
            Initial tilt theta_0 [rad], resting on a base edge (see :func:`~.model.block_scene`).
        initial_angular_velocity : float
            Initial rocking velocity d theta/dt [rad/s] about the supporting edge (the +x edge
            when >= 0 and theta_0 = 0); the centre of mass gets the matching rigid velocity.
        initial_velocity : tuple of float
            Extra initial velocity of the centre of mass [m/s].

        Returns
        -------
        Block3DResult
        """
        import mujoco

        if not isinstance(block, RectangularBlock):
            raise BlastscaleInputError(f"block = {block!r} is not a RectangularBlock")
        if pulse is not None and not hasattr(pulse, "cumulative_impulse"):
            raise BlastscaleInputError(f"pulse = {pulse!r} is not a pulse: expected a blastscale.blast.pulses.Pulse or None")
        T = float(check_positive("duration", duration, "s"))
        th0 = float(check_finite("initial rotation", initial_rotation, "rad"))
        om0 = float(check_finite("initial angular velocity", initial_angular_velocity, "rad/s"))
        v0 = check_finite("initial velocity", initial_velocity, "m/s")
        if v0.shape != (3,):
            raise BlastscaleInputError(f"initial velocity must have 3 components, got shape {v0.shape}")
        c = self.contact
        scene: Scene = block_scene(block, c, self.gravity, rotation=th0, shape_type=self.shape_type)
        m, d = scene.model, mujoco.MjData(scene.model)
        shape = scene.bodies[0].shape
        bid = scene.body_id(0)
        mu_star = pivot_friction_threshold(shape.half_width, shape.half_height)
        if pulse is not None and self.blast_mode == "auto" and 0.9 < c.friction / mu_star < 1.1:
            warnings.warn(
                f"friction = {c.friction:.4g} is within 10% of the pivoting threshold mu* = {mu_star:.4g}: "
                'blast_mode="auto" may under-estimate the rocking there by up to ~3%; compare with '
                'blast_mode="force" and a hard contact (time_constant ~ pulse duration / 50)',
                RuntimeWarning,
                stacklevel=2,
            )
        dt = c.timestep
        nsteps = max(1, int(math.ceil(T / dt - 1e-9)))

        if self.settle and th0 == 0.0:
            for _ in range(int(math.ceil(SETTLE_TIME_CONSTANTS * c.time_constant / dt))):
                mujoco.mj_step(m, d)
            d.qvel[:] = 0.0  # remove the (exp(-20)-small) residual transient exactly
        d.time = 0.0
        # initial velocities: rigid rotation about the supporting edge + translation
        if om0 != 0.0 or np.any(v0 != 0.0):
            s = 1.0 if (th0 > 0.0 or (th0 == 0.0 and om0 >= 0.0)) else -1.0
            mujoco.mj_forward(m, d)
            R = d.xmat[bid].reshape(3, 3)
            pivot = R @ np.array([s * shape.half_width, 0.0, -shape.half_height]) + d.xpos[bid]
            rel = d.xpos[bid] - pivot
            w = np.array([0.0, om0, 0.0])
            d.qvel[0:3] = np.cross(w, rel) + v0
            d.qvel[3:6] = R.T @ w  # free-joint angular velocity is in the body frame

        # blast: exact impulse per step over the pulse, zero afterwards
        face = shape.front_face()
        if pulse is not None:
            n_load = min(nsteps, int(math.ceil(pulse.duration / dt)) + 1)
            forces = step_forces(pulse, face.area, np.arange(n_load + 1) * dt)
        else:
            n_load, forces = 0, np.zeros(0)
        cb, nb = np.asarray(face.centre), np.asarray(face.normal)

        k = int(self.record_every)
        idx = np.unique(np.r_[np.arange(0, nsteps + 1, k), nsteps])
        nrec = idx.size
        qpos = np.empty((nrec, 7))
        qvel = np.empty((nrec, 6))
        ncon = np.empty(nrec, dtype=np.int32)
        mujoco.mj_forward(m, d)  # contacts of the initial state (does not advance it)
        qpos[0], qvel[0], ncon[0] = d.qpos, d.qvel, d.ncon
        rec_mask = np.zeros(nsteps + 1, dtype=bool)
        rec_mask[idx] = True
        j = 1
        xfrc = d.xfrc_applied
        delivered = 0.0
        mode = self.blast_mode
        kicks = 0
        for n in range(nsteps):
            if n < n_load:
                R = d.xmat[bid].reshape(3, 3)
                F = forces[n] * (R @ nb)
                xfrc[bid, 0:3] = F
                xfrc[bid, 3:6] = np.cross(R @ cb, F)  # moment about the centre of mass
                delivered += forces[n] * dt
                if mode == "kick" or (mode == "auto" and _any_contact_slides(m, d, c)):
                    _kick(m, d, bid, xfrc[bid] * dt)
                    xfrc[bid] = 0.0
                    kicks += 1
            elif n == n_load and n_load:
                xfrc[bid] = 0.0
            mujoco.mj_step(m, d)
            if rec_mask[n + 1]:
                qpos[j], qvel[j], ncon[j] = d.qpos, d.qvel, d.ncon
                j += 1
        return _record(idx * dt, qpos, qvel, ncon, shape, delivered, {**c.to_dict(), "gravity_m_s2": self.gravity,
                                                                       "duration_s": T, "blast_mode": mode,
                                                                       "kick_steps": kicks,
                                                                       "pivot_friction_threshold": mu_star})


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


def _any_contact_slides(m, d, c: ContactSettings) -> bool:
    """Classify the current step: does any contact force lie on its friction-cone boundary?

    Runs ``mj_forward`` (with the step's applied force in place) and compares each contact's
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


def _kick(m, d, bid: int, wrench_impulse: np.ndarray) -> None:
    """Add to qvel the velocity change of a world-frame impulse (linear [N*s], angular [N*m*s])
    applied at the centre of mass of body ``bid``: dv = M^-1 J^T (impulse)."""
    import mujoco

    jacp = np.zeros((3, m.nv))
    jacr = np.zeros((3, m.nv))
    mujoco.mj_jacBodyCom(m, d, jacp, jacr, bid)
    gen = jacp.T @ wrench_impulse[0:3] + jacr.T @ wrench_impulse[3:6]
    dq = np.zeros((1, m.nv))
    mujoco.mj_solveM(m, d, dq, gen.reshape(1, -1))
    d.qvel[:] += dq[0]


def _record(time, qpos, qvel, ncon, shape, delivered, settings) -> Block3DResult:
    R = quaternion_to_matrix(qpos[:, 3:7])
    pos = qpos[:, 0:3]
    theta = tilt_angle(R)
    omega_world = np.einsum("nij,nj->ni", R, qvel[:, 3:6])
    pivots = shape.pivot_points()  # (+x edge, -x edge) in body frame
    edge_x = pos[:, None, 0] + np.einsum("nj,kj->nk", R[:, 0, :], pivots)  # (n, 2) world x
    disp = edge_x - pivots[None, :, 0]  # from the upright pose centred at x = 0
    sliding = np.where(theta >= 0.0, disp[:, 0], disp[:, 1])
    base_c = np.array([0.0, 0.0, -shape.half_height])
    base_x = pos[:, 0] + R[:, 0, :] @ base_c
    corners_z = pos[:, None, 2] + np.einsum("nj,kj->nk", R[:, 2, :], shape.base_points())
    return Block3DResult(
        time=time,
        rotation=theta,
        angular_velocity=omega_world[:, 1],
        sliding=sliding,
        base_centre_x=base_x,
        com_x=pos[:, 0].copy(),
        com_z=pos[:, 2].copy(),
        velocity_x=qvel[:, 0].copy(),
        velocity_z=qvel[:, 2].copy(),
        uplift=corners_z.min(axis=1),
        n_contacts=ncon,
        alpha=math.atan2(shape.half_width, shape.half_height),
        half_width=shape.half_width,
        half_height=shape.half_height,
        impulse_delivered=delivered,
        settings=settings,
    )


def simulate_block(
    block: RectangularBlock,
    pulse=None,
    duration: float = 5.0,
    *,
    contact: ContactSettings | None = None,
    gravity: float = STANDARD_GRAVITY,
    record_every: int = 1,
    blast_mode: str = "auto",
    **initial,
) -> Block3DResult:
    """Run one block under a Method A blast: ``Block3DSimulator(contact, gravity, record_every,
    blast_mode=blast_mode).run(block, pulse, duration, **initial)``.

    Parameters
    ----------
    block : RectangularBlock
        The block; the blast loads its -x face (area 2h x 2w) towards +x.
    pulse : blastscale.blast.pulses.Pulse or None
        Reflected pressure pulse [Pa over s], t = 0 at shock arrival; None for no blast.
    duration : float
        Simulated time after arrival [s], > 0.
    contact : ContactSettings, optional
        Contact, time-step and solver settings; default ``ContactSettings()`` (full scale).
    gravity : float
        g [m/s^2], > 0.
    record_every : int
        Keep one state every ``record_every`` steps, >= 1.
    blast_mode : {"auto", "force", "kick"}
        How each step's impulse is applied (module docstring).
    **initial
        ``initial_rotation`` [rad], ``initial_angular_velocity`` [rad/s], ``initial_velocity``
        (3,) [m/s], as in :meth:`Block3DSimulator.run`.

    Returns
    -------
    Block3DResult
    """
    sim = Block3DSimulator(
        ContactSettings() if contact is None else contact, gravity, record_every, blast_mode=blast_mode
    )
    return sim.run(block, pulse, duration, **initial)
