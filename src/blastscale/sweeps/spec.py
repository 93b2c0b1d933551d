"""A sweep's cases: a base scenario, cartesian grid axes and Monte Carlo samples of scenario
fields (:class:`SweepSpec`), numbered in C order over the grid axes, then ``sample``.

The same draws serve every grid point (common random numbers: differences between grid points
are not sampling noise). A spec is plain data: it travels to Dask workers as its payload
(:meth:`SweepSpec.to_payload`) and identifies a store by its fingerprint.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass, field
from typing import Optional

import numpy as np

from .. import __version__
from .._code import code_fingerprint
from .._validate import BlastscaleInputError
from ..scenario.scenario import Scenario
from .budget import VALUES_PER_CASE, check_cases_budget
from .grids import Distribution

__all__ = ["SweepAxis", "SweepSample", "SweepSpec", "planar_case"]


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
    def build(
        cls,
        base,
        vary: Optional[dict] = None,
        sample: Optional[dict] = None,
        *,
        samples: int = 0,
        seed: int = 0,
        relative: Optional[dict] = None,
        outcomes: bool = False,
    ) -> "SweepSpec":
        """A validated spec.

        Parameters
        ----------
        base : Scenario
            The scenario every case starts from.
        vary : dict, optional
            Field (bare or dotted) -> grid values (a non-empty 1-D sequence, in the field's unit).
        sample : dict, optional
            Field -> :class:`~blastscale.sweeps.grids.Distribution` (absolute values).
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
            mode on cases that are not planar blocks or on a prototype-only scenario (no ``[scale]``).
        """
        vary, sample, relative = dict(vary or {}), dict(sample or {}), dict(relative or {})
        paths: dict[str, str] = {}
        for key in list(vary) + list(sample) + list(relative):
            paths[key] = base.resolve_key(key)
        grid_paths = [paths[k] for k in vary]
        abs_paths = [paths[k] for k in sample]
        if (
            len(set(grid_paths)) != len(grid_paths)
            or len(set(abs_paths)) != len(abs_paths)
            or set(grid_paths) & set(abs_paths)
            or len(set(paths[k] for k in relative)) != len(relative)
        ):
            raise BlastscaleInputError(f"fields = {', '.join(paths)}: a field may be varied or sampled only once")
        rel_paths = [paths[k] for k in relative]
        if set(rel_paths) & set(abs_paths):
            raise BlastscaleInputError(f"fields = {', '.join(paths)}: a field may be varied or sampled only once")
        all_paths = grid_paths + abs_paths + [p for p in rel_paths if p not in grid_paths]
        last = [p.split(".")[-1] for p in all_paths]

        def name(p):  # an identifier: the field's own name, its whole path where two fields share it
            return p.split(".")[-1] if last.count(p.split(".")[-1]) == 1 else p.replace(".", "_")

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

        # too many cases for the memory even in the outcome mode: refused before a value is drawn or checked
        check_cases_budget(
            spec.n_cases, 0.0, VALUES_PER_CASE["outcomes"], None, hint="fewer --vary values or --samples"
        )
        # every case must be a valid scenario: check each grid value, the extreme draws and the
        # corners now (one line, before any work is written)
        for a in spec.axes:
            for v in _values_to_check(a.values):
                base.with_values({a.path: v})
        for sm in spec.sampled:
            d = spec.draws()[sm.name]
            for x in (d.min(), d.max()):
                base.with_values({sm.path: _scenario_value(base, sm.path) * x if sm.relative else x})
        for k in {0, spec.n_cases - 1}:
            spec.scenario(k)
        if spec.outcomes and base.scale is None:
            raise BlastscaleInputError(
                "scale = none (a prototype-only scenario): the outcome mode compares the prototype with its "
                "specimen; add a [scale] section, or drop --outcomes to run the Study per case (prototype only)"
            )
        if spec.outcomes and not spec.planar_only:
            raise BlastscaleInputError(
                f"simulation.engine = {base.simulation.engine!r}, structure.kind = {base.structure.kind!r}: the "
                'outcome mode takes planar block cases only (set engine = "planar", or drop --outcomes to run '
                "the Study per case)"
            )
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
            "sampled": [
                {
                    "name": s.name,
                    "path": s.path,
                    "distribution": s.distribution.kind,
                    "params": list(s.distribution.params),
                    "relative": s.relative,
                }
                for s in self.sampled
            ],
            "samples": self.samples,
            "seed": self.seed,
            **({"outcomes": True} if self.outcomes else {}),  # absent otherwise: older fingerprints hold
        }

    def fingerprint(self) -> str:
        """sha256 of :meth:`describe`, the blastscale version and the fingerprint of its code
        (:func:`blastscale._code.code_fingerprint`): a resumed sweep must match it, so that no chunk
        computed by other code is reused (issue #30)."""

        text = json.dumps(
            {"spec": self.describe(), "version": __version__, "code": code_fingerprint()}, sort_keys=True, default=str
        )
        return hashlib.sha256(text.encode()).hexdigest()

    def to_payload(self) -> dict:
        """Picklable plain form (sent to Dask workers); :meth:`from_payload` inverts it."""
        return self.describe()

    @classmethod
    def from_payload(cls, payload: dict) -> "SweepSpec":

        base = Scenario.from_dict(payload["base"], source="sweep payload")
        axes = tuple(SweepAxis(a["name"], a["path"], tuple(a["values"])) for a in payload["axes"])
        samp = tuple(
            SweepSample(s["name"], s["path"], Distribution(s["distribution"], tuple(s["params"])), s["relative"])
            for s in payload["sampled"]
        )
        return cls(base, axes, samp, payload["samples"], payload["seed"], bool(payload.get("outcomes", False)))

    @property
    def planar_only(self) -> bool:
        """Whether every case is a planar block case (planar engine, block structure, and
        no varied or sampled field that changes that)."""
        try:
            return all(planar_case(self.scenario(k)) for k in {0, self.n_cases - 1}) and not any(
                p.endswith(".engine") or p.endswith(".kind")
                for p in [a.path for a in self.axes] + [s.path for s in self.sampled]
            )
        except BlastscaleInputError:
            return False


def _values_to_check(values: tuple):
    """The grid values to validate one by one: all of a short or non-numeric axis; of a long numeric axis
    (> 1000 values) its two ends (the scenario's ranges are intervals) and, when they are whole numbers (a
    count), any value that is not, so that checking 10^7 values does not take half an hour."""
    if len(values) <= 1000 or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values[:1000]):
        return values
    arr = np.asarray(values)
    if arr.dtype.kind not in "if":
        return values
    ends = [arr.min().item(), arr.max().item()]
    if float(ends[0]).is_integer() and float(ends[1]).is_integer():
        odd = arr[arr != np.round(arr)]
        ends += odd[:1].tolist()
    return tuple(ends)


def planar_case(sc) -> bool:
    """Whether a scenario is a planar block case (large chunks, the outcome mode)."""
    return sc.simulation.engine == "planar" and sc.structure.kind == "block"


def _plain(v):
    return v.item() if isinstance(v, np.generic) else v
