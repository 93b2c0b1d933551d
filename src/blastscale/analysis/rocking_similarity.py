"""Prototype vs reduced-scale model in planar rocking (paper Sec. "Equations of motion", Figs. 6-9).

The Study designs the specimen once and its planar engine (:mod:`blastscale.study.engines`)
simulates the prototype (its pulse from ``d.prototype``) and the specimen (``d.specimen_block``,
pulse from ``d.specimen``, gravity ``g varsigma``) with the same rocking solver and restitution;
:func:`compare_rocking` then

1. writes both histories as response datasets (:func:`rocking_dataset`) and up-scales and
   compares them with the package's one comparison contract (:mod:`.compare`:
   ``t_p = t_m / f.time``, ``theta_p = theta_m / f.angle``,
   ``theta_dot_p = theta_dot_m / f.angular_velocity``), sampling the model exactly at the
   model times that correspond to the prototype's sampling times (no interpolation error),
2. reports the largest angle difference over the run, the peak ratio and whether the
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
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .._validate import BlastscaleInputError
from ..rocking.results import RockingResult
from ..similitude.experiment import ModelDesign
from .compare import compare_responses, upscale_dataset
from .upscale import upscale, upscale_summary

__all__ = ["RockingSimilarity", "PrototypeRocking", "compare_rocking", "rocking_dataset"]


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
        positive); attribute ``collapsed`` (0/1).
    """
    import xarray as xr

    if result.t_eval is None:
        raise BlastscaleInputError("t_eval = None: simulate with t_eval to compare sampled histories")
    return xr.Dataset(
        {
            "rotation_y": (("time", "body"), result.theta_eval[:, None], {"units": "rad", "dimension": "angle"}),
            "angular_velocity": (
                ("time", "body", "component"),
                result.theta_dot_eval[:, None, None],
                {"units": "rad/s", "dimension": "angular_velocity"},
            ),
        },
        coords={"time": ("time", result.t_eval, {"units": "s"}), "body": ["block"], "component": ["y"]},
        attrs={"collapsed": int(result.collapsed), "source": "blastscale.rocking"},
    )


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
    max_abs_rotation_diff : float
        max_t |theta_model - theta_prototype| [rad].
    max_abs_angular_velocity_diff : float
        max_t |theta_dot_model - theta_dot_prototype| [rad/s] (prototype units).
    max_abs_rotation_diff_to_tipping : float
        The same angle difference over the times up to the earlier of the two (up-scaled)
        overturn times [rad]; equals ``max_abs_rotation_diff`` when neither overturns. The fall
        after the tipping point amplifies any time shift, so this is the figure that measures
        the similarity of the rocking phase of an overturning block.
    collapse_time_diff : float or None
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
    first_peak_ratio : float
        First-peak angle of the model over that of the prototype [-] (largest angles when
        either has no peak; 1 when both overturn).
    outcomes_agree : bool
        Both overturn or both survive.
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
    max_abs_rotation_diff: float
    max_abs_angular_velocity_diff: float
    max_abs_rotation_diff_to_tipping: float
    collapse_time_diff: float | None
    tipping_angular_velocity_diff: float | None
    max_fall_phase_diff: float | None
    first_peak_ratio: float
    outcomes_agree: bool

    @cached_property
    def comparison(self) -> dict:
        """The comparison contract's view (:func:`~blastscale.analysis.compare.compare_responses`)
        of ``rotation_y`` and ``angular_velocity``: first peaks from the samples, differences,
        outcomes (computed when first asked: xarray datasets are not needed for the figures above)."""
        up = upscale_dataset(rocking_dataset(self.model), self.design.factors)
        return compare_responses(rocking_dataset(self.prototype), up, outcome="collapsed")

    def to_dict(self) -> dict:
        """Plain dict: ``prototype`` and ``model`` (up-scaled) summaries and ``similarity``."""
        return {
            "prototype": self.prototype.summary(),
            "model": upscale_summary(self.model.summary(), self.design.factors),
            "similarity": {
                "max_abs_rotation_diff_rad": self.max_abs_rotation_diff,
                "max_abs_angular_velocity_diff_rad_s": self.max_abs_angular_velocity_diff,
                "max_abs_rotation_diff_to_tipping_rad": self.max_abs_rotation_diff_to_tipping,
                "collapse_time_diff_s": self.collapse_time_diff,
                "tipping_angular_velocity_diff_rad_s": self.tipping_angular_velocity_diff,
                "max_fall_phase_diff_rad": self.max_fall_phase_diff,
                "first_peak_ratio": self.first_peak_ratio,
                "outcomes_agree": self.outcomes_agree,
            },
        }


