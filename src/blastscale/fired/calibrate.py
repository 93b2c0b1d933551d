"""Calibration when asked: the contact parameters that best match the measured response (issue #25 item 7),
reported only when the record identifies them (issue #35 item 4).

``restitution`` (planar blocks): the coefficient e of the planar rocking model (Housner 1963: the angular
velocity x e at each impact) that, with a factor on the charge as fired (a nuisance parameter: the effective
charge's own error would otherwise be absorbed by e), minimises the sum of squares of the measured minus the
re-simulated horizontal displacement of every marker over the frames after the firing signal (the
re-simulation, :mod:`.refit`; scipy ``least_squares``, trust-region reflective, bounded). Its profile
(:func:`_profile`) is the misfit with the charge factor re-optimised at each e.

``friction`` (every kind but a block, on the 3D engine): the Coulomb coefficient mu (``structure.friction``)
whose re-simulation, the charge as fired held, minimises the same sum of squares; each evaluation is a 3D
re-simulation. A block is refused (one line): the planar rocking model has no sliding, so friction does not
enter it.

**The profile** (both): the RMS misfit ``m(x) = sqrt(mean(r^2))`` of the parameter x over its searched range
``[lo, hi]``: a grid of ``PROFILE_GRID`` evenly spaced values (the whole range is seen, so the search cannot
stop in a local dip far from the best), Brent's bounded search (golden-section steps with parabolic
interpolation; Brent 1973, ch. 5; scipy ``minimize_scalar(method="bounded")``) between the best grid value's
neighbours to ``xatol``, then ``PROFILE_EDGE_STEPS`` bisections of each edge of the accepted set (below).

**Identifiability before a number.** With sigma the tracks' noise (:func:`~.tracks.track_noise`, pooled over
the markers' frames: ``sigma^2 = sum n_i sigma_i^2 / sum n_i``), x* the best value and m* = m(x*), a value
is reported only when both hold:

1. **the misfit is the noise**: ``m* <= MISFIT_NOISE_MULTIPLE x sigma``. A model that reproduces the record
   leaves residuals of the noise alone, ``m*/sigma = 1 +- 1/sqrt(2n)`` (``n m*^2 / sigma^2`` is chi-square
   with n degrees of freedom; n ~ 10^3 frames: +-0.02); the multiple 2 (residual variance 4 sigma^2) leaves
   room for the noise estimate's own error and the interpolation of the re-simulation onto the frames, and
   no more: a larger misfit is the model failing to reproduce the record (another load, another mechanism, a
   chaotic history), and a parameter fitted to it would absorb that failure;
2. **the profile has a clear minimum**: the accepted set ``A = {x : m(x) <= MISFIT_NOISE_MULTIPLE sigma}``
   (of the values evaluated) is bracketed on both sides within the range by values outside it (the minimum
   is not at a bound, and the range does not cut the set), and on each side the profile rises to at least
   ``PROFILE_RISE x m*`` (its sum of squares four times the minimum's: far beyond the noise's relative
   scatter of the sum, sqrt(2/n)).

The interval reported is ``[low, high]``: the nearest evaluated values outside ``A`` below and above it, so
it holds every evaluated value the record cannot reject at the multiple (a consistency set, not a
Gauss-Newton interval: a contact parameter's response is not smooth at small scales, an impact's timing
jumps with it, and ``s^2 (J^T J)^-1`` from a local slope then claims a precision the record does not have:
issue #35's column calibrated to 0.354 +- 0.0009 at 20 x the noise). The truth's own misfit is the noise,
so it belongs to ``A`` and lies in the interval whenever the model is right. Otherwise ``identifiable`` is
false, the value and its interval are None and ``line`` says why in one line: "not identifiable: misfit X
mm RMS vs noise Y mm; <reason>".

**A chaotic structure** (a column of circular drums, which wobbles: the engine's own statement, see
:mod:`blastscale.analysis.ensemble`) is fitted on the frames up to each marker's measured first peak only:
after it a change of 1e-10 in the load moves the history by tens of % of the peak whatever the parameter,
so the misfit over the whole record measures the chaos (issue #35's failure: the profile of an engine-made
11-drum shot, friction 0.7, is 86-325 mm RMS everywhere but at 0.7 exactly, 0.1 mm; a search lands on a
spike-free dip and the local slope gives a tiny interval).

The up-scaled prediction is then redone, when a value is reported: the Study of the prototype with it
(restitution: planar; friction: 3D).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import least_squares, minimize_scalar

from .._validate import BlastscaleInputError, check_choice
from ..analysis.intervals import Z95
from ..analysis.upscale import upscale
from ..rocking.system import housner_restitution
from ..study.study import Study
from .outcome import pose_marker_history
from .refit import OUTCOMES, marker_history, simulate_specimen
from .tracks import history_first_peak, track_first_peak, track_noise

__all__ = [
    "CALIBRATIONS",
    "FRICTION_BOUNDS",
    "MISFIT_NOISE_MULTIPLE",
    "PROFILE_EDGE_STEPS",
    "PROFILE_GRID",
    "PROFILE_RISE",
    "RESTITUTION_BOUNDS",
    "calibrate_friction",
    "calibrate_restitution",
    "check_applies",
    "check_calibrate",
    "identify",
]

#: What ``--calibrate`` accepts.
CALIBRATIONS = ("restitution", "friction")
#: A value is reported only when the RMS misfit is at most this multiple of the tracks' noise (module docstring).
MISFIT_NOISE_MULTIPLE = 2.0
#: ... and the profile rises to at least this multiple of its minimum RMS on both sides within the range.
PROFILE_RISE = 2.0
#: Evenly spaced values of the parameter over its range evaluated first (the range's ends included).
PROFILE_GRID = 9
#: Bisections of each edge of the accepted set (the interval's resolution: the grid step / 2^steps).
PROFILE_EDGE_STEPS = 3
#: Search interval of the friction coefficient [-], the search's tolerance and its most evaluations (Brent).
FRICTION_BOUNDS = (0.2, 1.0)
FRICTION_XATOL = 0.002
FRICTION_EVALUATIONS = 10
#: Search interval of the restitution [-] and of the factor on the charge as fired (nuisance) [-].
RESTITUTION_BOUNDS = (0.3, 1.0)
CHARGE_FACTOR_BOUNDS = (0.5, 2.0)
RESTITUTION_XATOL = 0.0005


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


def _rms(r: np.ndarray) -> float:
    return math.sqrt(float(np.mean(r**2))) if r.size else math.inf


def _chaotic(design) -> bool:
    """Whether the specimen wobbles chaotically: a column of circular drums (module docstring)."""
    return getattr(design.specimen_structure, "section", None) == "circular"


def _fit_window(tracks: dict, chaotic: bool, response_s: dict | None) -> dict:
    """The frames fitted: every one (the residuals keep those after the firing signal), or for a chaotic
    structure those up to each marker's measured first peak (:func:`~.tracks.track_first_peak`, over the
    marker's expected time to its first peak ``response_s[name]`` [s]; the whole track when it has none: it
    never leaves the noise)."""
    if not chaotic:
        return tracks
    if response_s is None or set(response_s) < set(tracks):
        raise BlastscaleInputError(
            "calibrate_friction on a chaotic structure fits each marker up to its first peak: give response_s, "
            "each marker's expected time to its first peak [s]"
        )
    out = {}
    for name, (point, t, ux) in tracks.items():
        pk = track_first_peak(t, ux, response_s[name]).first_peak_time_s
        keep = slice(None) if pk is None else t <= pk
        out[name] = (point, t[keep], ux[keep])
    return out


def _noise(tracks: dict) -> float:
    """The tracks' noise [m]: each marker's (:func:`~.tracks.track_noise`, over its whole track), pooled over
    the frames, ``sqrt(sum n_i sigma_i^2 / sum n_i)``."""
    n = np.array([np.size(ux) for _, _, ux in tracks.values()], dtype=float)
    s = np.array([track_noise(ux) for _, _, ux in tracks.values()])
    return math.sqrt(float(np.sum(n * s**2) / np.sum(n)))


def _profile(misfit, bounds, xatol: float, maxiter: int, threshold: float) -> dict:
    """The profile ``{x: m(x)}`` of the RMS misfit ``misfit`` over ``bounds`` (module docstring): the grid, Brent's
    search between the best grid value's neighbours, the edges of ``{x : m(x) <= threshold}`` bisected."""
    pts: dict = {}

    def ev(x) -> float:
        x = float(x)
        if x not in pts:
            pts[x] = float(misfit(x))
        return pts[x]

    grid = np.linspace(float(bounds[0]), float(bounds[1]), PROFILE_GRID)
    i = int(np.argmin([ev(x) for x in grid]))
    a, b = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
    minimize_scalar(ev, bounds=(a, b), method="bounded", options={"xatol": xatol, "maxiter": maxiter})
    for _ in range(PROFILE_EDGE_STEPS):
        xs = sorted(pts)
        ok = [x for x in xs if pts[x] <= threshold]
        if not ok:
            break
        below, above = [x for x in xs if x < ok[0]], [x for x in xs if x > ok[-1]]
        if below:
            ev(0.5 * (below[-1] + ok[0]))
        if above:
            ev(0.5 * (ok[-1] + above[0]))
    return pts


