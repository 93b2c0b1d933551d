"""The comparison contract: up-scale a model's response and compare it with the prototype's.

Every response (planar rocking, a single block in 3D, a multi-drum column) is an
``xarray.Dataset`` whose data variables carry a ``dimension`` attribute naming their physical
dimension (``"length"``, ``"velocity"``, ``"angle"``, ``"angular_velocity"``, ``"time"``,
``"momentum"``, ``"force"``, ``"mass"``, ``"dimensionless"``, ``"count"``; any other field name
of :class:`~blastscale.similitude.ScalingFactors` works too). A model run becomes a prototype
prediction by dividing each variable by its factor (paper Tables 1-2):

.. math:: q_p^{up}(t_m / \\lambda_t) = q_m(t_m) / \\lambda_q

(:func:`upscale_dataset`, the one up-scaling function of the package), and the two are compared
on the prototype's time grid (:func:`align`, :func:`compare_responses`, the one comparison).

Per compared element (a body or a monitoring point) the comparison reports

* the first peak of each history and their ratio (model / prototype), see :func:`first_peak`;
* ``max_abs_diff`` = max_t |q_p(t) - q_m^{up}(t)| over the common times, and the same relative
  to the prototype's peak max_t |q_p(t)|;
* the peaks max_t |q|;

and, for the whole structure, whether the outcomes (``collapsed``, ``overturned``: a dataset
attribute) agree.

Reference: Masi, Stefanou & Maffi-Berthier, *Scaling laws for rigid-body response of masonry
structures under blast loads*, Tables 1-2 and Sec. 6 (the comparisons of prototype and model).
"""

from __future__ import annotations

import math

import numpy as np

from .._validate import BlastscaleInputError, check_range
from ..sim3d.results import MOTION_VARIABLES
from ..similitude.factors import DIMENSIONLESS, dimension_factor
from .upscale import upscale

__all__ = [
    "DEFAULT_COMPONENTS",
    "align",
    "compare_responses",
    "first_peak",
    "upscale_dataset",
]


#: Component compared for variables that have a ``component`` dimension: the horizontal
#: motion along the blast (x), and the rocking rotation about y for angular velocities.
DEFAULT_COMPONENTS = {"angular_velocity": "y"}

#: A local maximum of |q| counts as the first peak only when it reaches this fraction of the
#: history's largest |q| (contact jitter of micrometres before the main excursion is skipped).
FIRST_PEAK_FRACTION = 0.1


def upscale_dataset(ds, factors):
    """A model response in prototype units, every variable divided by its scaling factor.

    Parameters
    ----------
    ds : xarray.Dataset
        Model response. Each data variable (and each coordinate that is to be scaled) has an
        attribute ``dimension``; the coordinate ``time`` is a time [s] whether or not it has one.
    factors : blastscale.similitude.ScalingFactors
        Model / prototype factors (``design.factors``).

    Returns
    -------
    xarray.Dataset
        A new dataset: values / factor, same names, dims and units; the ``time`` coordinate
        / ``factors.time``; the attribute ``first_arrival_time_s`` (if present) / ``factors.time``;
        attribute ``upscaled`` = 1 and the factors used (``factor_<dimension>``).

    Raises
    ------
    BlastscaleInputError
        A data variable without a ``dimension`` attribute, or with one that has no factor.
    """
    out = ds.copy(deep=True)
    used = {}
    for name, var in list(out.data_vars.items()) + [(c, out.coords[c]) for c in out.coords]:
        dim = var.attrs.get("dimension")
        if dim is None:
            if name == "time":
                dim = "time"
            elif name in out.coords:
                continue  # labels (body, point, component)
            else:
                raise BlastscaleInputError(
                    f"variable {name!r} has no 'dimension' attribute: every data variable needs one "
                    f"({', '.join(DIMENSIONLESS)} or a ScalingFactors field)"
                )
        f = dimension_factor(factors, dim, name)
        used[dim] = f
        if f != 1.0:
            attrs = dict(var.attrs)
            if name in out.coords:
                out = out.assign_coords({name: (var.dims, var.values / f, attrs)})
            else:
                out[name] = (var.dims, var.values / f, attrs)
    if "first_arrival_time_s" in out.attrs:
        out.attrs["first_arrival_time_s"] = upscale(float(out.attrs["first_arrival_time_s"]), factors, "time")
    out.attrs["upscaled"] = 1
    out.attrs.update({f"factor_{k}": v for k, v in sorted(used.items())})
    return out


