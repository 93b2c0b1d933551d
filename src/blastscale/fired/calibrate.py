"""Calibration when asked: the contact parameters that best match the measured response (issue #25 item 7).

``restitution`` (planar blocks): the coefficient e of the planar rocking model (Housner 1963: the angular
velocity x e at each impact) that, with a factor on the charge as fired (a nuisance parameter: the effective
charge's own error would otherwise be absorbed by e), minimises the sum of squares of the measured minus the
re-simulated horizontal displacement of every marker over the frames after the firing signal (the
re-simulation, :mod:`.refit`; scipy ``least_squares``, trust-region reflective, bounded). Uncertainties are the
Gauss-Newton ones, ``cov = s^2 (J^T J)^-1`` with ``s^2`` the residual variance (Bates & Watts 1988, ch. 2;
independent residuals assumed). The up-scaled prediction is
then redone: the Study of the scenario with the calibrated restitution (the prototype's first peak and its
outcome).

``friction`` (every kind but a block, on the 3D engine): the Coulomb coefficient mu (``structure.friction``)
that minimises the same sum of squares, the charge as fired held (a 1-D search: each evaluation is a 3D
re-simulation). Bounded minimisation over ``FRICTION_BOUNDS`` by Brent's method (golden-section steps with
parabolic interpolation; Brent 1973, ch. 5; scipy ``minimize_scalar(method="bounded")``) to
``FRICTION_XATOL``, at most ``FRICTION_EVALUATIONS`` evaluations; then one Gauss-Newton step, J = dr/dmu by a
central difference of +-``FRICTION_STEP`` (three more runs; kept when it lowers the sum of squares), and the
95 % interval from the 1-D Gauss-Newton variance ``s^2 / (J^T J)`` (Bates & Watts 1988, ch. 2). Where
nothing slides mu does not enter the response: J ~ 0 and the interval is infinite (said in the result's
``identifiable``). A block is refused (one line): the planar rocking model has no sliding, so friction does
not enter it. The prototype's prediction is then redone through the Study (prototype alone, 3D) with mu.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import least_squares, minimize_scalar

from .._validate import BlastscaleInputError, check_choice
from ..analysis.upscale import upscale
from ..rocking.system import housner_restitution
from ..study.study import Study
from .outcome import pose_marker_history
from .refit import OUTCOMES, marker_history, simulate_specimen
from .tracks import track_first_peak

__all__ = [
    "CALIBRATIONS",
    "FRICTION_BOUNDS",
    "calibrate_friction",
    "calibrate_restitution",
    "check_applies",
    "check_calibrate",
]

#: What ``--calibrate`` accepts.
CALIBRATIONS = ("restitution", "friction")
_Z95 = 1.959963984540054
#: Search interval of the friction coefficient [-], its tolerance and the most evaluations of the search.
FRICTION_BOUNDS = (0.2, 1.0)
FRICTION_XATOL = 0.002
FRICTION_EVALUATIONS = 14
#: Step of the central difference dr/dmu [-].
FRICTION_STEP = 0.01


def check_calibrate(names) -> tuple:
    """The parameters to calibrate, checked: one line for an unknown name (whether one applies to the
    structure: :func:`check_applies`)."""
    out = tuple(n.strip() for n in names if n.strip())
    for n in out:
        check_choice("calibrate", n, CALIBRATIONS)
    return out


def check_applies(names, design, kind: str) -> None:
    """One line when a calibration does not apply to the structure (before anything is simulated):
    ``restitution`` needs a block (planar rocking), ``friction`` any other kind (a block's planar model has no
    sliding)."""
    block = design.specimen_block is not None
    if "restitution" in names and not block:
        raise BlastscaleInputError(
            f"calibrate = 'restitution' needs a block (planar rocking): structure.kind = {kind!r}"
        )
    if "friction" in names and block:
        raise BlastscaleInputError(
            "calibrate = 'friction' does not apply to a block: the planar rocking model has "
            "no sliding, friction does not enter it (valid for a block: restitution)"
        )


def _residuals(run, tracks: dict) -> np.ndarray:
    """Measured minus re-simulated horizontal displacement [m] of every marker, frames after the firing signal
    and within the simulated time."""
    res = []
    for point, t, ux in tracks.values():
        h = marker_history(run, point)
        keep = (t >= 0) & (t <= h["t"][-1])
        res.append(ux[keep] - np.interp(t[keep], h["t"], h["ux"]))
    return np.concatenate(res)


def calibrate_restitution(
    scenario, design, tracks: dict, charge_kg: float, standoff_m: float, bounds=(0.3, 1.0)
) -> dict:
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
    check_applies(("restitution",), design, scenario.structure.kind)
    if not tracks:
        raise BlastscaleInputError("calibrate needs marker tracks: [fired] tracks is not given")

    def residuals(x) -> np.ndarray:
        run = simulate_specimen(
            scenario, design, charge_kg * float(x[0]), standoff_m, "planar", restitution=float(x[1])
        )
        return _residuals(run, tracks)

    e0 = scenario.simulation.restitution or housner_restitution(design.specimen_block.alpha)  # the start: the model's
    x0 = [1.0, float(np.clip(e0, *bounds))]
    opt = least_squares(residuals, x0, bounds=([0.5, bounds[0]], [2.0, bounds[1]]), diff_step=1e-4, x_scale=[0.1, 0.1])
    n = opt.fun.size
    s2 = float(np.sum(opt.fun**2)) / max(n - 2, 1)
    try:
        cov = np.linalg.inv(opt.jac.T @ opt.jac) * s2
        sig = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    except np.linalg.LinAlgError:
        sig = np.full(2, math.inf)
    e = float(opt.x[1])
    proto = (
        Study.from_design(scenario, design, system="prototype", engine="planar", restitution=e).run().planar.prototype
    )
    return {
        "restitution": e,
        "restitution_ci95": _Z95 * float(sig[1]),
        "charge_factor": float(opt.x[0]),
        "charge_factor_ci95": _Z95 * float(sig[0]),
        "misfit_rms_m": math.sqrt(float(np.mean(opt.fun**2))),
        "samples": n,
        "prototype_first_peak_rad": float(proto.peak_angles[0]) if proto.peak_angles.size else None,
        "prototype_max_rotation_rad": float(proto.max_rotation),
        "prototype_outcome": OUTCOMES[bool(proto.collapsed)],
    }


def calibrate_friction(
    scenario, design, tracks: dict, charge_kg: float, standoff_m: float, bounds=FRICTION_BOUNDS
) -> dict:
    """The friction coefficient [-] that best matches the measured response (module docstring).

    Parameters as :func:`calibrate_restitution` (``scenario`` of any kind but a block).

    Returns
    -------
    dict
        ``friction``, ``friction_ci95`` (half-width; inf when not identifiable), ``identifiable``,
        ``at_bound`` (the optimum within the tolerance of a bound), ``misfit_rms_m``, ``samples``,
        ``evaluations`` (3D runs of the specimen), ``prototype_first_peak_m`` (marker name -> the prototype's
        first peak at the marker's up-scaled point [m], None when it has none), ``prototype_outcome``.
    """
    check_applies(("friction",), design, "block")
    if not tracks:
        raise BlastscaleInputError("calibrate needs marker tracks: [fired] tracks is not given")
    runs: dict = {}

    def residuals(mu: float) -> np.ndarray:
        if mu not in runs:
            run = simulate_specimen(scenario, design, charge_kg, standoff_m, "3d", friction=float(mu))
            runs[mu] = _residuals(run, tracks)
        return runs[mu]

    lo, hi = float(bounds[0]), float(bounds[1])
    opt = minimize_scalar(
        lambda mu: float(np.sum(residuals(mu) ** 2)),
        bounds=(lo, hi),
        method="bounded",
        options={"xatol": FRICTION_XATOL, "maxiter": FRICTION_EVALUATIONS},
    )
    mu = float(opt.x)
    r = residuals(mu)
    h = min(FRICTION_STEP, mu - lo, hi - mu) or FRICTION_STEP
    jac = (residuals(min(mu + h, hi)) - residuals(max(mu - h, lo))) / (min(mu + h, hi) - max(mu - h, lo))
    jtj = float(jac @ jac)
    if jtj > 0:  # one Gauss-Newton step below the search's tolerance, kept if it lowers the sum of squares
        step = float(np.clip(mu - float(jac @ r) / jtj, max(mu - h, lo), min(mu + h, hi)))
        if float(np.sum(residuals(step) ** 2)) < float(np.sum(r**2)):
            mu, r = step, residuals(step)
    s2 = float(np.sum(r**2)) / max(r.size - 1, 1)
    ok = jtj > 0 and s2 / jtj < (hi - lo) ** 2
    ci = _Z95 * math.sqrt(s2 / jtj) if ok else math.inf
    proto, st = _prototype_3d(scenario, design, mu)
    peaks = {}
    for name, (point, _, _) in tracks.items():
        ux, _ = pose_marker_history(
            proto.dataset, st, upscale(np.asarray(point, dtype=float), design.factors, "length")
        )
        t = np.asarray(proto.dataset["time"].values)
        largest = float(np.max(np.abs(ux)))
        peaks[name] = track_first_peak(t, ux, noise=1e-3 * largest, smooth=False).first_peak_m if largest > 0 else None
    return {
        "friction": mu,
        "friction_ci95": ci,
        "identifiable": bool(ok),
        "at_bound": bool(min(mu - lo, hi - mu) <= 2 * FRICTION_XATOL),
        "misfit_rms_m": math.sqrt(float(np.mean(r**2))),
        "samples": int(r.size),
        "evaluations": len(runs),
        "prototype_first_peak_m": peaks,
        "prototype_outcome": OUTCOMES[bool(proto.dataset.attrs["collapsed"])],
    }


def _prototype_3d(scenario, design, friction: float):
    """The design's prototype alone on the 3D engine with the friction coefficient ``friction`` [-], through the
    Study's entry from a design (:meth:`~blastscale.study.Study.from_design`): (its Response3D, its structure)."""
    r = Study.from_design(scenario, design, system="prototype", engine="3d", friction=friction).run()
    return r.response3d.prototype, r.structure