def identify(profile: dict, noise_m: float, bounds, name: str) -> dict:
    """The identifiability rule on an evaluated profile (module docstring).

    Parameters
    ----------
    profile : dict of float -> float
        Parameter value [-] -> RMS misfit [m] of the values evaluated.
    noise_m : float
        The tracks' noise sigma [m].
    bounds : (float, float)
        The searched range of the parameter [-].
    name : str
        The parameter's name (for the line).

    Returns
    -------
    dict
        ``identifiable`` (bool), ``value``, ``low``, ``high`` (None unless identifiable), ``best`` (the value of
        least misfit, always), ``misfit_rms_m`` (its misfit), ``noise_m``, ``line`` (one line: the value and
        its interval, or "not identifiable: misfit X mm RMS vs noise Y mm; <reason>").

    Examples
    --------
    A misfit of sqrt(sigma^2 + (x - 0.5)^2) (the noise plus a model error growing away from the truth 0.5):

    >>> prof = {x: (1e-4 + (x - 0.5) ** 2) ** 0.5 for x in (0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8)}
    >>> r = identify(prof, 1e-2, (0.2, 0.8), "friction")
    >>> r["identifiable"], r["value"], r["low"], r["high"]
    (True, 0.5, 0.4, 0.6)
    >>> identify({x: 0.02 for x in prof}, 1e-2, (0.2, 0.8), "friction")["line"]
    'not identifiable: misfit 20 mm RMS vs noise 10 mm; the profile is flat: the misfit stays within 2 x the noise over the whole range [0.2, 0.8] (friction does not enter the response)'
    """
    xs = np.array(sorted(profile), dtype=float)
    m = np.array([profile[x] for x in xs], dtype=float)
    k = int(np.argmin(m))
    best, least = float(xs[k]), float(m[k])
    thr = MISFIT_NOISE_MULTIPLE * noise_m
    lo, hi = float(bounds[0]), float(bounds[1])
    out = {"identifiable": False, "value": None, "low": None, "high": None, "best": best}
    out |= {"misfit_rms_m": least, "noise_m": float(noise_m)}
    ok = np.flatnonzero(m <= thr)
    below, above = (xs < xs[ok[0]], xs > xs[ok[-1]]) if ok.size else (xs < best, xs > best)
    rise = [float(np.max(m[s])) / least if np.any(s) and least > 0 else math.inf for s in (below, above)]
    if least > thr:
        why = (
            f"above {MISFIT_NOISE_MULTIPLE:g} x the noise: the model does not reproduce the record at any {name} "
            f"in [{lo:g}, {hi:g}] (best {best:.3g})"
        )
    elif not np.any(below) and not np.any(above):
        why = (
            f"the profile is flat: the misfit stays within {MISFIT_NOISE_MULTIPLE:g} x the noise over the whole "
            f"range [{lo:g}, {hi:g}] ({name} does not enter the response)"
        )
    elif not np.any(below) or not np.any(above):
        end = lo if not np.any(below) else hi
        why = (
            f"no clear minimum: the misfit stays within {MISFIT_NOISE_MULTIPLE:g} x the noise up to the bound "
            f"{name} = {end:g} (the range, not the record, bounds it)"
        )
    elif min(rise) < PROFILE_RISE:
        side = "below" if rise[0] < rise[1] else "above"
        why = (
            f"no clear minimum: the misfit rises only to {min(rise):.3g} x its least {side} {name} = {best:.3g} "
            f"(at least {PROFILE_RISE:g} x needed)"
        )
    else:
        low, high = float(xs[below][-1]), float(xs[above][0])
        out |= {"identifiable": True, "value": best, "low": low, "high": high}
        out["line"] = (
            f"{name} {best:.4g} ({low:.4g}-{high:.4g}), misfit {1e3 * least:.2g} mm RMS vs noise {1e3 * noise_m:.2g} mm"
        )
        return out
    out["line"] = f"not identifiable: misfit {1e3 * least:.2g} mm RMS vs noise {1e3 * noise_m:.2g} mm; {why}"
    return out