def align(prototype_ds, upscaled_ds):
    """The up-scaled model interpolated (linearly) onto the prototype's times where they overlap.

    Parameters
    ----------
    prototype_ds, upscaled_ds : xarray.Dataset
        Both in prototype units, each with a ``time`` coordinate [s] increasing.

    Returns
    -------
    (xarray.Dataset, xarray.Dataset)
        The prototype restricted to the common times and the model at exactly those times
        (variables without a ``time`` dimension are kept as they are).
    """
    tp = np.asarray(prototype_ds["time"].values, dtype=float)
    tm = np.asarray(upscaled_ds["time"].values, dtype=float)
    if tp.size == 0 or tm.size == 0:
        raise BlastscaleInputError("time = [] is out of range: both responses need at least one recorded time")
    # relative slack for the round-off of t / lambda_t at the last sample
    keep = (tp >= tm[0] * (1 - 1e-12) - 1e-300) & (tp <= tm[-1] * (1 + 1e-12))
    if not np.any(keep):
        raise BlastscaleInputError(
            f"time = [{tm[0]:.6g}, {tm[-1]:.6g}] s (up-scaled model) does not overlap the prototype's "
            f"[{tp[0]:.6g}, {tp[-1]:.6g}] s"
        )
    proto = prototype_ds.isel(time=np.flatnonzero(keep))
    t = proto["time"].values
    timed = [n for n, v in upscaled_ds.data_vars.items() if "time" in v.dims]
    model = upscaled_ds.drop_dims("time")
    model = model.assign_coords(time=("time", t, dict(prototype_ds["time"].attrs)))
    for name in timed:
        v = upscaled_ds[name]
        arr = np.moveaxis(np.asarray(v.values, dtype=float), v.dims.index("time"), 0)
        flat = arr.reshape(arr.shape[0], -1)
        res = np.empty((t.size, flat.shape[1]))
        for j in range(flat.shape[1]):
            res[:, j] = np.interp(t, tm, flat[:, j])
        res = np.moveaxis(res.reshape((t.size,) + arr.shape[1:]), 0, v.dims.index("time"))
        model[name] = (v.dims, res, dict(v.attrs))
    return proto, model


def first_peak(time, values, fraction: float = FIRST_PEAK_FRACTION) -> tuple[float, float]:
    """The first peak of a sampled history: its time [s] and signed value.

    The first sample k that is a local maximum of |q| (|q_k| >= |q_(k-1)| and |q_k| > |q_(k+1)|,
    plateaus included) with |q_k| >= ``fraction`` max |q|; a history that grows to its end
    (sliding, overturning) has its first peak at the largest |q|. For a clean (simulated) history; a
    measured, noisy marker track's is :func:`blastscale.fired.tracks.track_first_peak`.

    Parameters
    ----------
    time : array (n,)
        Times [s].
    values : array (n,)
        History [any unit].
    fraction : float
        Threshold relative to max |q| [-], in [0, 1].

    Returns
    -------
    (float, float)
        Time [s] and value [unit of ``values``]; (nan, 0.0) for an all-zero history.
    """
    return _first_peak(time, values, float(check_range("fraction", fraction, 0.0, 1.0)))


