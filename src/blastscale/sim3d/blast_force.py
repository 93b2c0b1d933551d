"""The blast as a force on a rigid body: the paper's Method A (uniform, simultaneous load).

The reflected pulse P(t) at the stand-off distance acts on the whole front face at once; the
resultant ``P(t) S`` is applied at the face centre along the face's *current* inward normal,
re-evaluated every time step from the body's orientation, together with its moment about the
centre of mass (for a box the line of action passes through the centre of mass, so that moment
is zero; the moment about a base edge, ``P S h``, is what rocks the block).

Time integration of the pulse. A full-scale pulse lasts about a millisecond and a
reduced-scale one ~sqrt(lambda) of that, i.e. only a few time steps. Sampling P(t_n) would
make the transferred impulse depend on where the samples fall (a Friedlander pulse sampled at
its peak with dt = t_o/5 over-counts the impulse by ~10%). Instead each step receives the
exact impulse of the pulse over that step as a constant force,

.. math:: \\bar F_n = S\\,\\frac{I(t_{n+1}) - I(t_n)}{t_{n+1} - t_n},
          \\qquad I(t) = \\int_0^t P\\,dt' ,

so that, with MuJoCo's semi-implicit Euler update ``v_{n+1} = v_n + dt M^{-1} F_n``, the
momentum delivered equals ``i S`` to round-off, whatever the step, and the impulsive limit
(a Dirac, :class:`~blastscale.blast.pulses.Impulsive`) is the special case of one step.
The price is that the peak force is smeared over one step; for a rigid body the response
depends on the impulse and (weakly) on the moment of the pulse, not on the peak.

References
----------
.. [1] Masi, Stefanou & Maffi-Berthier, *Scaling laws ...*, Sec. "Application to multi-drum
       columns", Method A; Eq. (1)-(3) for the pulse.
"""

from __future__ import annotations

import numpy as np

from .._validate import BlastscaleInputError, check_finite, check_positive

__all__ = ["mean_pressures", "step_forces"]


def step_forces(pulse, area: float, times) -> np.ndarray:
    """Constant force per step that carries the pulse's exact impulse, Method A.

    Parameters
    ----------
    pulse : blastscale.blast.pulses.Pulse
        Pressure pulse with ``cumulative_impulse(t)`` [Pa*s], t = 0 at shock arrival.
    area : float
        Loaded face area S [m^2].
    times : array_like
        Step boundaries t_0 < t_1 < ... < t_N [s] (t_0 = 0 is the arrival).

    Returns
    -------
    ndarray, shape (N,)
        :math:`\\bar F_n = S (I(t_{n+1}) - I(t_n)) / (t_{n+1} - t_n)` [N]. The impulse before
        t_0 is taken as zero, so a Dirac pulse at t_0 falls entirely into the first step.
    """
    S = float(check_positive("loaded area", area, "m^2"))
    t = check_finite("step times", times, "s")
    if t.ndim != 1 or t.size < 2:
        raise BlastscaleInputError(f"step times must be 1-D with at least 2 values, got shape {t.shape}")
    if np.any(np.diff(t) <= 0.0):
        k = int(np.flatnonzero(np.diff(t) <= 0.0)[0])
        raise BlastscaleInputError(
            f"step times = {t[k + 1]:.6g} s (element {k + 1}) is out of range: must be > the previous time {t[k]:.6g} s"
        )
    if not hasattr(pulse, "cumulative_impulse"):
        raise BlastscaleInputError(f"pulse = {pulse!r} is not a pulse: expected a blastscale.blast.pulses.Pulse")
    return S * mean_pressures(pulse, t)


def mean_pressures(pulse, times) -> np.ndarray:
    """Mean pressure of each step, (I(t_{n+1}) - I(t_n)) / (t_{n+1} - t_n) [Pa].

    Parameters
    ----------
    pulse : blastscale.blast.pulses.Pulse
        Pulse with ``cumulative_impulse(t)`` [Pa*s], t = 0 at shock arrival.
    times : ndarray (N + 1,)
        Increasing step boundaries [s] (not validated: the callers check them once).

    Returns
    -------
    ndarray (N,)
        [Pa]. The running impulse is zero up to t = 0 included, so a Dirac at t = 0 falls into
        the step that starts there, and steps before the arrival get zero.
    """
    t = np.asarray(times, dtype=float)
    cum = np.array(pulse.cumulative_impulse(np.maximum(t, 0.0)), dtype=float)
    cum[t <= 0.0] = 0.0  # no impulse before (or at) arrival
    return np.diff(cum) / np.diff(t)
