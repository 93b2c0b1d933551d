"""Ensembles of prototype and model runs: similarity of chaotic structures (wobbling columns).

A circular multi-drum column wobbles and its motion is chaotic: a change of 1e-10 in the load
moves its 8 s history by 20-57 % of the peak (docs/columns.md). One prototype trajectory and
one model trajectory then differ after the first impact whatever the scaling law, and their
difference measures the chaos, not the similarity. :func:`ensemble_compare` runs ``n`` members
of each system with the load multiplied by ``1 + perturbation * u_k`` (``u_k`` evenly spread
over [-1, 1]) and compares the ensembles:

* the first peak of each monitoring point (x displacement): mean and spread (max - min) over
  the members, prototype and up-scaled model (a collapsed member's up to its collapse);
* the envelope (min, max over the members at each prototype time) of each point's x
  displacement, and how much of the prototype's envelope the model's covers;
* the medians and 5-95 % bands over the members (:data:`QUANTILES`, ``numpy.percentile`` with linear
  interpolation between the order statistics) of each point's first peak and largest |x displacement|,
  and of each body's residual displacement and rotation (the damage; the model's up-scaled);
* the collapse probability (fraction of members that collapse), each body's fall probability, both with
  their Wilson interval (:func:`~.intervals.wilson_interval`, 95 % unless ``confidence`` says: honest for
  an ensemble of a few members), and the collapse times;
* the noise floor: the largest spread of the prototype ensemble over time relative to the
  peak, and the *predictability horizon*: the first time the prototype ensemble's spread at
  the top point exceeds ``horizon_fraction`` of its peak (trajectory comparison is
  meaningful before it, not after).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._threads import map_threads
from .._validate import BlastscaleInputError, check_range
from ..sim3d.results import MOTION_VARIABLES
from .compare import _first_peak, align, upscale_dataset
from .intervals import wilson_interval
from .systems import Settings3D, Systems3D, run_system
from .upscale import upscale_summary

__all__ = ["EnsembleComparison", "ensemble_compare", "ensemble_statistics", "member_factors", "QUANTILES"]

#: The ensembles' quantiles: (name, percentile [%]), by ``numpy.percentile`` with linear interpolation
#: (``method="linear"``: between the order statistics, Hyndman & Fan 1996's definition 7).
QUANTILES = (("p05", 5.0), ("median", 50.0), ("p95", 95.0))


def _quantiles(x, axis: int = 0) -> dict:
    """``{"p05", "median", "p95"}`` of ``x`` along ``axis`` (:data:`QUANTILES`)."""
    q = np.percentile(np.asarray(x, dtype=float), [p for _, p in QUANTILES], axis=axis, method="linear")
    return {name: q[i] for i, (name, _) in enumerate(QUANTILES)}


def _body_statistics(bodies) -> dict:
    """Per body of ``bodies`` (one dict per member: name -> ``residual_displacement_m`` [m],
    ``residual_rotation_rad`` [rad], ``fallen``): the quantiles of the residuals and the count of falls."""
    out = {}
    for name in bodies[0]:
        res = [b[name]["residual_displacement_m"] for b in bodies]
        rot = [b[name]["residual_rotation_rad"] for b in bodies]
        out[name] = {
            **{f"residual_displacement_{k}": float(v) for k, v in _quantiles(res).items()},
            **{f"residual_rotation_{k}": float(v) for k, v in _quantiles(rot).items()},
            "fall_count": int(sum(bool(b[name]["fallen"]) for b in bodies)),
        }
    return out


def ensemble_statistics(
    time,
    members,
    collapsed,
    horizon_fraction: float = 0.05,
    peak_fraction: float = 0.1,
    collapse_times=None,
    bodies=None,
) -> dict:
    """Statistics of an ensemble of histories of one quantity at several points.

    Parameters
    ----------
    time : array (n,)
        Common times [s].
    members : array (k, n, p)
        k members, n times, p points [unit].
    collapsed : array (k,) of bool
        Outcome of each member.
    horizon_fraction : float
        Spread / peak above which the members are considered to have diverged [-].
    peak_fraction : float
        See :func:`~.compare.first_peak`.
    collapse_times : array (k,), optional
        Collapse time of each member [s] (nan or None: it stands); a collapsed member's first
        peak is taken up to its collapse (after it the drums fall, and the engine's contacts,
        ground-base and adjacent drums only, no longer describe the motion).
    bodies : list of dict, optional
        Per member, its bodies (name -> ``residual_displacement_m`` [m], ``residual_rotation_rad`` [rad],
        ``fallen``: a 3D run's ``bodies`` summary, :meth:`~blastscale.sim3d.results.SimulationResult.bodies_summary`).

    Returns
    -------
    dict
        ``first_peak_mean``, ``first_peak_spread`` (max - min over members), ``first_peak_std``
        (p,) [unit]; ``first_peak_median``, ``first_peak_p05``, ``first_peak_p95`` and
        ``max_displacement_median``, ``max_displacement_p05``, ``max_displacement_p95`` (p,) [unit]: the
        quantiles (:data:`QUANTILES`) over the members of the first peak and of the largest |q| of each
        member's whole history; ``envelope_min``, ``envelope_max`` (n, p); ``peak`` (p,) (largest |q| of
        all members); ``spread`` (n, p) (max - min over members); ``max_spread_rel_peak`` (p,);
        ``horizon_s`` (p,) first time spread > ``horizon_fraction`` x peak (nan: never);
        ``collapse_probability``, ``collapse_count`` and ``members`` (k); ``collapse_time_mean``,
        ``collapse_time_spread`` [s] over the collapsed members (nan when none); ``bodies`` (with ``bodies``;
        else None): per body ``residual_displacement_{p05,median,p95}`` [m],
        ``residual_rotation_{p05,median,p95}`` [rad] and ``fall_count`` (members in which it fell);
        ``member_collapsed`` (k,) and ``member_bodies`` (``bodies`` as given, None without): each member's
        outcome and bodies, for its damage state (:func:`blastscale.analysis.damage.damage_state`).
    """

    q = np.asarray(members, dtype=float)
    if q.ndim != 3:
        raise BlastscaleInputError(f"members shape = {q.shape} is not (members, times, points)")
    frac = float(check_range("horizon_fraction", horizon_fraction, 0.0, 1.0))
    peak_fraction = float(check_range("peak_fraction", peak_fraction, 0.0, 1.0))
    t = np.asarray(time, dtype=float)
    tc = (
        np.full(q.shape[0], np.nan)
        if collapse_times is None
        else np.array([np.nan if x is None else float(x) for x in collapse_times])
    )
    upto = [t <= tc[k] if np.isfinite(tc[k]) else np.ones(t.size, dtype=bool) for k in range(q.shape[0])]
    fp = np.array(
        [
            [_first_peak(t[upto[k]], q[k, upto[k], j], peak_fraction)[1] for j in range(q.shape[2])]
            for k in range(q.shape[0])
        ]
    )
    spread = q.max(axis=0) - q.min(axis=0)
    peak = np.max(np.abs(q), axis=(0, 1))
    if bodies is not None and len(bodies) != q.shape[0]:
        raise BlastscaleInputError(f"bodies has {len(bodies)} members, members has {q.shape[0]}: one per member")
    safe = np.where(peak > 0, peak, np.inf)
    horizon = np.full(q.shape[2], math.nan)
    for j in range(q.shape[2]):
        idx = np.flatnonzero(spread[:, j] > frac * peak[j])
        if idx.size and peak[j] > 0:
            horizon[j] = t[idx[0]]
    col = np.asarray(collapsed, dtype=bool)
    return {
        "first_peak_mean": fp.mean(axis=0),
        "first_peak_spread": fp.max(axis=0) - fp.min(axis=0),
        "first_peak_std": fp.std(axis=0),
        **{f"first_peak_{k}": v for k, v in _quantiles(fp).items()},
        **{f"max_displacement_{k}": v for k, v in _quantiles(np.max(np.abs(q), axis=1)).items()},
        "envelope_min": q.min(axis=0),
        "envelope_max": q.max(axis=0),
        "peak": peak,
        "spread": spread,
        "max_spread_rel_peak": spread.max(axis=0) / safe,
        "horizon_s": horizon,
        "collapse_probability": float(np.mean(col)),
        "collapse_count": int(col.sum()),
        "members": int(q.shape[0]),
        "collapse_time_mean": float(np.nanmean(tc)) if np.any(np.isfinite(tc)) else math.nan,
        "collapse_time_spread": float(np.nanmax(tc) - np.nanmin(tc)) if np.any(np.isfinite(tc)) else math.nan,
        "bodies": None if bodies is None else _body_statistics(bodies),
        "member_collapsed": col.tolist(),
        "member_bodies": None if bodies is None else list(bodies),
    }


@dataclass(frozen=True, eq=False)
class EnsembleComparison:
    """Result of :func:`ensemble_compare` (prototype units).

    Attributes
    ----------
    time : ndarray (n,)
        Common prototype times [s] after the first arrival.
    points : tuple of str
        Monitoring points (x displacement compared).
    prototype, model : dict
        :func:`ensemble_statistics` of the prototype members and of the up-scaled model members
        (``model`` None for a prototype-only ensemble).
    factors : tuple of float
        The load multipliers of the members [-].
    prototype_members, model_members : ndarray (k, n, p)
        The members' x displacements [m] (model up-scaled, on the prototype's times; None
        without a model).
    settings : dict
        Inputs (perturbation, n, load method, duration; ``confidence``, the intervals' level, when given).
    top_point : str
        The point reported as the top: the highest at rest (the recorder's), else the last.
    motion : xarray.Dataset or None
        The stored motion (:data:`blastscale.sim3d.results.MOTION_VARIABLES`, each system's, the model's
        up-scaled) of two members along ``case``: ``median`` (the member whose largest |x displacement| of any
        point is closest to the members' median of it, prototype) and ``worst`` (the largest); coordinate
        ``case_member`` gives which (:func:`motion_cases`).
    """

    time: np.ndarray
    points: tuple
    prototype: dict
    model: dict
    factors: tuple
    prototype_members: np.ndarray
    model_members: np.ndarray
    settings: dict = field(default_factory=dict)
    top_point: str = ""

    def __post_init__(self):
        if not self.top_point:
            object.__setattr__(self, "top_point", str(self.points[-1]))

    motion: object = None

    def to_dict(self) -> dict:
        """Per point (``points``): first-peak mean and spread of each system [m], their ratio, envelope
        coverage, the prototype's noise floor and horizon, and the median and 5-95 % band of each system's
        first peak and largest |x displacement| (``first_peak_{prototype,model}_{median,p05,p95}_m``,
        ``max_displacement_{prototype,model}_{median,p05,p95}_m``); per body (``bodies``, when the members
        kept their bodies): the median and band of the residual displacement [m] and rotation [rad] and the
        fall probability with its interval (``fall_probability_{prototype,model}`` and ``_low``, ``_high``);
        the collapse probabilities with theirs (``collapse_probability_{prototype,model}_low``, ``_high``).
        Quantiles: :data:`QUANTILES`; intervals: Wilson's at ``settings["confidence"]`` (95 % when absent).
        Without a model (a prototype-only ensemble) the model's figures are None."""
        p, m = self.prototype, self.model
        pts = {}
        for j, name in enumerate(self.points):
            pts[name] = {
                "first_peak_prototype_mean_m": float(p["first_peak_mean"][j]),
                "first_peak_prototype_spread_m": float(p["first_peak_spread"][j]),
                **_point_quantiles(p, "prototype", j),
                "first_peak_model_mean_m": None,
                "first_peak_model_spread_m": None,
                **_point_quantiles(m, "model", j),
                "first_peak_ratio": None,
                "peak_prototype_m": float(p["peak"][j]),
                "peak_model_m": None,
                "noise_floor_rel_peak": float(p["max_spread_rel_peak"][j]),
                "model_noise_floor_rel_peak": None,
                "envelope_mismatch_rel_peak": None,
                "horizon_prototype_s": float(p["horizon_s"][j]),
                "horizon_model_s": None,
            }
            if m is None:
                continue
            lo, hi = p["envelope_min"][:, j], p["envelope_max"][:, j]
            mlo, mhi = m["envelope_min"][:, j], m["envelope_max"][:, j]
            # difference of the envelopes relative to the prototype's peak: how far the model's band
            # lies outside the prototype's band (0 when inside)
            outside = np.maximum(np.maximum(mhi - hi, 0.0), np.maximum(lo - mlo, 0.0))
            pts[name].update(
                {
                    "first_peak_model_mean_m": float(m["first_peak_mean"][j]),
                    "first_peak_model_spread_m": float(m["first_peak_spread"][j]),
                    "first_peak_ratio": float(m["first_peak_mean"][j] / p["first_peak_mean"][j])
                    if p["first_peak_mean"][j] != 0
                    else math.nan,
                    "peak_model_m": float(m["peak"][j]),
                    "model_noise_floor_rel_peak": float(m["max_spread_rel_peak"][j]),
                    "envelope_mismatch_rel_peak": float(np.max(outside) / p["peak"][j])
                    if p["peak"][j] > 0
                    else math.nan,
                    "horizon_model_s": float(m["horizon_s"][j]),
                }
            )
        lo_p, hi_p = self._interval(p["collapse_count"], p["members"])
        lo_m, hi_m = (None, None) if m is None else self._interval(m["collapse_count"], m["members"])
        return {
            "n_members": len(self.factors),
            "perturbation": self.settings.get("perturbation"),
            "collapse_probability_prototype": p["collapse_probability"],
            "collapse_probability_prototype_low": lo_p,
            "collapse_probability_prototype_high": hi_p,
            "collapse_probability_model": None if m is None else m["collapse_probability"],
            "collapse_probability_model_low": lo_m,
            "collapse_probability_model_high": hi_m,
            "collapse_time_prototype_mean_s": p["collapse_time_mean"],
            "collapse_time_prototype_spread_s": p["collapse_time_spread"],
            "collapse_time_model_mean_s": None if m is None else m["collapse_time_mean"],
            "collapse_time_model_spread_s": None if m is None else m["collapse_time_spread"],
            "points": pts,
            "bodies": self._bodies(),
        }

    def _interval(self, k: int, n: int) -> tuple:
        """Wilson's interval of ``k`` of ``n`` at ``settings["confidence"]`` (its default when absent)."""
        c = self.settings.get("confidence")
        return wilson_interval(k, n) if c is None else wilson_interval(k, n, c)

    def _bodies(self) -> dict | None:
        """The ``bodies`` block of :meth:`to_dict` (None when the members kept no bodies)."""
        p, m = self.prototype, self.model
        if p.get("bodies") is None:
            return None
        out = {}
        for name, b in p["bodies"].items():
            mb = None if m is None or m.get("bodies") is None else m["bodies"].get(name)
            out[name] = {}
            for system, s, n in (("prototype", b, p["members"]), ("model", mb, None if m is None else m["members"])):
                out[name].update(
                    {
                        f"residual_{q}_{system}_{k}_{u}": None if s is None else s[f"residual_{q}_{k}"]
                        for q, u in (("displacement", "m"), ("rotation", "rad"))
                        for k, _ in QUANTILES
                    }
                )
                lo, hi = (None, None) if s is None else self._interval(s["fall_count"], n)
                out[name].update(
                    {
                        f"fall_probability_{system}": None if s is None else s["fall_count"] / n,
                        f"fall_probability_{system}_low": lo,
                        f"fall_probability_{system}_high": hi,
                    }
                )
        return out


def _point_quantiles(stats: dict | None, system: str, j: int) -> dict:
    """The median and 5-95 % band of point ``j``'s first peak and largest |x displacement| [m] of one system's
    :func:`ensemble_statistics` (None without it)."""
    return {
        f"{q}_{system}_{k}_m": None if stats is None else float(stats[f"{q}_{k}"][j])
        for q in ("first_peak", "max_displacement")
        for k, _ in QUANTILES
    }


def member_factors(n: int, perturbation: float) -> tuple:
    """The load factors of ``n`` ensemble members: ``1 + perturbation * u_k``, u_k evenly spread over [-1, 1]
    (one member: the load itself) [-]."""
    if int(n) == 1:
        return (1.0,)
    return tuple(1.0 + perturbation * u for u in np.linspace(-1.0, 1.0, int(n)))


def ensemble_compare(
    systems: Systems3D,
    settings: Settings3D = Settings3D(),
    *,
    n: int = 8,
    perturbation: float = 1e-6,
    horizon_fraction: float = 0.05,
    progress=None,
    threads: int | None = None,
    confidence: float | None = None,
) -> EnsembleComparison:
    """Ensembles of a structure and of its reduced-scale model under slightly perturbed loads.

    Parameters
    ----------
    systems : Systems3D
        The prototype and the specimen of a design (:meth:`~.systems.Systems3D.of_design`), or the prototype
        alone (``Systems3D(System3D(structure, blast, ...))``: a prototype-only study).
    settings : Settings3D
        As :func:`~.structure3d.compare_structure3d`.
    n : int
        Members per system, >= 2.
    perturbation : float
        Largest relative change of the load [-], in (0, 0.1]; member k multiplies every
        wrench by ``1 + perturbation * u_k``, u evenly spread over [-1, 1].
    horizon_fraction : float
        See :func:`ensemble_statistics`.
    progress : callable, optional
        Called as ``progress(k, n)`` after each member (pair).
    threads : int, optional
        Runs in flight at once (:mod:`blastscale._threads`; default: the cores this process may
        use, divided by the local Dask workers). The members' histories do not depend on it (bitwise).
    confidence : float, optional
        Level of the collapse and fall probabilities' intervals [-], in (0, 1) (the study's
        ``verdict.confidence``; None: :func:`~.intervals.wilson_interval`'s default, 95 %).

    Returns
    -------
    EnsembleComparison
        Without a specimen, ``model`` and ``model_members`` are None.
    """

    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 2:
        raise BlastscaleInputError(f"n = {n!r} is out of range: must be a whole number >= 2")
    eps = float(check_range("perturbation", perturbation, 0.0, 0.1))
    if eps == 0.0:
        raise BlastscaleInputError("perturbation = 0 is out of range: must be in (0, 0.1]")
    level = {} if confidence is None else {"confidence": confidence}
    if confidence is not None:  # checked before the runs
        check_range("confidence", confidence, 0.0, 1.0, lo_open=True, hi_open=True)
    factors = member_factors(n, eps)
    runs = systems.runs()
    names = tuple(name for name, _ in runs)
    tasks = [(f, system) for f in factors for _, system in runs]  # (load factor, system) of each member run

    def tick(done):
        if progress is not None and done % len(runs) == 0:
            progress(done // len(runs), len(factors))

    responses = map_threads(lambda task: run_system(task[1], settings, task[0]).response, tasks, threads, done=tick)
    members = _Members(names)
    for k in range(len(factors)):
        members.add({s: responses[k * len(names) + i] for i, s in enumerate(names)}, systems.design)
    q = {s: np.stack(v) for s, v in members.q.items()}
    stats = {
        s: ensemble_statistics(
            members.t,
            q[s],
            members.collapsed[s],
            horizon_fraction,
            collapse_times=members.times[s],
            bodies=members.bodies[s],
        )
        for s in names
    }
    return EnsembleComparison(
        time=members.t,
        points=members.points,
        prototype=stats["prototype"],
        model=stats.get("model"),
        factors=factors,
        prototype_members=q["prototype"],
        model_members=q.get("model"),
        settings={
            "perturbation": eps,
            "n": int(n),
            "load_method": settings.load,
            "pulse_shape": settings.pulse_shape,
            "duration_s": float(systems.prototype.duration),
            **level,
        },
        top_point=members.top,
        motion=_cases_motion(members.poses, q["prototype"], members.t.size),
    )


class _Members:
    """The members' histories gathered on the prototype's common times (the model's up-scaled; a member that
    ended early shortens the common span for all)."""

    def __init__(self, names: tuple):
        self.q: dict = {s: [] for s in names}
        self.collapsed: dict = {s: [] for s in names}
        self.times: dict = {s: [] for s in names}
        self.poses: dict = {s: [] for s in names}
        self.bodies: dict = {s: [] for s in names}
        self.t = self.points = self.top = None

    def add(self, runs: dict, design) -> None:
        """One member's responses by system (``prototype`` and, with ``design``, ``model``)."""
        ds = {"prototype": runs["prototype"].dataset}
        summ = {"prototype": runs["prototype"].summary()}
        if "model" in runs:
            ds["prototype"], ds["model"] = align(
                ds["prototype"], upscale_dataset(runs["model"].dataset, design.factors)
            )
            summ["model"] = upscale_summary(runs["model"].summary(), design.factors)
        if self.t is None:
            self.t = ds["prototype"]["time"].values
            self.points = tuple(str(p) for p in ds["prototype"]["point"].values)
            self.top = str(ds["prototype"].attrs.get("top_point", self.points[-1]))
        elif ds["prototype"].sizes["time"] != self.t.size:  # a member ended early: the shortest common span
            m = min(self.t.size, ds["prototype"].sizes["time"])
            self.t = self.t[:m]
            self.q = {s: [x[:m] for x in v] for s, v in self.q.items()}
            ds = {s: d.isel(time=slice(0, m)) for s, d in ds.items()}
        for s in ds:
            x = ds[s]["point_displacement"].sel(component="x").transpose("time", "point").values
            self.q[s].append(x[: self.t.size])
            self.poses[s].append(ds[s][[v for v in MOTION_VARIABLES if v in ds[s]]])
            self.collapsed[s].append(bool(summ[s]["collapsed"]))
            self.times[s].append(summ[s].get("collapse_time_s"))
            self.bodies[s].append(
                {
                    n: {k: b[k] for k in ("residual_displacement_m", "residual_rotation_rad", "fallen")}
                    for n, b in summ[s]["bodies"].items()
                }
            )


def motion_cases(members) -> dict:
    """The members an ensemble's motion keeps: ``median`` (largest |x displacement| of any point closest to the
    members' median of it) and ``worst`` (the largest), by index, of ``members`` (k, n, p) [m]."""
    peak = np.abs(np.asarray(members, dtype=float)).max(axis=(1, 2))
    return {"median": int(np.argmin(np.abs(peak - np.median(peak)))), "worst": int(np.argmax(peak))}


def _cases_motion(poses: dict, members, nt: int):
    """The stored motion of :func:`motion_cases`' members, systems stacked, along ``case`` (None when the runs
    kept none)."""
    import xarray as xr

    if not all(poses.values()) or "body_position" not in poses["prototype"][0]:
        return None
    cases = motion_cases(members)
    per_case = []
    for k in cases.values():
        parts = [poses[s][k].isel(time=slice(0, nt)) for s in poses]
        per_case.append(
            xr.concat(
                parts,
                dim=xr.DataArray(list(poses), dims="system"),
                coords="minimal",
                compat="override",
                combine_attrs="override",
            )
        )
    out = xr.concat(
        per_case,
        dim=xr.DataArray(list(cases), dims="case"),
        coords="minimal",
        compat="override",
        combine_attrs="override",
    )
    return out.assign_coords(case_member=("case", list(cases.values()), {"units": "1", "long_name": "ensemble member"}))