def _first_peak(time, values, frac: float) -> tuple[float, float]:
    """:func:`first_peak` with a checked ``frac``: the comparisons check it once per call."""
    q = np.asarray(values, dtype=float)
    a = np.abs(q)
    peak = float(np.max(a)) if a.size else 0.0
    if peak == 0.0 or not math.isfinite(peak):
        return math.nan, 0.0
    # runs of equal samples (a plateau is one run); a run is a peak when higher than both neighbours
    start = np.flatnonzero(np.concatenate([[True], a[1:] != a[:-1]]))
    r = a[start]
    prev = np.concatenate([[-np.inf], r[:-1]])
    nxt = np.concatenate([r[1:], [-np.inf]])
    runs = np.flatnonzero((r > prev) & (r > nxt) & (r >= frac * peak))
    cand = start[runs]
    k = int(cand[0]) if cand.size else int(np.argmax(a))
    return float(np.asarray(time)[k]), float(q[k])


def _component(var, name: str, components):
    if "component" not in var.dims:
        return var, None
    comp = components.get(name, DEFAULT_COMPONENTS.get(name, "x")) if isinstance(components, dict) else components
    labels = [str(c) for c in var["component"].values]
    if comp not in labels:
        raise BlastscaleInputError(
            f"component of {name!r} = {comp!r} is not recorded: valid values are {', '.join(labels)}"
        )
    return var.sel(component=comp), comp


def _outcome(ds, key: str):
    v = ds.attrs.get(key)
    return None if v is None or (isinstance(v, str) and v == "none") else bool(v)


def compare_responses(
    prototype_ds,
    upscaled_ds,
    *,
    variables=None,
    components=None,
    outcome: str = "collapsed",
    peak_fraction: float = FIRST_PEAK_FRACTION,
    start: float | None = None,
    end: float | None = None,
) -> dict:
    """Compare a prototype response with an up-scaled model response, per body and per point.

    Parameters
    ----------
    prototype_ds : xarray.Dataset
        Prototype response (SI, prototype units).
    upscaled_ds : xarray.Dataset
        Model response already in prototype units (:func:`upscale_dataset`); it is
        interpolated onto the prototype's times where they overlap (:func:`align`).
    variables : sequence of str, optional
        Data variables to compare (default: every variable with a ``time`` dimension whose
        dimension is not ``count``, but the stored motion: :data:`blastscale.sim3d.results.MOTION_VARIABLES`).
    components : str or dict, optional
        Component compared for variables with a ``component`` dimension: one label for all,
        or variable -> label (default :data:`DEFAULT_COMPONENTS`, else ``"x"``).
    outcome : str
        Boolean dataset attribute that states the outcome (``"collapsed"``, ``"overturned"``).
    peak_fraction : float
        See :func:`first_peak`.
    start : float, optional
        Compare only the prototype times >= ``start`` [s] (e.g. after the load: during a
        finite pulse velocities rise over the blast's own duration, whose model/prototype
        ratio is not the time factor; paper Eq. 8 matches only the impulse).
    end : float, optional
        Compare only the prototype times <= ``end`` [s] (e.g. up to the earlier collapse: a
        fall amplifies any time shift, as a rocking block's after its tipping point).

    Returns
    -------
    dict
        ``variables``: variable -> element (body or point name; the variable's name when it has
        no such dimension) -> metrics: ``component``, ``first_peak_prototype``,
        ``first_peak_model`` [unit of the variable], ``first_peak_time_prototype_s``,
        ``first_peak_time_model_s`` [s], ``first_peak_ratio`` [-] (model / prototype; nan when the
        prototype's is 0), ``peak_prototype``, ``peak_model`` (max |q|), ``max_abs_diff``
        [unit], ``max_abs_diff_rel_peak`` [-] (max_abs_diff / peak_prototype), ``units``.
        ``outcome_prototype``, ``outcome_model`` (bool or None), ``outcomes_agree`` (bool, or
        None when an outcome is not recorded), ``time_compared_s`` ([start, end] of the common
        times), ``n_times`` (samples compared).
    """
    peak_fraction = float(check_range("peak_fraction", peak_fraction, 0.0, 1.0))
    proto, model = _window(*align(prototype_ds, upscaled_ds), start, end)
    t = proto["time"].values
    components = {} if components is None else components
    if variables is None:
        variables = [
            n
            for n, v in proto.data_vars.items()
            if "time" in v.dims
            and v.attrs.get("dimension") != "count"
            and n in model.data_vars
            and n not in MOTION_VARIABLES
        ]
    out_vars = {name: _compare_variable(proto, model, name, components, peak_fraction) for name in variables}
    op, om = _outcome(prototype_ds, outcome), _outcome(upscaled_ds, outcome)
    return {
        "variables": out_vars,
        "outcome_prototype": op,
        "outcome_model": om,
        "outcomes_agree": None if op is None or om is None else op == om,
        "time_compared_s": [float(t[0]), float(t[-1])],
        "n_times": int(t.size),
    }