def _keys(name: str, res: dict, profile: dict) -> dict:
    """The result's keys for parameter ``name`` (docs/fired.md)."""
    return {
        name: res["value"],
        f"{name}_low": res["low"],
        f"{name}_high": res["high"],
        f"best_{name}": res["best"],
        "identifiable": res["identifiable"],
        "line": res["line"],
        "misfit_rms_m": res["misfit_rms_m"],
        "noise_m": res["noise_m"],
        "misfit_noise_multiple": MISFIT_NOISE_MULTIPLE,
        "profile": [[x, profile[x]] for x in sorted(profile)],
    }


def calibrate_restitution(
    scenario, design, tracks: dict, charge_kg: float, standoff_m: float, bounds=RESTITUTION_BOUNDS
) -> dict:
    """The restitution [-] that best matches the measured rocking, when the record identifies it (module
    docstring).

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
        ``restitution`` with ``restitution_low`` / ``restitution_high`` (None when not identifiable),
        ``best_restitution``, ``identifiable``, ``line``, ``misfit_rms_m``, ``noise_m``,
        ``misfit_noise_multiple``, ``profile`` ([e, RMS misfit [m]] pairs, the charge factor re-optimised at
        each), ``charge_factor`` (on ``charge_kg``, at the best e) and its Gauss-Newton ``charge_factor_ci95``
        (half-width), ``samples``, ``prototype_first_peak_rad``, ``prototype_max_rotation_rad``,
        ``prototype_outcome`` (the Study redone with e; None when not identifiable).
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
    cb = CHARGE_FACTOR_BOUNDS
    opt = least_squares(
        residuals, x0, bounds=([cb[0], bounds[0]], [cb[1], bounds[1]]), diff_step=1e-4, x_scale=[0.1, 0.1]
    )
    n = opt.fun.size
    s2 = float(np.sum(opt.fun**2)) / max(n - 2, 1)
    try:
        cov = np.linalg.inv(opt.jac.T @ opt.jac) * s2
        sig = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    except np.linalg.LinAlgError:
        sig = np.full(2, math.inf)

    def misfit(e: float) -> float:  # the profile: the charge factor re-optimised at e
        o = least_squares(lambda c: residuals([c[0], e]), [opt.x[0]], bounds=cb, diff_step=1e-4, x_scale=[0.1])
        return _rms(o.fun)

    sigma = _noise(tracks)
    profile = _profile(misfit, bounds, RESTITUTION_XATOL, 20, MISFIT_NOISE_MULTIPLE * sigma)
    profile[float(opt.x[1])] = min(profile.get(float(opt.x[1]), math.inf), _rms(opt.fun))
    res = identify(profile, sigma, bounds, "restitution")
    out = _keys("restitution", res, profile)
    out |= {"charge_factor": float(opt.x[0]), "charge_factor_ci95": Z95 * float(sig[0]), "samples": n}
    out |= {"prototype_first_peak_rad": None, "prototype_max_rotation_rad": None, "prototype_outcome": None}
    if res["identifiable"]:
        proto = (
            Study.from_design(scenario, design, system="prototype", engine="planar", restitution=res["value"])
            .run()
            .planar.prototype
        )
        out["prototype_first_peak_rad"] = float(proto.peak_angles[0]) if proto.peak_angles.size else None
        out["prototype_max_rotation_rad"] = float(proto.max_rotation)
        out["prototype_outcome"] = OUTCOMES[bool(proto.collapsed)]
    return out


def calibrate_friction(
    scenario,
    design,
    tracks: dict,
    charge_kg: float,
    standoff_m: float,
    bounds=FRICTION_BOUNDS,
    *,
    response_s: dict | None = None,
) -> dict:
    """The friction coefficient [-] that best matches the measured response, when the record identifies it
    (module docstring).

    Parameters as :func:`calibrate_restitution` (``scenario`` of any kind but a block); ``response_s``: marker
    name -> its expected time to the first peak [s] (the prediction's), which sets the first-peak search of a
    chaotic structure's fit window (required there; unused otherwise).

    Returns
    -------
    dict
        ``friction`` with ``friction_low`` / ``friction_high`` (None when not identifiable), ``best_friction``,
        ``identifiable``, ``line``, ``misfit_rms_m``, ``noise_m``, ``misfit_noise_multiple``, ``profile``
        ([mu, RMS misfit [m]] pairs), ``window`` ("record", or "first peak" for a chaotic structure),
        ``samples`` (frames fitted), ``evaluations`` (3D runs of the specimen), ``prototype_first_peak_m``
        (marker name -> the prototype's first peak at the marker's up-scaled point [m], None when it has none)
        and ``prototype_outcome`` (the prototype redone with mu; {} and None when not identifiable).
    """
    check_applies(("friction",), design, "block")
    if not tracks:
        raise BlastscaleInputError("calibrate needs marker tracks: [fired] tracks is not given")
    chaotic = _chaotic(design)
    fitted = _fit_window(tracks, chaotic, response_s)
    samples: dict = {}

    def misfit(mu: float) -> float:
        r = _residuals(simulate_specimen(scenario, design, charge_kg, standoff_m, "3d", friction=mu), fitted)
        samples[mu] = r.size
        return _rms(r)

    sigma = _noise(tracks)
    profile = _profile(misfit, bounds, FRICTION_XATOL, FRICTION_EVALUATIONS, MISFIT_NOISE_MULTIPLE * sigma)
    res = identify(profile, sigma, bounds, "friction")
    out = _keys("friction", res, profile)
    out |= {"window": "first peak" if chaotic else "record", "samples": int(samples[res["best"]])}
    out |= {"evaluations": len(profile), "prototype_first_peak_m": {}, "prototype_outcome": None}
    if not res["identifiable"]:
        return out
    proto, st = _prototype_3d(scenario, design, res["value"])
    t = np.asarray(proto.dataset["time"].values)
    for name, (point, _, _) in tracks.items():
        ux, _ = pose_marker_history(
            proto.dataset, st, upscale(np.asarray(point, dtype=float), design.factors, "length")
        )
        largest = float(np.max(np.abs(ux)))
        out["prototype_first_peak_m"][name] = (
            history_first_peak(t, ux, noise=1e-3 * largest).first_peak_m if largest > 0 else None
        )
    out["prototype_outcome"] = OUTCOMES[bool(proto.dataset.attrs["collapsed"])]
    return out


def _prototype_3d(scenario, design, friction: float):
    """The design's prototype alone on the 3D engine with the friction coefficient ``friction`` [-], through the
    Study's entry from a design (:meth:`~blastscale.study.Study.from_design`): (its Response3D, its structure)."""
    r = Study.from_design(scenario, design, system="prototype", engine="3d", friction=friction).run()
    return r.response3d.prototype, r.structure
