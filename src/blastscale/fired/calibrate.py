"""Calibration when asked: the contact parameters that best match the measured rocking (issue #25 item 7).

``restitution`` (planar blocks): the coefficient e of the planar rocking model (Housner 1963: the angular
velocity x e at each impact) that, with a factor on the charge as fired (a nuisance parameter: the effective
charge's own error would otherwise be absorbed by e), minimises the sum of squares of the measured minus the
re-simulated horizontal displacement of every marker over the frames after the firing signal (the
re-simulation, :mod:`.refit`; scipy ``least_squares``, trust-region reflective, bounded). Uncertainties are the
Gauss-Newton ones, ``cov = s^2 (J^T J)^-1`` with ``s^2`` the residual variance (Bates & Watts 1988, ch. 2;
independent residuals assumed). The up-scaled prediction is
then redone: the Study of the scenario with the calibrated restitution (the prototype's first peak and its
outcome). ``friction`` needs the 3D engine's sliding and is not available yet (one line).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import least_squares

from .._validate import BlastscaleInputError
from ..rocking.system import housner_restitution
from ..study import Study
from .refit import OUTCOMES, marker_history, simulate_specimen

__all__ = ["CALIBRATIONS", "calibrate_restitution", "check_calibrate"]

#: What ``--calibrate`` accepts.
CALIBRATIONS = ("restitution", "friction")
_Z95 = 1.959963984540054


def check_calibrate(names) -> tuple:
    """The parameters to calibrate, checked: one line for an unknown name or one not available yet."""
    out = tuple(n.strip() for n in names if n.strip())
    for n in out:
        if n not in CALIBRATIONS:
            raise BlastscaleInputError(f"calibrate = {n!r} is not known: valid values are {', '.join(CALIBRATIONS)}")
        if n == "friction":
            raise BlastscaleInputError("calibrate = 'friction' is not available yet: it needs the 3D engine's sliding "
                                       "histories (valid now: restitution, for a block)")
    return out


def calibrate_restitution(scenario, design, tracks: dict, charge_kg: float, standoff_m: float,
                          bounds=(0.3, 1.0)) -> dict:
    """The restitution [-] that best matches the measured rocking (module docstring).

    Parameters
    ----------
    scenario : Scenario
        The scenario (a block).
    design : ModelDesign
    tracks : dict
        Marker name -> (point_m, t [s], ux [m]): the measured horizontal displacements.
    charge_kg, standoff_m : float
        The load as fired [kg TNT], [m].
    bounds : (float, float)
        Search interval of e.

    Returns
    -------
    dict
        ``restitution``, ``restitution_ci95`` (half-width), ``charge_factor`` (on ``charge_kg``) and its
        ``charge_factor_ci95``, ``misfit_rms_m`` (at the optimum), ``samples``,
        ``prototype_first_peak_rad``, ``prototype_max_rotation_rad``, ``prototype_outcome`` (the Study redone).
    """
    if design.specimen_block is None:
        raise BlastscaleInputError(f"calibrate = 'restitution' needs a block (planar rocking): structure.kind = "
                                   f"{scenario.structure.kind!r}")
    if not tracks:
        raise BlastscaleInputError("calibrate needs marker tracks: [fired] tracks is not given")

    def residuals(x) -> np.ndarray:
        sc = scenario.with_values({"simulation.restitution": float(x[1])})
        run = simulate_specimen(sc, design, charge_kg * float(x[0]), standoff_m, "planar")
        res = []
        for point, t, ux in tracks.values():
            h = marker_history(run, point)
            keep = (t >= 0) & (t <= h["t"][-1])
            res.append(ux[keep] - np.interp(t[keep], h["t"], h["ux"]))
        return np.concatenate(res)

    e0 = scenario.simulation.restitution or housner_restitution(design.specimen_block.alpha)  # the start: the model's
    x0 = [1.0, float(np.clip(e0, *bounds))]
    opt = least_squares(residuals, x0, bounds=([0.5, bounds[0]], [2.0, bounds[1]]), diff_step=1e-4, x_scale=[0.1, 0.1])
    n = opt.fun.size
    s2 = float(np.sum(opt.fun ** 2)) / max(n - 2, 1)
    try:
        cov = np.linalg.inv(opt.jac.T @ opt.jac) * s2
        sig = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    except np.linalg.LinAlgError:
        sig = np.full(2, math.inf)
    e = float(opt.x[1])
    proto = Study(scenario.with_values({"simulation.restitution": e, "engine": "planar"})).run().planar.prototype
    return {"restitution": e, "restitution_ci95": _Z95 * float(sig[1]), "charge_factor": float(opt.x[0]),
            "charge_factor_ci95": _Z95 * float(sig[0]), "misfit_rms_m": math.sqrt(float(np.mean(opt.fun ** 2))),
            "samples": n,
            "prototype_first_peak_rad": float(proto.peak_angles[0]) if proto.peak_angles.size else None,
            "prototype_max_rotation_rad": float(proto.max_rotation), "prototype_outcome": OUTCOMES[bool(proto.collapsed)]}