def _window(proto, model, start: float | None, end: float | None):
    """The aligned responses restricted to the prototype times in [``start``, ``end``] [s] (None: open)."""
    if start is None and end is None:
        return proto, model
    tt = proto["time"].values
    lo = -np.inf if start is None else float(start)
    hi = np.inf if end is None else float(end)
    inside = np.flatnonzero((tt >= lo) & (tt <= hi))
    if inside.size == 0:
        raise BlastscaleInputError(
            f"time window = [{lo:.6g}, {hi:.6g}] s is out of range: the common times are [{tt[0]:.6g}, {tt[-1]:.6g}] s"
        )
    return proto.isel(time=inside), model.isel(time=inside)


def _compare_variable(proto, model, name: str, components: dict, peak_fraction: float) -> dict:
    """One variable's metrics per element (body or point; the variable's name when it has no such dimension),
    of its component (:func:`_component`)."""
    if name not in proto.data_vars or name not in model.data_vars:
        raise BlastscaleInputError(
            f"variable = {name!r} is not in both responses: valid values are "
            f"{', '.join(n for n in proto.data_vars if n in model.data_vars)}"
        )
    vp, comp = _component(proto[name], name, components)
    vm, _ = _component(model[name], name, components)
    others = [d for d in vp.dims if d != "time"]
    if len(others) > 1:
        raise BlastscaleInputError(f"variable = {name!r} has dims {vp.dims}: at most one besides time and component")
    t = proto["time"].values
    labels = [str(x) for x in vp[others[0]].values] if others else [name]
    ap = np.asarray(vp.transpose("time", *others).values, dtype=float).reshape(t.size, -1)
    am = np.asarray(vm.transpose("time", *others).values, dtype=float).reshape(t.size, -1)
    units = proto[name].attrs.get("units", "")
    return {
        label: {"component": comp, **_metrics(t, ap[:, j], am[:, j], peak_fraction), "units": units}
        for j, label in enumerate(labels)
    }


def _metrics(t: np.ndarray, p: np.ndarray, m: np.ndarray, peak_fraction: float) -> dict:
    """First peaks (and their ratio), peaks and the largest difference of a prototype history ``p`` and an
    up-scaled model history ``m`` on the common times ``t`` [s]."""
    tp1, p1 = _first_peak(t, p, peak_fraction)
    tm1, m1 = _first_peak(t, m, peak_fraction)
    peak_p = float(np.max(np.abs(p)))
    diff = float(np.max(np.abs(p - m)))
    return {
        "first_peak_prototype": p1,
        "first_peak_model": m1,
        "first_peak_time_prototype_s": tp1,
        "first_peak_time_model_s": tm1,
        "first_peak_ratio": m1 / p1 if p1 != 0.0 else math.nan,
        "peak_prototype": peak_p,
        "peak_model": float(np.max(np.abs(m))),
        "max_abs_diff": diff,
        "max_abs_diff_rel_peak": diff / peak_p if peak_p > 0.0 else math.nan,
    }
