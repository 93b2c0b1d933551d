"""Parameter sweeps over scenario fields: cartesian grids and Monte Carlo samples, run in chunks
(serially or on a Dask cluster), resumable, stored as a Zarr dataset.

A sweep is a base :class:`~blastscale.io.scenario.Scenario`, grid axes (``charge_kg =
10:100:10``) and sampled fields (``friction = uniform:0.5,0.8``, N samples, a seed). Its cases are
the cartesian product of the axes, times the samples (the same draws at every grid point: common
random numbers, so differences between grid points are not sampling noise). Each case is the base
scenario ``with_values`` of its field values, and its result is the flat dict of scalars of the
Study (``Study(scenario).run().scalars()``; None -> NaN).

Two paths give these scalars:

* **planar batch** (:func:`planar_scalars`): cases whose engine is ``"planar"`` (a block) run in
  chunks through the compiled batch kernel (prototype and model, one call per chunk), with the
  Study's own design (once per distinct design) and critical charge (once per distinct
  structure, stand-off and blast model). It returns every key of the Study's ``scalars()``
  (``experiment.*``, ``design.*``, ``critical.*``, ``3d`` and the planar keys of
  :data:`PLANAR_KEYS`), computed from the same kernel inputs and the same formulas as the Study's
  ``compare_rocking``, without its per-case xarray machinery: bit for bit the Study's values
  (tests/test_sweeps.py checks every key).
* **Study** (every other case: 3D, both engines, columns): one Study per case.

A chunk's result depends only on its cases, so a sweep gives the same values whatever the chunk
size, the number of workers or the order of completion, and a killed sweep run again skips the
chunks already written (:func:`run_sweep`).

Store layout (Zarr, through xarray): one data variable per scalar key (dims: the grid axes named
after the bare field names, then ``sample``), coordinates the grid values and the sampled values
(on ``sample``), attributes: the sweep description (JSON), its fingerprint, versions, units.
While it runs, finished chunks live in ``STORE.parts/`` (one ``.npz`` per chunk, written
atomically), consolidated into the store at the end.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import shutil
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Optional

import numpy as np

from .._validate import BlastscaleInputError
from .grids import Distribution

__all__ = [
    "SweepSpec",
    "SweepAxis",
    "SweepSample",
    "evaluate_chunk",
    "planar_scalars",
    "planar_outcomes",
    "OUTCOME_KEYS",
    "study_scalars",
    "run_sweep",
    "SweepRun",
    "PLANAR_KEYS",
    "VALID_KEY",
    "field_unit",
]

#: Planar keys of the batch path (besides the Study's experiment.*, design.*, critical.*, 3d).
PLANAR_KEYS = tuple(
    [f"planar.{who}.{k}" for who in ("prototype", "model")
     for k in ("overturned", "max_angle_rad", "overturn_time_s", "first_impact_time_s", "n_impacts", "end_time_s")]
    + [f"planar.similarity.{k}" for k in ("max_abs_angle_diff_rad", "max_abs_angular_velocity_diff_rad_s",
                                          "max_abs_angle_diff_to_tipping_rad", "max_fall_phase_diff_rad",
                                          "overturn_time_diff_s", "tipping_angular_velocity_diff_rad_s",
                                          "peak_ratio", "outcomes_agree")]
)

#: Key of every case's result: False where the Study refused the case (its other values are NaN).
VALID_KEY = "sweep.valid"

_UNIT_SUFFIX = (("_kg_m3", "kg/m^3"), ("_m_s2", "m/s^2"), ("_rad_s", "rad/s"), ("_kg", "kg"), ("_m", "m"),
                ("_s", "s"), ("_rad", "rad"), ("_deg", "deg"), ("_Pa_s", "Pa*s"), ("_Pa", "Pa"), ("_Ns", "N*s"))


def field_unit(name: str) -> str:
    """Unit of a scenario or result key from its suffix (``charge_kg`` -> ``kg``; ``-`` if none)."""
    for suf, unit in _UNIT_SUFFIX:
        if name.endswith(suf):
            return unit
    return "-"


# ------------------------------------------------------------------------------------ the spec
@dataclass(frozen=True)
class SweepAxis:
    """A grid axis: ``name`` (coordinate name), ``path`` (dotted scenario path), ``values``."""

    name: str
    path: str
    values: tuple


@dataclass(frozen=True)
class SweepSample:
    """A sampled field: ``name``, ``path``, ``distribution``; ``relative`` multiplies the case's
    nominal value (grid or base scenario) by the draw instead of replacing it."""

    name: str
    path: str
    distribution: Distribution
    relative: bool = False


def _scenario_value(scenario, path: str):
    node = scenario
    for part in path.split("."):
        node = getattr(node, part)
    return node


@dataclass(frozen=True)
class SweepSpec:
    """A sweep: base scenario, grid axes, sampled fields (see the module docstring).

    Build it with :meth:`build`; ``cases`` are numbered in C order over ``shape`` (the grid axes,
    then ``sample``).
    """

    base: object  # Scenario
    axes: tuple = ()
    sampled: tuple = ()
    samples: int = 0
    seed: int = 0
    outcomes: bool = False
    _draws: dict = field(default_factory=dict, compare=False, repr=False)

    @classmethod
    def build(cls, base, vary: Optional[dict] = None, sample: Optional[dict] = None, *, samples: int = 0,
              seed: int = 0, relative: Optional[dict] = None, outcomes: bool = False) -> "SweepSpec":
        """A validated spec.

        Parameters
        ----------
        base : Scenario
            The scenario every case starts from.
        vary : dict, optional
            Field (bare or dotted) -> grid values (a non-empty 1-D sequence, in the field's unit).
        sample : dict, optional
            Field -> :class:`~blastscale.analysis.grids.Distribution` (absolute values).
        relative : dict, optional
            Field -> Distribution of a factor on the nominal value (e.g. lognormal(1, beta)).
        samples : int
            Number of Monte Carlo samples (>= 1 when something is sampled).
        seed : int
            Seed of numpy's ``default_rng``.
        outcomes : bool
            Outcome mode (:func:`planar_outcomes`): the first-swing results of planar block cases
            only, vectorised, instead of every Study scalar.

        Raises
        ------
        BlastscaleInputError
            Unknown or ambiguous field, a field given twice, an empty grid, samples < 1, outcome
            mode on cases that are not planar blocks.
        """
        vary, sample, relative = dict(vary or {}), dict(sample or {}), dict(relative or {})
        paths: dict[str, str] = {}
        for key in list(vary) + list(sample) + list(relative):
            paths[key] = base.resolve_key(key)
        grid_paths = [paths[k] for k in vary]
        abs_paths = [paths[k] for k in sample]
        if len(set(grid_paths)) != len(grid_paths) or len(set(abs_paths)) != len(abs_paths) \
                or set(grid_paths) & set(abs_paths) or len(set(paths[k] for k in relative)) != len(relative):
            raise BlastscaleInputError(f"fields = {', '.join(paths)}: a field may be varied or sampled only once")
        rel_paths = [paths[k] for k in relative]
        if set(rel_paths) & set(abs_paths):
            raise BlastscaleInputError(f"fields = {', '.join(paths)}: a field may be varied or sampled only once")
        all_paths = grid_paths + abs_paths + [p for p in rel_paths if p not in grid_paths]
        last = [p.split(".")[-1] for p in all_paths]

        def name(p):
            return p.split(".")[-1] if last.count(p.split(".")[-1]) == 1 else p

        axes = []
        for key, vals in vary.items():
            arr = np.atleast_1d(np.asarray(vals))
            if arr.ndim != 1 or arr.size == 0:
                raise BlastscaleInputError(f"{key} = {vals!r}: a grid must be a non-empty 1-D list of values")
            axes.append(SweepAxis(name(paths[key]), paths[key], tuple(arr.tolist())))
        samp = [SweepSample(name(paths[k]), paths[k], d) for k, d in sample.items()]
        samp += [SweepSample(name(paths[k]) + "_factor", paths[k], d, True) for k, d in relative.items()]
        if samp and (not isinstance(samples, (int, np.integer)) or isinstance(samples, bool) or samples < 1):
            raise BlastscaleInputError(f"samples = {samples!r} is out of range: must be a whole number >= 1")
        if not isinstance(seed, (int, np.integer)) or isinstance(seed, bool) or seed < 0:
            raise BlastscaleInputError(f"seed = {seed!r} is out of range: must be a whole number >= 0")
        spec = cls(base, tuple(axes), tuple(samp), int(samples) if samp else 0, int(seed), bool(outcomes))
        # every case must be a valid scenario: check each grid value, the extreme draws and the
        # corners now (one line, before any work is written)
        for a in spec.axes:
            for v in a.values:
                base.with_values({a.path: v})
        for sm in spec.sampled:
            d = spec.draws()[sm.name]
            for x in (d.min(), d.max()):
                base.with_values({sm.path: _scenario_value(base, sm.path) * x if sm.relative else x})
        for k in {0, spec.n_cases - 1}:
            spec.scenario(k)
        if spec.outcomes and not spec.planar_only:
            raise BlastscaleInputError(
                f"simulation.engine = {base.simulation.engine!r}, structure.kind = {base.structure.kind!r}: the "
                "outcome mode takes planar block cases only (set engine = \"planar\", or drop --outcomes to run "
                "the Study per case)")
        return spec

    # -- geometry of the case set ---------------------------------------------------------------
    @property
    def shape(self) -> tuple:
        """Shape of the case array: grid axes, then ``samples`` when sampled."""
        return tuple(len(a.values) for a in self.axes) + ((self.samples,) if self.sampled else ())

    @property
    def dims(self) -> tuple:
        """Dimension names: the grid axes' names, then ``sample``."""
        return tuple(a.name for a in self.axes) + (("sample",) if self.sampled else ())

    @property
    def n_cases(self) -> int:
        return int(np.prod(self.shape)) if self.shape else 1

    def draws(self) -> dict:
        """Sampled values per sampled field (arrays of length ``samples``), drawn in declaration
        order from ``numpy.random.default_rng(seed)``."""
        if not self._draws and self.sampled:
            rng = np.random.default_rng(self.seed)
            for s in self.sampled:
                self._draws[s.name] = s.distribution.sample(rng, self.samples)
        return self._draws

    def value_arrays(self, start: int, stop: int) -> dict:
        """Field values (dotted path -> array over the cases ``start .. stop - 1``): grid values
        as an object array of the values given, draws as floats."""
        idx = np.unravel_index(np.arange(int(start), int(stop)), self.shape) if self.shape else ()
        out = {a.path: np.array(a.values, dtype=object)[i] for a, i in zip(self.axes, idx)}
        if self.sampled:
            j = idx[-1]
            for s in self.sampled:
                x = self.draws()[s.name][j]
                if s.relative:
                    nominal = out[s.path].astype(float) if s.path in out else _scenario_value(self.base, s.path)
                    out[s.path] = nominal * x
                else:
                    out[s.path] = x
        return out

    def values(self, k: int) -> dict:
        """Field values (dotted path -> value) of case ``k``."""
        return {p: _plain(v[0]) for p, v in self.value_arrays(k, k + 1).items()}

    def scenario(self, k: int):
        """The scenario of case ``k`` (validated; an out-of-range value raises one line)."""
        return self.base.with_values(self.values(k)) if (self.axes or self.sampled) else self.base

    # -- identity ---------------------------------------------------------------------------------
    def describe(self) -> dict:
        """JSON-ready description (base scenario, axes, samples, seed)."""
        return {
            "base": self.base.to_dict(),
            "axes": [{"name": a.name, "path": a.path, "values": list(a.values)} for a in self.axes],
            "sampled": [{"name": s.name, "path": s.path, "distribution": s.distribution.kind,
                         "params": list(s.distribution.params), "relative": s.relative} for s in self.sampled],
            "samples": self.samples,
            "seed": self.seed,
            **({"outcomes": True} if self.outcomes else {}),  # absent otherwise: older fingerprints hold
        }

    def fingerprint(self) -> str:
        """sha256 of :meth:`describe` and the blastscale version: a resumed sweep must match it."""
        from .. import __version__

        text = json.dumps({"spec": self.describe(), "version": __version__}, sort_keys=True, default=str)
        return hashlib.sha256(text.encode()).hexdigest()

    def to_payload(self) -> dict:
        """Picklable plain form (sent to Dask workers); :meth:`from_payload` inverts it."""
        return self.describe()

    @classmethod
    def from_payload(cls, payload: dict) -> "SweepSpec":
        from ..io.scenario import Scenario

        base = Scenario.from_dict(payload["base"], source="sweep payload")
        axes = tuple(SweepAxis(a["name"], a["path"], tuple(a["values"])) for a in payload["axes"])
        samp = tuple(SweepSample(s["name"], s["path"], Distribution(s["distribution"], tuple(s["params"])), s["relative"])
                     for s in payload["sampled"])
        return cls(base, axes, samp, payload["samples"], payload["seed"], bool(payload.get("outcomes", False)))

    @property
    def planar_only(self) -> bool:
        """Whether every case takes the planar batch path (planar engine, block structure, and
        no varied or sampled field that changes that)."""
        try:
            return all(_planar_case(self.scenario(k)) for k in {0, self.n_cases - 1}) and not any(
                p.endswith(".engine") or p.endswith(".kind") for p in
                [a.path for a in self.axes] + [s.path for s in self.sampled])
        except BlastscaleInputError:
            return False


# ------------------------------------------------------------------------------------ scalars
def _planar_case(sc) -> bool:
    return sc.simulation.engine == "planar" and sc.structure.kind == "block"


def study_scalars(scenario) -> dict:
    """The Study path: ``Study(scenario).run().scalars()`` plus ``sweep.valid`` (warnings
    silenced: a sweep reports results, not one warning per case). A case the Study refuses
    (e.g. a model scaled distance outside the blast fits) gives ``{"sweep.valid": False}``:
    its other values are NaN in the store."""
    import warnings

    from ..study import Study

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            return {**Study(scenario).run().scalars(), VALID_KEY: True}
        except BlastscaleInputError:
            return {VALID_KEY: False}


def _block_key(b) -> tuple:
    return (b.height, b.width, b.depth, b.density)


def planar_scalars(scenarios) -> list[dict]:
    """The planar batch path for a list of planar block scenarios (module docstring): one dict of
    scalars per scenario, from one compiled kernel call per sampling size for all prototypes and
    models.

    Parameters
    ----------
    scenarios : sequence of Scenario
        Each with ``simulation.engine == "planar"`` and a block structure.

    Returns
    -------
    list of dict
        The Study's ``experiment.*``, ``design.*``, ``critical.*``, ``3d`` keys,
        :data:`PLANAR_KEYS` (SI; NaN where not applicable) and ``sweep.valid`` (True; a case
        whose design the blast fits refuse gives only ``{"sweep.valid": False}``).
    """
    import warnings

    from ..rocking import _kernel as K
    from .rocking_similarity import _fall_phase_diff
    from ..rocking import critical_charge
    from ..rocking import DEFAULT_SOLVER, encode_pulse
    from ..rocking.system import RockingSystem
    from ..study import Study, StudyResult

    solver = DEFAULT_SOLVER
    designs: dict = {}
    criticals: dict = {}
    bases: dict = {}
    rows = []  # per case: (scenario, structure, design, base scalars, sys_p, sys_m, t)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for sc in scenarios:
            if not _planar_case(sc):
                raise BlastscaleInputError(f"simulation.engine = {sc.simulation.engine!r}: the planar batch path "
                                           "takes planar block scenarios only")
            st = Study(sc)
            structure = st.structure()
            sim, bl = sc.simulation, sc.blast
            dkey = (_block_key(structure), bl.charge_kg, bl.standoff_m, sc.scale.length, sc.density_ratio,
                    sc.scale.gravity_ratio, sc.scale.law, bl.model, sim.gravity_m_s2, bl.extrapolate)
            if dkey not in designs:
                try:
                    designs[dkey] = st.design(structure)
                except BlastscaleInputError as exc:  # e.g. the model's Z outside the blast fits
                    designs[dkey] = exc
            d = designs[dkey]
            if isinstance(d, BlastscaleInputError):
                rows.append((sc, structure, None, {VALID_KEY: False}))
                continue
            crit, ckey = None, None
            if sim.critical_charge:
                ckey = (_block_key(structure), sim.gravity_m_s2, sim.restitution, bl.standoff_m, bl.pulse, bl.model,
                        bl.extrapolate)
                if ckey not in criticals:
                    system = RockingSystem.from_block(structure, sim.gravity_m_s2, sim.restitution)
                    criticals[ckey] = critical_charge(system, bl.standoff_m, pulse=bl.pulse, model=bl.model,
                                                      extrapolate=bl.extrapolate)
                crit = criticals[ckey]
            if (dkey, ckey) not in bases:  # experiment.*, design.*, critical.*: functions of these keys only
                b = StudyResult(scenario=sc, structure=structure, model_structure=structure.scaled(d.scale, d.density_ratio),
                                design=d, critical=crit).scalars()
                b.pop("planar", None)
                b[VALID_KEY] = True
                bases[(dkey, ckey)] = b
            rows.append((sc, structure, d, bases[(dkey, ckey)]))
    # the kernel inputs, exactly as RockingSolver.simulate builds them in compare_rocking
    per = {"alpha": [], "e": [], "w0": [], "tau_end": [], "kind": [], "par": [], "tt": [], "tf": [], "tev": [], "p": []}
    times = []
    ok_rows = [r for r in rows if r[2] is not None]
    n = len(ok_rows)
    for sc, structure, d, _ in ok_rows:
        sim = sc.simulation
        dur = float(sim.duration_s)
        t = np.linspace(0.0, dur, int(sim.samples))
        f = d.factors
        dur_m = dur * f.time
        t_m = np.minimum(t * f.time, dur_m)
        times.append(t)
        for system, pulse, du, tt in (
            (RockingSystem.from_block(structure, sim.gravity_m_s2, sim.restitution), d.prototype.pulse(sc.blast.pulse), dur, t),
            (RockingSystem.from_block(d.model_block, sim.gravity_m_s2 * d.gravity_ratio, sim.restitution),
             d.model.pulse(sc.blast.pulse), dur_m, t_m),
        ):
            p = system.frequency_parameter
            kind, par, tab_t, tab_f, dw = encode_pulse(pulse, system, 0.0)
            per["alpha"].append(system.alpha)
            per["e"].append(system.coefficient_of_restitution)
            per["w0"].append(0.0 / p + dw)
            per["tau_end"].append(du * p)
            per["kind"].append(kind)
            per["par"].append(par)
            per["tt"].append(tab_t)
            per["tf"].append(tab_f)
            per["tev"].append(np.ascontiguousarray(tt) * p)
            per["p"].append(p)
    summ = np.empty((2 * n, K.N_SUMMARY))
    theta = [None] * (2 * n)
    wdot = [None] * (2 * n)
    sizes = np.array([x.size for x in per["tev"]], dtype=np.int64)
    for m in np.unique(sizes):  # one compiled call per sampling size
        idx = np.flatnonzero(sizes == m)
        off = np.zeros(idx.size + 1, dtype=np.int64)
        off[1:] = np.cumsum([per["tt"][i].size for i in idx])
        tab_t = np.concatenate([per["tt"][i] for i in idx]) if off[-1] else np.zeros(0)
        tab_f = np.concatenate([per["tf"][i] for i in idx]) if off[-1] else np.zeros(0)
        s, th, w = K.solve_batch(
            np.array([per["alpha"][i] for i in idx]), np.array([per["e"][i] for i in idx]), np.zeros(idx.size),
            np.array([per["w0"][i] for i in idx]), np.array([per["tau_end"][i] for i in idx]),
            np.array([per["kind"][i] for i in idx], dtype=np.int64), np.ascontiguousarray([per["par"][i] for i in idx]),
            tab_t, tab_f, off, np.ascontiguousarray([per["tev"][i] for i in idx]),
            float(solver.rtol), float(solver.atol), float(solver.rest_velocity), -1, False, int(solver.max_steps), False,
        )
        bad = s[:, K.S_STATUS] != 0
        if np.any(bad):
            solver._check_status(s[np.argmax(bad), K.S_STATUS], int(idx[np.argmax(bad)] // 2))
        summ[idx] = s
        for j, i in enumerate(idx):
            theta[i], wdot[i] = th[j], w[j]
    out = []
    c = -1
    for sc, structure, d, base in rows:
        if d is None:
            out.append(dict(base))
            continue
        c += 1
        f = d.factors
        ip, im = 2 * c, 2 * c + 1
        pp, pm = per["p"][ip], per["p"][im]
        sp, sm = summ[ip], summ[im]
        res = dict(base)

        def summary(s, p, ft):
            # RockingResult.summary() (model: upscaled_summary, times / f.time, angles / f.angle)
            ot, fi = s[K.S_OVERTURN_TAU] / p, s[K.S_FIRST_IMPACT_TAU] / p
            fa, ft = (f.angle, ft) if ft else (1.0, 1.0)  # x / 1.0 is x: the prototype is unchanged
            return {
                "overturned": bool(s[K.S_OVERTURNED]),
                "max_angle_rad": float(s[K.S_MAX_ABS_THETA]) / fa,
                "overturn_time_s": float(ot) / ft if math.isfinite(ot) else math.nan,
                "first_impact_time_s": float(fi) / ft if math.isfinite(fi) else math.nan,
                "n_impacts": int(s[K.S_N_IMPACTS]),
                "end_time_s": float(s[K.S_END_TAU] / p) / ft,
            }

        sp_d, sm_d = summary(sp, pp, None), summary(sm, pm, f.time)
        for who, dd in (("prototype", sp_d), ("model", sm_d)):
            for k, v in dd.items():
                res[f"planar.{who}.{k}"] = v
        t = times[c]
        th_p, om_p = theta[ip], wdot[ip] * pp
        th_m, om_m = theta[im] / f.angle, wdot[im] * pm / f.angular_velocity
        diff = np.abs(th_m - th_p)
        ot_p, ot_m = sp[K.S_OVERTURN_TAU] / pp, sm[K.S_OVERTURN_TAU] / pm
        tips = [x for x in (ot_p, ot_m / f.time) if math.isfinite(x)]
        upto = t <= min(tips) if tips else np.ones(t.size, dtype=bool)
        both = sp_d["overturned"] and sm_d["overturned"]
        if both:
            ratio = 1.0
        elif sp[K.S_N_PEAKS] > 0 and sm[K.S_N_PEAKS] > 0:
            ratio = float(abs(sm[K.S_FIRST_PEAK]) / abs(sp[K.S_FIRST_PEAK]))
        else:
            ratio = float(sm[K.S_MAX_ABS_THETA] / sp[K.S_MAX_ABS_THETA]) if sp[K.S_MAX_ABS_THETA] > 0 else math.nan
        fall = _fall_phase_diff(t, th_p, om_p, th_m, om_m, max(ot_p, ot_m / f.time), pp) if both else None
        res.update({
            "planar.similarity.max_abs_angle_diff_rad": float(np.max(diff)),
            "planar.similarity.max_abs_angular_velocity_diff_rad_s": float(np.max(np.abs(om_m - om_p))),
            "planar.similarity.max_fall_phase_diff_rad": math.nan if fall is None else fall,
            "planar.similarity.max_abs_angle_diff_to_tipping_rad": float(np.max(diff[upto])),
            "planar.similarity.overturn_time_diff_s": ot_m / f.time - ot_p if both else math.nan,
            "planar.similarity.tipping_angular_velocity_diff_rad_s":
                (sm[K.S_W_AT_ALPHA] * pm) / f.angular_velocity - sp[K.S_W_AT_ALPHA] * pp if both else math.nan,
            "planar.similarity.peak_ratio": ratio,
            "planar.similarity.outcomes_agree": sp_d["overturned"] == sm_d["overturned"],
        })
        out.append({k: (v.item() if hasattr(v, "item") else v) for k, v in res.items()})
    return out


#: Keys of the outcome mode (:func:`planar_outcomes`), the Study's names where they mean the same.
OUTCOME_KEYS = (
    "planar.prototype.overturned", "planar.prototype.max_angle_rad", "planar.model.overturned",
    "planar.model.max_angle_rad", "planar.similarity.max_angle_ratio", "planar.similarity.outcomes_agree",
    "design.model_charge_kg", "design.model_standoff_m", VALID_KEY,
)
#: Fields the outcome mode vectorises over; the others that matter group the cases (one body, scale,
#: law, blast model and pulse per group); the rest (friction, duration, samples, 3D settings, ...)
#: play no part in it.
_LOAD_PATHS = ("blast.charge_kg", "blast.standoff_m", "simulation.restitution")


def _outcome_field(path: str) -> bool:
    return (path.startswith(("structure.", "blast.", "scale.")) or path == "simulation.gravity_m_s2") \
        and path not in _LOAD_PATHS + ("structure.friction", "blast.load", "blast.incidence")


def _groups(vals: dict, paths: list, n: int) -> list:
    """Index arrays of the cases sharing the values of ``paths`` (one group when none)."""
    if not paths:
        return [np.arange(n)]
    codes = []
    for p in paths:
        col = vals[p]
        try:
            _, inv = np.unique(col, return_inverse=True)
        except TypeError:  # unorderable mix (e.g. None and numbers): by first occurrence
            seen: dict = {}
            inv = np.array([seen.setdefault(v, len(seen)) for v in col.tolist()])
        codes.append(inv.ravel())
    _, inv = np.unique(np.stack(codes), axis=1, return_inverse=True)
    inv = inv.ravel()
    return [np.flatnonzero(inv == g) for g in range(int(inv.max()) + 1)]


def _outcome_group(sc, W, R, e) -> dict:
    """Outcome-mode arrays for n load cases ``W`` [kg], ``R`` [m], restitution ``e`` [-] (NaN:
    Housner's) of one scenario ``sc`` (body, scale, law, blast model and pulse)."""
    from ..blast.parameters import blast_parameters, get_blast_model, valid_scaled_distance_range
    from ..rocking import charge_for_impulse, first_swing_blast
    from ..rocking.system import RockingSystem, housner_restitution
    from ..similitude import scaling_factors
    from ..similitude.laws import hopkinson_cranz_density_ratio
    from ..study import Study

    n = W.size
    out = {k: np.full(n, np.nan) for k in OUTCOME_KEYS}
    out[VALID_KEY] = np.zeros(n, dtype=bool)
    bl, sim, scl = sc.blast, sc.simulation, sc.scale
    lam, sig, gam = scl.length, scl.gravity_ratio, sc.density_ratio
    if scl.law == "hopkinson-cranz":  # the law imposes gamma (design_model refuses another one)
        g_hc = hopkinson_cranz_density_ratio(lam, sig)
        if gam is not None and abs(gam - g_hc) > 1e-9 * g_hc:
            return out
        gam = g_hc
    structure = Study(sc).structure()
    proto = RockingSystem.from_block(structure, sim.gravity_m_s2)
    model = RockingSystem.from_block(structure.scaled(lam, gam), sim.gravity_m_s2 * sig)
    e = np.where(np.isnan(e), housner_restitution(proto.alpha), e)
    bm = get_blast_model(bl.model)
    # the Z range where the Study designs the model: every fit used (the impulse fit only with
    # extrapolate, where the general law is still solved on it), for the prototype and the model
    zr = bm.valid_range("scaled_reflected_impulse") if bl.extrapolate else valid_scaled_distance_range(bm)
    Z = R / np.cbrt(W)
    ok = (Z >= zr[0]) & (Z <= zr[1])
    Rm = lam * R
    Wm = np.full(n, np.nan)
    if np.any(ok):
        if scl.law == "hopkinson-cranz":
            Wm[ok] = W[ok] * scaling_factors(lam, gam, sig, 1.0).charge
        else:  # general law (paper Eq. 8): the model delivers the impulse x gamma sqrt(varsigma lambda^3)
            ip = bm.scaled_reflected_impulse(Z[ok], extrapolate=bl.extrapolate) * np.cbrt(W[ok])
            Wm[ok] = charge_for_impulse(ip * gam * math.sqrt(sig * lam**3), Rm[ok], bm,
                                        extrapolate=bl.extrapolate, z_range=zr)
        ok &= np.isfinite(Wm)
    if np.any(ok):
        bp = blast_parameters(W[ok], R[ok], bm, extrapolate=bl.extrapolate)
        bpm = blast_parameters(Wm[ok], Rm[ok], bm, extrapolate=bl.extrapolate)
        fp = first_swing_blast(proto.alpha, e[ok], proto.frequency_parameter, proto.load_ratio_per_pascal, bp,
                               bl.pulse)
        fm = first_swing_blast(model.alpha, e[ok], model.frequency_parameter, model.load_ratio_per_pascal, bpm,
                               bl.pulse)
        out["planar.prototype.overturned"][ok] = fp.overturned
        out["planar.prototype.max_angle_rad"][ok] = fp.max_rotation
        out["planar.model.overturned"][ok] = fm.overturned
        out["planar.model.max_angle_rad"][ok] = fm.max_rotation  # angles are not scaled (factor 1)
        out["planar.similarity.max_angle_ratio"][ok] = fm.max_rotation / fp.max_rotation
        out["planar.similarity.outcomes_agree"][ok] = fp.overturned == fm.overturned
        out["design.model_charge_kg"][ok] = Wm[ok]
        out["design.model_standoff_m"][ok] = Rm[ok]
        out[VALID_KEY][ok] = True
    return out


def planar_outcomes(spec: SweepSpec, start: int, stop: int) -> dict:
    """The outcome mode: first-swing results of the planar block cases ``start .. stop - 1`` of a
    sweep, vectorised over the cases (the design in numpy, the pulse phases in the compiled
    kernel, the first free swing in closed form; :func:`blastscale.rocking.first_swing.first_swing`).

    For the prototype and the model (designed by the scenario's law; the general law's model
    charge found by inverting the blast model's reflected impulse, which equals the Study's
    ``design_model`` to ~1e-12): ``overturned`` (at any time), ``max_angle_rad`` (the largest
    |theta| of the whole motion; pi/2 where it overturns), their ratio (model / prototype) and
    outcome agreement, the model charge and stand-off, and ``sweep.valid`` (False where the Study
    would refuse the design: a scaled distance outside the blast fits; NaN values there).
    Cases are grouped by the fields that matter other than charge, stand-off and restitution
    (structure, blast model and pulse, scale, gravity: one body, scale and law per group; friction,
    duration, samples and the 3D settings play no part); within a group everything is array
    arithmetic.

    Returns
    -------
    dict
        :data:`OUTCOME_KEYS` -> array over the cases (booleans as floats with NaN where some case
        of the chunk is invalid).
    """
    import warnings

    vals = spec.value_arrays(start, stop)
    n = int(stop) - int(start)
    base = spec.base
    col = {p: (vals[p].astype(float) if p in vals else np.full(n, np.nan if v is None else float(v)))
           for p, v in zip(_LOAD_PATHS, (base.blast.charge_kg, base.blast.standoff_m, base.simulation.restitution))}
    others = [p for p in vals if _outcome_field(p)]
    out = {k: np.full(n, np.nan) for k in OUTCOME_KEYS}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for idx in _groups(vals, others, n):
            sc = base.with_values({p: _plain(vals[p][idx[0]]) for p in others}) if others else base
            res = _outcome_group(sc, *(col[p][idx] for p in _LOAD_PATHS))
            for k in OUTCOME_KEYS:
                out[k][idx] = res[k]
    valid = out[VALID_KEY] == 1.0
    for k in ("planar.prototype.overturned", "planar.model.overturned", "planar.similarity.outcomes_agree", VALID_KEY):
        if k == VALID_KEY or valid.all():
            out[k] = out[k] == 1.0
    return out


def _plain(v):
    return v.item() if isinstance(v, np.generic) else v


def evaluate_chunk(payload: dict, start: int, stop: int) -> dict:
    """Scalars of the cases ``start .. stop - 1`` of a sweep (``payload`` from
    :meth:`SweepSpec.to_payload`): ``{"start", "stop", "values": {key: list}}``. Planar block
    cases take the batch path, the others the Study path; a case's values never depend on the
    other cases of its chunk."""
    spec = SweepSpec.from_payload(payload)
    if spec.outcomes:
        return {"start": start, "stop": stop, "values": planar_outcomes(spec, start, stop)}
    scen = [spec.scenario(k) for k in range(start, stop)]
    planar = [i for i, sc in enumerate(scen) if _planar_case(sc)]
    rows: list = [None] * len(scen)
    if planar:
        for i, r in zip(planar, planar_scalars([scen[i] for i in planar])):
            rows[i] = r
    for i, sc in enumerate(scen):
        if rows[i] is None:
            rows[i] = study_scalars(sc)
    keys = sorted({k for r in rows for k in r})
    return {"start": start, "stop": stop,
            "values": {k: [r.get(k, math.nan) for r in rows] for k in keys}}


# ------------------------------------------------------------------------------------ running
@dataclass(frozen=True)
class SweepRun:
    """What :func:`run_sweep` did: the store, the number of cases, chunks computed now and
    skipped (already written), ``seconds`` [s] computing them (on Dask: from the first submission
    to the last chunk written; the cluster's start and stop and the final consolidation are not
    counted), workers, and the rate of that computing."""

    store: str
    n_cases: int
    chunks_run: int
    chunks_skipped: int
    seconds: float
    workers: int
    cases_per_minute: float

    def to_dict(self) -> dict:
        return dict(self.__dict__)


def _chunk_path(parts: Path, i: int) -> Path:
    return parts / f"chunk-{i:07d}.npz"


def _write_chunk(parts: Path, i: int, result: dict) -> None:
    """Atomically write one chunk (temp file + rename: a killed sweep leaves whole files only)."""
    arrays = {"__start": np.array(result["start"]), "__stop": np.array(result["stop"])}
    for k, v in result["values"].items():
        arrays["v:" + k] = np.asarray(v)
    fd, tmp = tempfile.mkstemp(dir=parts, suffix=".tmp")
    with os.fdopen(fd, "wb") as fh:
        np.savez(fh, **arrays)
    os.replace(tmp, _chunk_path(parts, i))


def _read_chunk(path: Path) -> dict:
    with np.load(path, allow_pickle=False) as z:
        return {"start": int(z["__start"]), "stop": int(z["__stop"]),
                "values": {k[2:]: z[k] for k in z.files if k.startswith("v:")}}


def _consolidate(spec: SweepSpec, parts: Path, n_chunks: int, store: Path, meta: dict) -> None:
    import xarray as xr

    chunks = [_read_chunk(_chunk_path(parts, i)) for i in range(n_chunks)]
    keys = sorted({k for c in chunks for k in c["values"]})
    n = spec.n_cases
    data = {}
    for k in keys:
        vals = [c["values"].get(k) for c in chunks]
        kinds = {v.dtype.kind for v in vals if v is not None}
        if kinds == {"b"} and all(v is not None for v in vals):
            arr = np.empty(n, dtype=bool)
        elif kinds <= {"i", "u", "b"} and all(v is not None for v in vals):
            arr = np.empty(n, dtype=np.int64)
        elif kinds <= {"i", "u", "b", "f"}:
            arr = np.full(n, np.nan)
        else:
            continue  # not a number (never produced by scalars())
        for c, v in zip(chunks, vals):
            if v is not None:
                arr[c["start"]:c["stop"]] = v
        data[k] = (spec.dims, arr.reshape(spec.shape), {"units": field_unit(k)})
    coords = {a.name: (a.name, np.asarray(a.values), {"units": field_unit(a.path), "path": a.path}) for a in spec.axes}
    if spec.sampled:
        coords["sample"] = ("sample", np.arange(spec.samples))
        for s in spec.sampled:
            coords[s.name] = ("sample", spec.draws()[s.name],
                              {"units": "-" if s.relative else field_unit(s.path), "path": s.path,
                               "distribution": f"{s.distribution.kind}:{','.join(map(str, s.distribution.params))}",
                               "relative": int(s.relative)})
    ds = xr.Dataset(data, coords=coords, attrs=meta)
    tmp = store.with_name(store.name + ".tmp")
    if tmp.exists():
        shutil.rmtree(tmp)
    ds.to_zarr(tmp, mode="w", consolidated=False)
    if store.exists():
        shutil.rmtree(store)
    os.replace(tmp, store)


def _metadata(spec: SweepSpec, chunk: int) -> dict:
    import platform

    import numba

    from .. import __version__

    return {
        "title": "blastscale sweep",
        "sweep": json.dumps(spec.describe(), default=str),
        "fingerprint": spec.fingerprint(),
        "chunk_size": int(chunk),
        "n_cases": spec.n_cases,
        "blastscale_version": __version__,
        "numpy_version": np.__version__,
        "numba_version": numba.__version__,
        "python_version": platform.python_version(),
        "scalars": ("outcome mode: first-swing outcomes and largest rotations of the prototype and the model "
                    "(blastscale.analysis.sweeps.planar_outcomes)") if spec.outcomes else
                   ("Study(scenario).run().scalars() per case (planar block cases: the planar batch path, "
                    "blastscale.analysis.sweeps.planar_scalars)"),
        "created": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
    }


def _default_chunk(spec: SweepSpec, workers: int) -> int:
    if spec.outcomes:  # ~70 us per case: 20000 cases are ~1.5 s per task
        return int(max(1, min(20000, math.ceil(spec.n_cases / max(1, 2 * workers)))))
    if spec.planar_only:  # enough cases per task to amortise the task overhead, enough tasks to balance
        return int(max(1, min(2000, math.ceil(spec.n_cases / max(1, 4 * workers)))))
    return 1


def run_sweep(
    spec: SweepSpec,
    store,
    *,
    scheduler: Optional[str] = None,
    workers: Optional[int] = None,
    chunk: Optional[int] = None,
    force: bool = False,
    progress: Optional[Callable[[int, int], None]] = None,
) -> SweepRun:
    """Run a sweep into a Zarr store, resumably.

    Parameters
    ----------
    spec : SweepSpec
        The sweep.
    store : str or path
        The Zarr store (a directory, ``*.zarr``); finished chunks wait in ``store + ".parts"``.
    scheduler : str, optional
        Address of a running Dask scheduler (``tcp://127.0.0.1:8786``): run there unchanged.
    workers : int, optional
        Without ``scheduler``: a ``LocalCluster`` of this many single-threaded worker processes on
        127.0.0.1, no dashboard (default: the machine's CPU count); 0 runs in this process.
    chunk : int, optional
        Cases per task (default: outcome mode ~n / (2 workers), at most 20000; planar sweeps
        ~n / (4 workers), at most 2000; else 1).
    force : bool
        Replace a store of a different sweep (else refused).
    progress : callable, optional
        ``progress(cases_done, n_cases)`` after each chunk.

    Returns
    -------
    SweepRun
    """
    store = Path(store)
    fp = spec.fingerprint()
    if store.exists():
        old = _store_fingerprint(store)
        if old == fp:
            n = spec.n_cases
            return SweepRun(str(store), n, 0, 0, 0.0, 0, math.nan)
        if not force:
            raise BlastscaleInputError(
                f"out = {str(store)!r} already holds {'another sweep' if old else 'something else'}: "
                "choose another --out or pass --force to replace it")
    if not store.parent.is_dir():
        raise BlastscaleInputError(f"out = {str(store)!r}: the folder {str(store.parent)!r} does not exist")
    nw = (os.cpu_count() or 1) if workers is None else int(workers)
    if nw < 0:
        raise BlastscaleInputError(f"workers = {workers} is out of range: must be >= 0 (0: in this process)")
    parts = store.with_name(store.name + ".parts")
    manifest = parts / "sweep.json"
    if parts.exists():
        try:
            man = json.loads(manifest.read_text())
        except (OSError, ValueError):
            man = {}
        if man.get("fingerprint") != fp:
            if not force and man:
                raise BlastscaleInputError(
                    f"out = {str(store)!r}: the unfinished chunks in {str(parts)!r} belong to another sweep "
                    "(pass --force to discard them)")
            shutil.rmtree(parts)
        else:
            chunk = int(man["chunk"])  # resume with the chunking the chunks were written with
    if chunk is None:
        chunk = _default_chunk(spec, max(1, nw))
    if not isinstance(chunk, (int, np.integer)) or chunk < 1:
        raise BlastscaleInputError(f"chunk = {chunk!r} is out of range: must be a whole number >= 1")
    parts.mkdir(exist_ok=True)
    if not manifest.exists():
        manifest.write_text(json.dumps({"fingerprint": fp, "chunk": int(chunk), "n_cases": spec.n_cases}))
    n = spec.n_cases
    bounds = [(i, s, min(n, s + chunk)) for i, s in enumerate(range(0, n, chunk))]
    todo = [b for b in bounds if not _chunk_path(parts, b[0]).exists()]
    done_cases = sum(b[2] - b[1] for b in bounds) - sum(b[2] - b[1] for b in todo)
    t0 = time.perf_counter()
    payload = spec.to_payload()
    if progress:
        progress(done_cases, n)
    used = nw
    if todo and scheduler is None and nw == 0:  # in this process
        for i, a, b in todo:
            _write_chunk(parts, i, evaluate_chunk(payload, a, b))
            done_cases += b - a
            if progress:
                progress(done_cases, n)
    dt = time.perf_counter() - t0
    if todo and not (scheduler is None and nw == 0):
        used, dt = _run_dask(payload, todo, parts, scheduler, nw,
                             lambda k: progress(done_cases + k, n) if progress else None)
    _consolidate(spec, parts, len(bounds), store, _metadata(spec, chunk))
    shutil.rmtree(parts, ignore_errors=True)
    ran = sum(b - a for _, a, b in todo)
    return SweepRun(str(store), n, len(todo), len(bounds) - len(todo), dt, used,
                    ran / dt * 60.0 if dt > 0 and ran else math.nan)


def _store_fingerprint(store: Path) -> Optional[str]:
    try:
        import zarr

        return zarr.open_group(str(store), mode="r").attrs.get("fingerprint")
    except Exception:  # not a zarr store (or unreadable): treated as foreign
        return None


def _run_dask(payload, todo, parts: Path, scheduler, nw: int, tick) -> tuple:
    """Submit the chunks, write each as it completes; returns the number of workers used and the
    seconds from the first submission to the last chunk written (cluster start and stop excluded)."""
    from dask.distributed import Client, LocalCluster, as_completed

    cluster = None
    if scheduler is None:
        import warnings

        import dask

        # Dask's nannies set MALLOC_TRIM_THRESHOLD_=65536 in their workers: glibc then hands every
        # freed block above 64 kB back to the system, and the numpy temporaries of a planar chunk
        # come back as fresh pages each time (measured: +55 % CPU per outcome-mode chunk); the
        # local workers keep glibc's own (dynamic) threshold
        with warnings.catch_warnings(), dask.config.set({"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}):
            # the scheduler's HTTP (health) server takes another port when 8787 is busy: not our concern
            warnings.filterwarnings("ignore", message="Port .* is already in use", category=UserWarning)
            cluster = LocalCluster(n_workers=nw, threads_per_worker=1, processes=True, host="127.0.0.1",
                                   dashboard_address=None)
        client = Client(cluster)
    else:
        try:
            client = Client(scheduler, timeout="20s")
        except (OSError, TimeoutError) as exc:
            raise BlastscaleInputError(f"scheduler = {scheduler!r} cannot be reached: {exc}") from None
    try:
        used = len(client.scheduler_info().get("workers", {})) or nw
        t0 = time.perf_counter()
        futs = {client.submit(evaluate_chunk, payload, a, b, key=f"blastscale-chunk-{i}-{payload_hash(payload)}",
                              pure=False): (i, a, b) for i, a, b in todo}
        k = 0
        for fut in as_completed(futs):
            i, a, b = futs[fut]
            _write_chunk(parts, i, fut.result())
            k += b - a
            tick(k)
        return used, time.perf_counter() - t0
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def payload_hash(payload: dict) -> str:
    """Short hash of a sweep payload (task keys unique per sweep)."""
    return hashlib.sha1(json.dumps(payload, sort_keys=True, default=str).encode()).hexdigest()[:12]