def compare_rocking(
    prototype: RockingResult, model: RockingResult, design: ModelDesign, frequency_parameter: float
) -> RockingSimilarity:
    """Compare a prototype's rocking history with its specimen's, up-scaled (the planar engine's
    one comparison; the Study simulates both, :mod:`blastscale.study.engines`).

    Parameters
    ----------
    prototype : RockingResult
        The prototype's run, sampled at ``t_eval`` = the common times t [s].
    model : RockingResult
        The specimen's run, sampled at ``min(t * f.time, duration * f.time)`` (the specimen times
        that correspond to t exactly: no interpolation error) [specimen units].
    design : ModelDesign
        The experiment (its ``factors`` up-scale the specimen).
    frequency_parameter : float
        The prototype's p = sqrt(m g r / J_o) [1/s] (the fall's phase plane).

    Returns
    -------
    RockingSimilarity
    """
    f = design.factors
    t = prototype.t_eval
    # the specimen is sampled at exactly the times that correspond to t: up-scaled, its samples are
    # the prototype's times (no interpolation), so the comparison works on the arrays themselves
    th_m = upscale(model.theta_eval, f, "angle")
    om_m = upscale(model.theta_dot_eval, f, "angular_velocity")
    dth = float(np.max(np.abs(th_m - prototype.theta_eval)))
    dom = float(np.max(np.abs(om_m - prototype.theta_dot_eval)))
    tips = [x for x in (prototype.collapse_time, upscale(model.collapse_time, f, "time")) if x is not None]
    upto = t <= min(tips) if tips else np.ones(t.size, dtype=bool)
    dtip = float(np.max(np.abs(th_m - prototype.theta_eval)[upto]))
    dt_tip = dw_tip = fall = None
    if prototype.collapsed and model.collapsed:
        dt_tip = upscale(model.collapse_time, f, "time") - prototype.collapse_time
        dw_tip = (
            upscale(model.angular_velocity_at_tipping, f, "angular_velocity") - prototype.angular_velocity_at_tipping
        )
        fall = _fall_phase_diff(
            t,
            prototype.theta_eval,
            prototype.theta_dot_eval,
            th_m,
            om_m,
            max(prototype.collapse_time, upscale(model.collapse_time, f, "time")),
            frequency_parameter,
        )
    if prototype.collapsed and model.collapsed:
        ratio = 1.0
    elif prototype.peak_angles.size and model.peak_angles.size:
        ratio = float(abs(model.peak_angles[0]) / abs(prototype.peak_angles[0]))
    else:
        ratio = float(model.max_rotation / prototype.max_rotation) if prototype.max_rotation > 0 else math.nan
    return RockingSimilarity(
        design=design,
        prototype=prototype,
        model=model,
        t=t,
        theta_prototype=prototype.theta_eval,
        theta_model=th_m,
        theta_dot_prototype=prototype.theta_dot_eval,
        theta_dot_model=om_m,
        max_abs_rotation_diff=dth,
        max_abs_angular_velocity_diff=dom,
        max_abs_rotation_diff_to_tipping=dtip,
        collapse_time_diff=dt_tip,
        tipping_angular_velocity_diff=dw_tip,
        max_fall_phase_diff=fall,
        first_peak_ratio=ratio,
        outcomes_agree=bool(prototype.collapsed) == bool(model.collapsed),
    )


@dataclass(frozen=True)
class PrototypeRocking:
    """The planar engine's result for a prototype-only study (no specimen, no comparison).

    Attributes
    ----------
    prototype : RockingResult
        The prototype's run, sampled at ``t_eval``.
    """

    prototype: RockingResult
    model = None
    design = None
    outcomes_agree = None

    def to_dict(self) -> dict:
        """``prototype`` summary; ``model`` and ``similarity`` are None."""
        return {"prototype": self.prototype.summary(), "model": None, "similarity": None}
