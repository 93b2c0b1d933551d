"""Prototype vs reduced-scale model in planar rocking (paper Sec. "Equations of motion", Figs. 6-9).

Given a prototype block, a scenario (charge W at stand-off R) and the scales lambda (length),
gamma (density) and varsigma (gravity), :func:`compare_rocking`

1. designs the model with :func:`blastscale.similitude.design_model` (model charge and
   stand-off from the general law, or Hopkinson-Cranz),
2. simulates the prototype (its pulse from ``d.prototype``) and the model
   (``block.scaled(lambda, gamma)``, pulse from ``d.model``, gravity ``g varsigma``) with the
   same rocking solver and restitution,
3. writes both histories as response datasets (:func:`rocking_dataset`) and up-scales and
   compares them with the package's one comparison contract (:mod:`.compare`:
   ``t_p = t_m / f.time``, ``theta_p = theta_m / f.angle``,
   ``theta_dot_p = theta_dot_m / f.angular_velocity``), sampling the model exactly at the
   model times that correspond to the prototype's sampling times (no interpolation error),
4. reports the largest angle difference over the run, the peak ratio and whether the
   outcomes (rock / overturn) agree; for overturning bodies also the difference up to the
   tipping point, the tipping-time and tipping-velocity differences and the difference of
   the two falls on a common phase (angular velocity at equal angle).

With an impulsive load the model is an exact similarity transform of the prototype: the
up-scaled history equals the prototype's to round-off. With finite pulses the blast cannot
deliver the required pressure and duration factors at once (only the impulse is matched,
paper Eq. 8), and the up-scaled model departs by about 1e-4 rad for the paper's block.

Which figure measures similarity when the body overturns: the fall that follows the tipping
point is free motion (the ms-long pulse is long over) away from an unstable equilibrium, so
the ~1e-4 relative energy difference left by the finite pulse shifts the tipping time by
~0.5 ms (100 kg; ~2 ms at 85 kg, diverging like a logarithm at the critical charge), and at
equal times during the fall the angles then differ by (fall speed) x (time shift), 1e-3 to
6e-3 rad for the paper's block, until both lie on the ground. Aligning the falls at their
tipping points does not help (the fall amplifies the velocity difference like sinh(p t)).
On a common phase the falls agree: energy conservation gives
``theta_dot_m^2 - theta_dot_p^2 = const`` at equal angle, so the angular velocities at equal
angle differ by at most the difference at the tipping point (paper: "the scaling law is found
to correctly capture the dynamics ... when the phase space is examined"). The same
ill-conditioning hits rocking bodies near the threshold (79.8 kg: the first excursion climbs
close to the top, where the time spent diverges; whole-run difference 4e-2 to 9e-2 rad while
the outcomes agree and the first peaks agree to 0.7 %).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._validate import BlastscaleInputError, check_positive
from ..blast.parameters import DEFAULT_BLAST_MODEL
from ..rocking import DEFAULT_SOLVER, RockingResult, RockingSolver, check_count
from ..rocking.system import RockingSystem
from ..similitude import ModelDesign, design_model
from ..structures.block import STANDARD_GRAVITY, RectangularBlock
from .compare import align, compare_responses, upscale_dataset

__all__ = ["RockingSimilarity", "compare_rocking", "rocking_dataset", "upscaled_summary"]

_SHAPES = ("friedlander", "triangular", "impulsive")


def _opt_div(x: float | None, f: float) -> float | None:
    return None if x is None else x / f


def _fall_phase_diff(t, th_p, om_p, th_m, om_m, t_tipped: float, p: float) -> float | None:
    """max |om_m - om_p| / p [-] at equal angle over the samples where both bodies fall to the
    same side (after ``t_tipped`` [s], strictly between the tipping and the lying angles), the
    model's angular velocity linearly interpolated at the prototype's angles (|theta| grows
    monotonically during a fall). None when they fall to different sides or share no sample."""
    side = np.sign(th_p[-1])
    if side == 0 or np.sign(th_m[-1]) != side:
        return None
    half_pi = 0.5 * math.pi
    fall = t >= t_tipped
    ap, am = side * th_p, side * th_m
    mp = fall & (ap < half_pi)
    mm = fall & (am < half_pi)
    if np.count_nonzero(mm) < 2:
        return None
    # prototype angles inside the range the model's samples cover (no extrapolation)
    mp &= (ap >= am[mm][0]) & (ap <= am[mm][-1])
    if not np.any(mp):
        return None
    om_m_at = np.interp(ap[mp], am[mm], om_m[mm])
    return float(np.max(np.abs(om_m_at - om_p[mp]))) / p


def rocking_dataset(result: RockingResult):
    """A planar rocking history as a response dataset of the comparison contract.

    Parameters
    ----------
    result : RockingResult
        A run simulated with ``t_eval`` (the sampled history).

    Returns
    -------
    xarray.Dataset
        Coordinates ``time`` [s], ``body`` = ["block"], ``component`` = ["y"]; variables
        ``rotation_y`` (time, body) [rad] (dimension ``angle``) and ``angular_velocity``
        (time, body, component) [rad/s] (``angular_velocity``, about +y, top towards +x
        positive); attribute ``overturned`` (0/1).
    """
    import xarray as xr

    if result.t_eval is None:
        raise BlastscaleInputError("t_eval = None: simulate with t_eval to compare sampled histories")
    return xr.Dataset(
        {
            "rotation_y": (("time", "body"), result.theta_eval[:, None], {"units": "rad", "dimension": "angle"}),
            "angular_velocity": (("time", "body", "component"), result.theta_dot_eval[:, None, None],
                                 {"units": "rad/s", "dimension": "angular_velocity"}),
        },
        coords={"time": ("time", result.t_eval, {"units": "s"}), "body": ["block"], "component": ["y"]},
        attrs={"overturned": int(result.overturned), "source": "blastscale.rocking"},
    )


def upscaled_summary(model: RockingResult, design: ModelDesign) -> dict:
    """The model's scalar results in prototype units (times / f.time, angles / f.angle):
    keys ``overturned``, ``max_angle_rad``, ``overturn_time_s``, ``first_impact_time_s``,
    ``n_impacts``, ``end_time_s``."""
    f = design.factors
    return {
        "overturned": bool(model.overturned),
        "max_angle_rad": float(model.max_angle) / f.angle,
        "overturn_time_s": _opt_div(model.overturn_time, f.time),
        "first_impact_time_s": _opt_div(model.first_impact_time, f.time),
        "n_impacts": model.n_impacts,
        "end_time_s": float(model.end_time) / f.time,
    }


@dataclass(frozen=True)
class RockingSimilarity:
    """Prototype and up-scaled model rocking histories and their agreement (SI, prototype units).

    Attributes
    ----------
    design : ModelDesign
        The model experiment (charges, stand-offs, factors).
    prototype, model : RockingResult
        The two simulations, each in its own units.
    t : ndarray
        Common prototype times [s].
    theta_prototype, theta_model : ndarray
        Rocking angle of the prototype and of the up-scaled model at ``t`` [rad].
    theta_dot_prototype, theta_dot_model : ndarray
        Angular velocity of the prototype and of the up-scaled model at ``t`` [rad/s].
    max_abs_angle_diff : float
        max_t |theta_model - theta_prototype| [rad].
    max_abs_angular_velocity_diff : float
        max_t |theta_dot_model - theta_dot_prototype| [rad/s] (prototype units).
    max_abs_angle_diff_to_tipping : float
        The same angle difference over the times up to the earlier of the two (up-scaled)
        overturn times [rad]; equals ``max_abs_angle_diff`` when neither overturns. The fall
        after the tipping point amplifies any time shift, so this is the figure that measures
        the similarity of the rocking phase of an overturning block.
    overturn_time_diff : float or None
        Up-scaled model overturn time minus the prototype's [s]; None unless both overturn.
    tipping_angular_velocity_diff : float or None
        Up-scaled model |theta_dot| at the tipping point minus the prototype's [rad/s]; None
        unless both overturn.
    max_fall_phase_diff : float or None
        Both overturn to the same side: max over the common part of the falls (after both
        tipped, before either lies down) of ``|theta_dot_m - theta_dot_p| / p`` at equal angle
        [rad, i.e. the angle-velocity phase plane in the dimensionless time p t]. When the
        pulse is over at the tipping point (ms-long pulses, tipping after ~1 s) it is bounded
        by ``|tipping_angular_velocity_diff| / p`` (energy conservation); None otherwise.
    peak_ratio : float
        First-peak angle of the model over that of the prototype [-] (largest angles when
        either has no peak; 1 when both overturn).
    outcomes_agree : bool
        Both overturn or both survive.
    pulse : str
        Pulse shape used.
    comparison : dict
        The contract's comparison (:func:`~blastscale.analysis.compare.compare_responses`) of
        ``rotation_y`` and ``angular_velocity`` (first peaks from the samples, differences).
    """

    design: ModelDesign
    prototype: RockingResult
    model: RockingResult
    t: np.ndarray
    theta_prototype: np.ndarray
    theta_model: np.ndarray
    theta_dot_prototype: np.ndarray
    theta_dot_model: np.ndarray
    max_abs_angle_diff: float
    max_abs_angular_velocity_diff: float
    max_abs_angle_diff_to_tipping: float
    overturn_time_diff: float | None
    tipping_angular_velocity_diff: float | None
    max_fall_phase_diff: float | None
    peak_ratio: float
    outcomes_agree: bool
    pulse: str
    extra: dict = field(default_factory=dict, repr=False)
    comparison: dict = field(default_factory=dict, repr=False)

    def to_dict(self) -> dict:
        """Plain dict: ``prototype`` and ``model`` (up-scaled) summaries and ``similarity``."""
        return {
            "prototype": self.prototype.summary(),
            "model": upscaled_summary(self.model, self.design),
            "similarity": {
                "max_abs_angle_diff_rad": self.max_abs_angle_diff,
                "max_abs_angular_velocity_diff_rad_s": self.max_abs_angular_velocity_diff,
                "max_abs_angle_diff_to_tipping_rad": self.max_abs_angle_diff_to_tipping,
                "overturn_time_diff_s": self.overturn_time_diff,
                "tipping_angular_velocity_diff_rad_s": self.tipping_angular_velocity_diff,
                "max_fall_phase_diff_rad": self.max_fall_phase_diff,
                "peak_ratio": self.peak_ratio,
                "outcomes_agree": self.outcomes_agree,
            },
        }


def compare_rocking(
    block: RectangularBlock,
    charge: float,
    standoff: float,
    scale: float,
    density_ratio: float = 1.0,
    gravity_ratio: float = 1.0,
    *,
    pulse: str = "friedlander",
    model: str = DEFAULT_BLAST_MODEL,
    law: str = "general",
    duration: float = 5.0,
    n_samples: int = 2001,
    gravity: float = STANDARD_GRAVITY,
    restitution: float | None = None,
    solver: RockingSolver | None = None,
    design: ModelDesign | None = None,
) -> RockingSimilarity:
    """Simulate a prototype block and its reduced-scale model and compare them.

    Parameters
    ----------
    block : RectangularBlock
        Prototype block.
    charge : float
        Prototype TNT charge W [kg].
    standoff : float
        Prototype stand-off R [m].
    scale, density_ratio, gravity_ratio : float
        lambda, gamma, varsigma = model / prototype [-].
    pulse : {"friedlander", "triangular", "impulsive"}
        Reflected pulse shape (paper Eqs. 1, 3, impulsive limit).
    model : str
        Blast model (``"kingery-bulmash"`` or ``"masi2021"``).
    law : {"general", "hopkinson-cranz"}
        Scaling law for the model charge.
    duration : float
        Prototype time to simulate [s] (the model runs ``duration * f.time``).
    n_samples : int
        Number of common sampling times over [0, duration] (>= 2).
    gravity : float
        Prototype gravity [m/s^2]; the model's is ``gravity * gravity_ratio``.
    restitution : float, optional
        Restitution e for both (default Housner's, the same for both since alpha is).
    solver : RockingSolver, optional
        Solver (default tolerances rtol 1e-10, atol 1e-12).
    design : ModelDesign, optional
        A design made beforehand with ``geometry=block`` (a caller that designs once, e.g.
        :class:`blastscale.study.Study`); it then replaces the design from ``charge`` ...
        ``gravity``, which must describe the same scenario.

    Returns
    -------
    RockingSimilarity
    """
    if not isinstance(block, RectangularBlock):
        raise BlastscaleInputError(f"block must be a RectangularBlock, got {type(block).__name__}")
    if pulse not in _SHAPES:
        raise BlastscaleInputError(f"pulse = {pulse!r} is not known: valid values are {', '.join(_SHAPES)}")
    dur = float(check_positive("duration", duration, "s"))
    n_samples = check_count("n_samples", n_samples, 2)
    solver = solver or DEFAULT_SOLVER
    d = design if design is not None else design_model(
        charge, standoff, scale, density_ratio, gravity_ratio, law=law, model=model, geometry=block, gravity=gravity
    )
    f = d.factors
    t = np.linspace(0.0, dur, int(n_samples))
    sys_p = RockingSystem.from_block(block, gravity, restitution)
    sys_m = RockingSystem.from_block(d.model_block, gravity * d.gravity_ratio, restitution)
    res_p = solver.simulate(sys_p, d.prototype.pulse(pulse), dur, t_eval=t)
    dur_m = dur * f.time
    t_m = np.minimum(t * f.time, dur_m)
    res_m = solver.simulate(sys_m, d.model.pulse(pulse), dur_m, t_eval=t_m)
    proto_ds = rocking_dataset(res_p)
    up_ds = upscale_dataset(rocking_dataset(res_m), f)
    cmp = compare_responses(proto_ds, up_ds, outcome="overturned")
    _, model_at = align(proto_ds, up_ds)
    th_m = model_at["rotation_y"].values[:, 0]
    om_m = model_at["angular_velocity"].values[:, 0, 0]
    dth = cmp["variables"]["rotation_y"]["block"]["max_abs_diff"]
    dom = cmp["variables"]["angular_velocity"]["block"]["max_abs_diff"]
    tips = [x for x in (res_p.overturn_time, _opt_div(res_m.overturn_time, f.time)) if x is not None]
    upto = t <= min(tips) if tips else np.ones(t.size, dtype=bool)
    dtip = float(np.max(np.abs(th_m - res_p.theta_eval)[upto]))
    dt_tip = dw_tip = fall = None
    if res_p.overturned and res_m.overturned:
        dt_tip = res_m.overturn_time / f.time - res_p.overturn_time
        dw_tip = res_m.angular_velocity_at_tipping / f.angular_velocity - res_p.angular_velocity_at_tipping
        fall = _fall_phase_diff(
            t, res_p.theta_eval, res_p.theta_dot_eval, th_m, om_m,
            max(res_p.overturn_time, res_m.overturn_time / f.time), sys_p.frequency_parameter,
        )
    if res_p.overturned and res_m.overturned:
        ratio = 1.0
    elif res_p.peak_angles.size and res_m.peak_angles.size:
        ratio = float(abs(res_m.peak_angles[0]) / abs(res_p.peak_angles[0]))
    else:
        ratio = float(res_m.max_angle / res_p.max_angle) if res_p.max_angle > 0 else math.nan
    return RockingSimilarity(
        design=d,
        prototype=res_p,
        model=res_m,
        t=t,
        theta_prototype=res_p.theta_eval,
        theta_model=th_m,
        theta_dot_prototype=res_p.theta_dot_eval,
        theta_dot_model=om_m,
        max_abs_angle_diff=dth,
        max_abs_angular_velocity_diff=dom,
        max_abs_angle_diff_to_tipping=dtip,
        overturn_time_diff=dt_tip,
        tipping_angular_velocity_diff=dw_tip,
        max_fall_phase_diff=fall,
        peak_ratio=ratio,
        outcomes_agree=bool(cmp["outcomes_agree"]),
        pulse=pulse,
        comparison=cmp,
    )
