"""Fragility curves of any structure: the probability that the prototype reaches each damage state
against the charge, under uncertain parameters, and its lognormal fit.

For every charge W of a grid, N Monte Carlo samples of the uncertain fields (a lognormal factor
of median 1 and log-standard deviation beta on a field's nominal value, or uniform absolute
values) give N scenarios (the same draws at every charge: common random numbers, so the
empirical curve is monotone when the outcome is). Each is decided by one of two criteria
(:data:`CRITERIA`):

* ``first-swing`` (blocks): the first-swing energy criterion of :mod:`blastscale.rocking.swing`
  (overturns at any time; planar rocking of the block; vectorised through the compiled kernel, a
  million draws a minute). It knows one state: ``collapse`` (the block overturns);
* ``damage`` (any structure): one Study per case on the sweep machinery (:mod:`.run`: in this
  process or on Dask, resumable into a store), the prototype alone (the specimen plays no part in the
  prototype's fragility; no ensembles: the draws are the ensemble), judged by the damage states of
  :func:`blastscale.analysis.damage.damage_state` (slight, moderate, severe, collapse: each state
  *reached* counts for it and for every milder one).

The counts k_j / N_j of each state are fitted by maximum likelihood with the lognormal fragility

.. math:: P(\\text{state reached} \\mid W) = \\Phi\\left(\\frac{\\ln(W/\\theta)}{\\beta}\\right),
          \\qquad \\max_{\\theta,\\beta} \\sum_j k_j \\ln\\Phi(z_j) + (N_j - k_j)\\ln(1 - \\Phi(z_j)),

(Shinozuka et al. 2000; Baker 2015 for the binomial likelihood), with 95 % profile-likelihood intervals
(Venzon & Moolgavkar 1988; Raue et al. 2009): the values of ln theta (of ln beta) at which the likelihood,
maximised over the other parameter, falls by chi2_1(0.95) / 2 = 1.92 from its maximum.

Known answer: with the charge alone uncertain, lognormal of median W and log-deviation beta, the
block overturns iff ``W eps > W_c`` (W_c the critical charge), so P(overturn | W) =
``Phi(ln(W / W_c) / beta)`` exactly: theta = W_c (tests/integration/test_fragility.py).

References: Shinozuka, M., Feng, M. Q., Lee, J., Naganuma, T. (2000). Statistical analysis of
fragility curves. J. Eng. Mech. 126(12), 1224-1231. Baker, J. W. (2015). Efficient analytical
fragility function fitting using dynamic structural analysis. Earthquake Spectra 31(1), 579-599.
Venzon, D. J., Moolgavkar, S. H. (1988). A method for computing profile-likelihood-based confidence
intervals. Appl. Statist. 37(1), 87-94. Raue, A. et al. (2009). Structural and practical identifiability
analysis of partially observed dynamical models by exploiting the profile likelihood. Bioinformatics
25(15), 1923-1929.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np

from .. import __version__
from .._validate import BlastscaleInputError
from ..analysis.damage import LEVELS
from ..analysis.planar import first_swing_of, planar_system
from ..rocking.solver import RockingSolver
from ..roots import scalar_root
from ..scenario.scenario import Scenario
from ..structures import from_spec
from ..study.memory import check_budget
from ..units import split_unit
from .budget import FIRST_SWING_SECONDS
from .grids import Distribution
from .layout import select
from .run import run_in_memory
from .spec import SweepSpec

__all__ = [
    "fragility",
    "FragilityResult",
    "StateFragility",
    "fit_lognormal_fragility",
    "LognormalFit",
    "overturning_outcomes",
    "CRITERIA",
    "default_criterion",
]

#: fields that only change the load (the body is then built once)
_LOAD_FIELDS = ("blast.charge_kg", "blast.standoff_m")

#: The criteria that decide a draw (module docstring), and the damage states each one knows.
CRITERIA = {"first-swing": ("collapse",), "damage": LEVELS[1:]}

#: Half the 95 % quantile of chi-square with one degree of freedom: the profile likelihood's drop at a 95 % bound.
_CHI2_95_HALF = 1.9207294103470614


def default_criterion(scenario) -> str:
    """``first-swing`` for a block (planar rocking, vectorised), ``damage`` for any other structure."""
    return "first-swing" if scenario.structure.kind == "block" else "damage"


@dataclass(frozen=True)
class LognormalFit:
    """Maximum-likelihood lognormal fragility (SI): ``median_charge_kg`` theta [kg], ``beta`` [-],
    95 % profile-likelihood bounds ``median_ci_kg`` and ``beta_ci``, standard errors ``se_ln_median`` and
    ``se_ln_beta`` [-] and the covariance of (ln theta, ln beta) from the observed information, the
    maximised log-likelihood.

    A bound the data cannot close (the profile likelihood does not fall by 1.92 within a factor
    :data:`OPEN_FACTOR` of the estimate) is open: 0 and ``inf`` (``math.inf``; "inf" in JSON), with ``note``
    saying why.
    When the charges separate the outcomes completely (every draw stands up to one charge and
    overturns from the next one on) the likelihood has no maximum: ``beta`` is None (no estimate,
    bounds [0, inf)), the median lies between those two charges (its bounds) and its value is their
    geometric mean; ``bounded`` is False."""

    median_charge_kg: float
    beta: "float | None"
    median_ci_kg: tuple
    beta_ci: tuple
    se_ln_median: float
    se_ln_beta: float
    log_likelihood: float
    note: str = ""
    bounded: bool = True
    covariance: tuple = ()

    def probability(self, charge):
        """Fitted P(state reached | W) at charges W [kg] (a step at the median when ``beta`` is None)."""
        from scipy.stats import norm

        w = np.asarray(charge, dtype=float)
        if not self.beta:
            return (w > self.median_charge_kg).astype(float)
        return norm.cdf(np.log(w / self.median_charge_kg) / self.beta)

    def band(self, charge, confidence: float = 0.95):
        """Pointwise bounds of the fitted curve at charges W [kg]: ``Phi(z -+ q s_z)`` with
        z = ln(W / theta) / beta, s_z its standard error from the covariance of (ln theta, ln beta)
        (delta method: dz/d ln theta = -1/beta, dz/d ln beta = -z) and q the normal quantile; None when
        the fit has no covariance (no beta, or an information matrix that cannot be inverted)."""
        from scipy.stats import norm

        if not self.beta or len(self.covariance) != 2 or not np.all(np.isfinite(self.covariance)):
            return None
        w = np.asarray(charge, dtype=float)
        z = np.log(w / self.median_charge_kg) / self.beta
        c = np.asarray(self.covariance, dtype=float)
        var = c[0, 0] / self.beta**2 + 2.0 * z * c[0, 1] / self.beta + z**2 * c[1, 1]
        q = norm.ppf(0.5 + confidence / 2.0) * np.sqrt(np.maximum(var, 0.0))
        return norm.cdf(z - q), norm.cdf(z + q)


#: A 95 % bound further than this factor from its estimate is reported open (0, inf): the data do not
#: bound the quantity within a decade either side (one informative charge, or none).
OPEN_FACTOR = 10.0


def _separated(W: np.ndarray, k: np.ndarray, n: np.ndarray) -> "tuple | None":
    """(last all-standing charge, first all-overturning charge) when the counts separate completely."""
    order = np.argsort(W)
    ws, ks, ns = W[order], k[order], n[order]
    if not np.all((ks == 0) | (ks == ns)):
        return None
    first = int(np.argmax(ks == ns))
    if np.any(ks[first:] != ns[first:]) or first == 0:
        return None
    return float(ws[first - 1]), float(ws[first])


def _separated_fit(lo: float, hi: float, reached: str, not_reached: str) -> LognormalFit:
    """The fit of completely separated counts (every draw below ``lo`` [kg] short of the state, every draw from
    ``hi`` [kg] reaching it): no maximum; the median bracketed by the two charges, beta open."""
    return LognormalFit(
        median_charge_kg=math.sqrt(lo * hi),
        beta=None,
        median_ci_kg=(lo, hi),
        beta_ci=(0.0, math.inf),
        se_ln_median=math.nan,
        se_ln_beta=math.nan,
        log_likelihood=0.0,
        bounded=False,
        note=(
            f"every draw {not_reached} at W <= {lo:.6g} kg and {reached} at W >= {hi:.6g} kg: the median lies "
            f"between them and beta cannot be estimated (open bounds; add charges between {lo:.6g} and "
            f"{hi:.6g} kg)"
        ),
    )


def _observed_covariance(nll, x: np.ndarray) -> tuple:
    """(covariance, standard errors) of the parameters ``x`` from the observed information: the inverse of the
    central-difference Hessian of the negative log-likelihood (step 1e-4); NaN when it cannot be inverted."""
    h = 1e-4
    H = np.empty((2, 2))
    for i in range(2):
        for j in range(2):
            e_i, e_j = np.eye(2)[i] * h, np.eye(2)[j] * h
            H[i, j] = (nll(x + e_i + e_j) - nll(x + e_i - e_j) - nll(x - e_i + e_j) + nll(x - e_i - e_j)) / (4 * h * h)
    try:
        cov = np.linalg.inv(H)
        return cov, np.sqrt(np.maximum(np.diag(cov), 0.0))
    except np.linalg.LinAlgError:
        return np.full((2, 2), math.nan), np.array([math.nan, math.nan])


def _profile_bounds(nll, x: np.ndarray, best: float, which: int) -> tuple:
    """95 % profile-likelihood bounds of ``exp(x[which])``: where ``min over the other parameter of nll``
    exceeds ``best`` by :data:`_CHI2_95_HALF`, searched within a factor :data:`OPEN_FACTOR` either side (open:
    0 or inf beyond)."""
    from scipy.optimize import minimize_scalar

    other = 1 - which

    def excess(v: float) -> float:
        def at(u):
            y = np.empty(2)
            y[which], y[other] = v, u
            return nll(y)

        with np.errstate(all="ignore"):  # Brent's parabolic steps meet an infinite likelihood far out: no news
            r = minimize_scalar(at, bracket=(x[other] - 0.1, x[other] + 0.1), tol=1e-10)
        return min(float(r.fun), at(x[other])) - best - _CHI2_95_HALF

    span = math.log(OPEN_FACTOR)
    out = []
    for side in (-1.0, 1.0):
        edge = x[which] + side * span
        try:
            if not excess(edge) > 0.0:
                out.append(0.0 if side < 0 else math.inf)
                continue
            out.append(math.exp(scalar_root(excess, x[which], edge, xtol=1e-12)))
        except (ValueError, FloatingPointError, OverflowError):
            out.append(0.0 if side < 0 else math.inf)
    return tuple(out)


def fit_lognormal_fragility(
    charges, collapsed, samples, *, reached: str = "overturns", not_reached: str = "stands"
) -> LognormalFit:
    """Fit ``P = Phi(ln(W / theta) / beta)`` to binomial counts by maximum likelihood.

    Parameters
    ----------
    charges : array_like
        Charges W_j [kg] > 0.
    collapsed : array_like
        Counts k_j [-] of the draws that reach the state (overturn).
    samples : int or array_like
        Trials N_j [-] per charge.
    reached, not_reached : str
        What a draw does that reaches the state and one that does not, in the notes (``overturns``,
        ``stands``).

    Returns
    -------
    LognormalFit
        With 95 % profile-likelihood bounds (module docstring).

    Raises
    ------
    BlastscaleInputError
        When every count is 0 or every count is N (no transition in the charge range: the median is
        not identifiable).
    """
    from scipy.optimize import minimize
    from scipy.special import log_ndtr  # scipy.stats.norm's logcdf (and logsf at -z), without its checks

    W = np.asarray(charges, dtype=float)
    k = np.asarray(collapsed, dtype=float)
    n = np.broadcast_to(np.asarray(samples, dtype=float), W.shape)
    if np.all(k == 0) or np.all(k == n):
        raise BlastscaleInputError(
            f"collapsed = {'none' if np.all(k == 0) else 'all'} of the samples at every charge in "
            f"[{W.min():.6g}, {W.max():.6g}] kg: widen --charges to cover the transition"
        )
    cut = _separated(W, k, n)
    if cut is not None:
        return _separated_fit(*cut, reached, not_reached)
    lw = np.log(W)

    def nll(x):
        z = (lw - x[0]) / math.exp(x[1])
        return -float(np.sum(k * log_ndtr(z) + (n - k) * log_ndtr(-z)))

    p = k / n
    mid = float(np.interp(0.5, p, lw)) if np.all(np.diff(p) >= 0) else float(np.mean(lw))
    spread = max(0.05, 0.25 * float(lw.max() - lw.min()))
    res = minimize(
        nll,
        np.array([mid, math.log(spread)]),
        method="Nelder-Mead",
        options={"xatol": 1e-10, "fatol": 1e-12, "maxiter": 4000},
    )
    x = res.x
    cov, se = _observed_covariance(nll, x)
    theta, beta = math.exp(x[0]), math.exp(x[1])
    best = float(res.fun)
    m_ci, b_ci = _profile_bounds(nll, x, best, 0), _profile_bounds(nll, x, best, 1)
    opened = [name for name, ci in (("median", m_ci), ("beta", b_ci)) if math.isinf(ci[1]) or ci[0] == 0.0]
    return LognormalFit(
        median_charge_kg=theta,
        beta=beta,
        median_ci_kg=m_ci,
        beta_ci=b_ci,
        se_ln_median=float(se[0]),
        se_ln_beta=float(se[1]),
        log_likelihood=-best,
        note=(
            f"the data do not bound the {' and the '.join(opened)} (open 95 % bounds): add charges where "
            f"some but not all draws {'overturn' if reached == 'overturns' else 'reach the state'}"
        )
        if opened
        else "",
        bounded=not opened,
        covariance=tuple(map(tuple, cov.tolist())),
    )


def overturning_outcomes(spec, *, block_size: int = 20000) -> np.ndarray:
    """Whether the prototype overturns (at any time) in every case of a sweep spec, by the
    first-swing criterion; shaped like ``spec.shape``.

    The scenario must be a block (planar rocking). Fields that change only the load (charge,
    stand-off) are vectorised over one body; any other field builds the body of each case.
    """

    base = spec.base
    if base.structure.kind != "block":
        raise BlastscaleInputError(
            f"structure.kind = {base.structure.kind!r}: the first-swing criterion needs a block (any structure: "
            "the damage criterion, --criterion damage)"
        )
    paths = {a.path for a in spec.axes} | {s.path for s in spec.sampled}
    per_case_body = bool(paths - set(_LOAD_FIELDS))
    n = spec.n_cases
    out = np.empty(n, dtype=bool)

    def system_of(sc):
        sim = sc.simulation
        return planar_system(from_spec(sc.structure), sim.gravity_m_s2, sim.restitution)

    one = None if per_case_body else system_of(base)
    solver = RockingSolver(threads=base.simulation.threads)  # the cases over this process's cores
    bl = base.blast
    for a in range(0, n, block_size):
        b = min(n, a + block_size)
        vals = spec.value_arrays(a, b)  # the whole block at once, not case by case
        W, R = (
            vals[p].astype(float) if p in vals else np.full(b - a, float(v))
            for p, v in zip(_LOAD_FIELDS, (bl.charge_kg, bl.standoff_m))
        )
        systems = [system_of(spec.scenario(k)) for k in range(a, b)] if per_case_body else one
        out[a:b] = first_swing_of(
            systems,
            W,
            R,
            pulse_shape=bl.pulse_shape,
            blast_model=bl.blast_model,
            extrapolate=bl.extrapolate,
            solver=solver,
        ).collapsed
    return out.reshape(spec.shape)


#: Why a field cannot enter the first-swing criterion (by dotted path; the others: it plays no part in it).
_NOT_FIRST_SWING = {
    "simulation.restitution": "a block at rest pushed by the blast is still swinging outward when the pulse "
    "ends, so no impact (where the restitution acts) decides its outcome",
    "structure.friction": "planar rocking has no sliding",
}


def _first_swing_field(path: str) -> bool:
    """Whether a field enters the first-swing criterion: the block, the charge and stand-off, gravity."""
    return path in _LOAD_FIELDS + ("simulation.gravity_m_s2",) or (
        path.startswith("structure.") and path != "structure.friction"
    )


#: Fields a damage fragility never reads: the prototype alone runs (no specimen), judged by [damage] only.
_NOT_DAMAGE = ("scale.", "verdict.", "lab.", "fired.", "simulation.ensemble_", "title")
#: Fields of planar rocking alone, refused when no planar engine runs.
_PLANAR_ONLY = ("simulation.restitution", "simulation.samples", "simulation.critical_charge")


def _refuse_fields(criterion: str, base, fields: dict) -> None:
    """Refuse, in one line, an uncertain field that cannot enter ``criterion`` (``fields``: flag text -> path)."""
    for flag, path in fields.items():
        if criterion == "first-swing" and not _first_swing_field(path):
            why = _NOT_FIRST_SWING.get(path, "it plays no part in the first swing of a rigid block")
            raise BlastscaleInputError(
                f"{flag}: {path} cannot enter the first-swing criterion ({why}); it takes the block's "
                "dimensions and density, charge_kg, standoff_m and gravity_m_s2 (or use --criterion damage: "
                "one Study per case)"
            )
        planar = base.simulation.engine in ("planar", "both") and base.structure.kind == "block"
        if criterion == "damage" and (path.startswith(_NOT_DAMAGE) or (path in _PLANAR_ONLY and not planar)):
            raise BlastscaleInputError(
                f"{flag}: {path} cannot enter the damage fragility (the prototype alone runs, one Study per "
                "case, without [scale] or ensembles, judged by [damage]): leave it out"
            )


@dataclass(frozen=True)
class StateFragility:
    """The fragility of one damage state: ``exceeded`` (n,) draws that reach it per charge, ``trials`` (n,)
    draws the engine decided per charge (a case the Study refuses is no trial), the lognormal ``fit`` (None
    when no transition was seen)."""

    name: str
    exceeded: np.ndarray
    trials: np.ndarray
    fit: Optional[LognormalFit]

    @property
    def probability(self) -> np.ndarray:
        """Observed fraction reaching the state per charge [-] (NaN where no trial)."""
        with np.errstate(invalid="ignore", divide="ignore"):
            return self.exceeded / self.trials

    def to_dict(self) -> dict:
        f = self.fit
        return {
            "exceeded": self.exceeded.tolist(),
            "trials": self.trials.tolist(),
            "median_charge_kg": None if f is None else f.median_charge_kg,
            "beta": None if f is None else f.beta,
            "median_charge_ci_kg": None if f is None else list(f.median_ci_kg),
            "beta_ci": None if f is None else list(f.beta_ci),
            "fit_bounded": None if f is None else f.bounded,
            "fit_note": None if f is None else (f.note or None),
        }


#: What each criterion's ``--json`` says it did.
_METHODS = {
    "first-swing": "first-swing energy criterion (planar rocking of the prototype), binomial maximum likelihood",
    "damage": "damage states of the prototype (one Study per case, without [scale] or ensembles; "
    "docs/sweeps.md), binomial maximum likelihood",
}


@dataclass(frozen=True)
class FragilityResult:
    """A fragility curve (SI): ``charge_kg`` (n,) [kg], ``collapsed`` (n,) counts of the draws that collapse
    (overturn) over ``samples`` draws, ``probability`` (n,) [-], the lognormal ``fit`` of the collapse (None
    when no transition was seen), the uncertain ``fields`` (description), ``seed``, ``seconds`` [s] of
    computing, the ``criterion`` and ``states``: name -> :class:`StateFragility` for every state the criterion
    knows (intact excluded)."""

    charge_kg: np.ndarray
    collapsed: np.ndarray
    samples: int
    probability: np.ndarray
    fit: LognormalFit | None
    fields: dict
    seed: int
    seconds: float
    extra: dict = field(default_factory=dict)
    criterion: str = "first-swing"
    states: dict = field(default_factory=dict)

    @property
    def standard_error(self) -> np.ndarray:
        """Binomial standard error of each probability, sqrt(p (1 - p) / samples) [-]."""
        return np.sqrt(self.probability * (1 - self.probability) / self.samples)

    def to_dict(self) -> dict:
        """Plain dict with unit-suffixed keys (JSON-ready)."""

        f = self.fit
        return {
            "blastscale_version": __version__,
            "method": _METHODS[self.criterion],
            "criterion": self.criterion,
            "charge_kg": self.charge_kg.tolist(),
            "collapsed": self.collapsed.tolist(),
            "samples": self.samples,
            "probability": self.probability.tolist(),
            "binomial_standard_error": self.standard_error.tolist(),
            "median_charge_kg": None if f is None else f.median_charge_kg,
            "beta": None if f is None else f.beta,
            "median_charge_ci_kg": None if f is None else list(f.median_ci_kg),
            "beta_ci": None if f is None else list(f.beta_ci),
            "log_likelihood": None if f is None else f.log_likelihood,
            "fit_bounded": None if f is None else f.bounded,
            "fit_note": None if f is None else (f.note or None),
            "fields": self.fields,
            "seed": self.seed,
            "seconds": self.seconds,
            "cases_per_minute": self.collapsed.size * self.samples / self.seconds * 60.0 if self.seconds > 0 else None,
            "states": {name: st.to_dict() for name, st in self.states.items()},
            **self.extra,
        }


def _distributions(lognormal, uniform) -> tuple:
    """(relative, absolute) distributions of the uncertain fields, each checked (one line)."""
    rel = {}
    for key, beta in (lognormal or {}).items():
        b = float(beta)
        if not (math.isfinite(b) and b > 0):
            raise BlastscaleInputError(
                f"--lognormal {key} = {beta!r}: beta is out of range: must be > 0 (beta = 0 is no uncertainty: "
                "every draw equals the nominal value; leave the field out, or use `blastscale critical` for "
                "the charge at which a certain block overturns)"
            )
        rel[key] = Distribution("lognormal", (1.0, b))
    absolute = {}
    for key, (lo, hi) in (uniform or {}).items():
        if not (math.isfinite(lo) and math.isfinite(hi) and hi > lo):
            raise BlastscaleInputError(f"{key} = uniform {lo:g}:{hi:g} is an empty range: hi must exceed lo")
        absolute[key] = Distribution("uniform", (float(lo), float(hi)))
    if not rel and not absolute:
        raise BlastscaleInputError(
            "uncertain fields = none: give at least one --lognormal FIELD=beta or --uniform FIELD=lo:hi"
        )
    return rel, absolute


def _checked_charges(charges) -> np.ndarray:
    W = np.atleast_1d(np.asarray(charges, dtype=float))
    if W.ndim != 1 or W.size == 0 or not np.all(np.isfinite(W) & (W > 0)):
        bad = next((f"{w:g} kg" for w in W.ravel() if not (np.isfinite(w) and w > 0)), "empty")
        shown = ", ".join(f"{w:g}" for w in W.ravel()[:6]) + (", ..." if W.size > 6 else "")
        raise BlastscaleInputError(
            f"charges = [{shown}] is out of range ({bad}): give a non-empty list of charges > 0 kg"
        )
    return W


def _prototype_alone(scenario):
    """The scenario of a damage fragility's cases: the prototype alone (no [scale]), no ensembles, no planar
    critical-charge search (the draws are the ensemble; the specimen plays no part in the prototype's fragility)."""
    data = scenario.to_dict()
    data.pop("scale", None)
    sim = dict(data.get("simulation") or {})
    sim.update(ensemble_members=0, critical_charge=False)
    data["simulation"] = sim
    return Scenario.from_dict(data, source="fragility")


def _levels(spec: SweepSpec, criterion: str, run) -> tuple:
    """(level, decided) arrays shaped like ``spec.shape``: each draw's damage level (:data:`LEVELS` index;
    first-swing: 4 where it overturns, else 0) and whether the engine decided it."""
    if criterion == "first-swing":
        over = overturning_outcomes(spec)
        return np.where(over, len(LEVELS) - 1, 0), np.ones(over.shape, dtype=bool)
    tree = run(spec)
    decided = np.asarray(tree["valid"].values, dtype=bool).reshape(spec.shape)
    try:
        level = np.asarray(select(tree, "damage.prototype.level").values, dtype=float).reshape(spec.shape)
    except KeyError:  # the Study refused every case: nothing decided
        level = np.full(spec.shape, np.nan)
    return np.where(decided, np.nan_to_num(level, nan=-1.0), -1.0).astype(int), decided


def _state_fits(W: np.ndarray, level: np.ndarray, decided: np.ndarray, criterion: str) -> dict:
    """name -> :class:`StateFragility` of every state ``criterion`` knows: the draws (rows: charges) whose
    ``level`` reaches it, over those ``decided``, and the lognormal fit."""
    trials = decided.sum(axis=1).astype(np.int64)
    states = {}
    for name in CRITERIA[criterion]:
        k = (level >= LEVELS.index(name)).sum(axis=1).astype(np.int64)
        words = (
            {} if criterion == "first-swing" else {"reached": f"reaches {name}", "not_reached": f"stays below {name}"}
        )
        try:
            fit = (
                fit_lognormal_fragility(W[trials > 0], k[trials > 0], trials[trials > 0], **words)
                if trials.any()
                else None
            )
        except BlastscaleInputError:
            fit = None
        states[name] = StateFragility(name, k, trials, fit)
    return states


def fragility(
    scenario,
    charges,
    *,
    lognormal=None,
    uniform=None,
    samples: int = 1000,
    seed: int = 0,
    criterion: Optional[str] = None,
    run: Optional[Callable] = None,
) -> FragilityResult:
    """Probability of reaching each damage state against the charge, with a lognormal fit per state (module
    docstring).

    Parameters
    ----------
    scenario : Scenario
        The base scenario (any structure; its charge is replaced by the grid).
    charges : array_like
        Charges W [kg] > 0 (a non-empty 1-D grid).
    lognormal : dict, optional
        Field (bare or dotted) -> beta [-] > 0: the field is its nominal value times a lognormal
        factor of median 1 and log-standard deviation beta (``charge_kg``: the charge and its TNT
        equivalence).
    uniform : dict, optional
        Field -> (lo, hi): uniform absolute values, in the field's unit (friction, geometric tolerances).
    samples : int
        Draws per charge (>= 1).
    seed : int
        Seed of numpy's ``default_rng``.
    criterion : {"first-swing", "damage"}, optional
        What decides a draw (:data:`CRITERIA`; default :func:`default_criterion`).
    run : callable, optional
        ``run(spec) -> tree``: how the damage criterion's sweep runs (default
        :func:`blastscale.sweeps.run.run_in_memory`, in this process; :func:`~blastscale.sweeps.run.run_sweep`
        into a store for Dask and resuming); it is given the spec, whose ``n_cases`` it may say first.

    Returns
    -------
    FragilityResult

    Raises
    ------
    BlastscaleInputError
        A charge not > 0, no uncertain field, a beta not > 0, an empty uniform range, an unknown criterion, a
        field that cannot enter the criterion (one line each, before any work).
    """
    W = _checked_charges(charges)
    rel, absolute = _distributions(lognormal, uniform)
    criterion = default_criterion(scenario) if criterion is None else criterion
    if criterion not in CRITERIA:
        raise BlastscaleInputError(f"criterion = {criterion!r} is not known: valid values are {', '.join(CRITERIA)}")
    base = scenario if criterion == "first-swing" else _prototype_alone(scenario)
    flags = {f"--lognormal {k}": base.resolve_key(k) for k in rel} | {
        f"--uniform {k}": base.resolve_key(k) for k in absolute
    }
    _refuse_fields(criterion, base, flags)
    draws = W.size * int(samples)
    if criterion == "first-swing":
        check_budget(
            "samples",
            samples,
            "",
            draws * 8.0 * (len(rel) + len(absolute) + 6) * 3,
            draws * FIRST_SWING_SECONDS,
            hint=f"{W.size} charges x samples draws",
        )
    elif base.structure.kind == "block" and base.simulation.engine == "planar":
        raise BlastscaleInputError(
            'criterion = "damage" with simulation.engine = "planar": a rocking block has no residual offsets; '
            'set engine = "3d" (or use the first-swing criterion)'
        )
    spec = SweepSpec.build(base, {"charge_kg": W}, absolute, relative=rel, samples=samples, seed=seed)
    run = run_in_memory if run is None else run
    t0 = time.perf_counter()
    level, decided = _levels(spec, criterion, run)
    dt = time.perf_counter() - t0
    states = _state_fits(W, level, decided, criterion)
    col = states["collapse"]
    fields = {
        s.name: {
            "path": s.path,
            "distribution": s.distribution.kind,
            "params": list(s.distribution.params),
            "relative": s.relative,
        }
        for s in spec.sampled
    }
    with np.errstate(invalid="ignore", divide="ignore"):
        p = col.exceeded / col.trials
    return FragilityResult(
        W, col.exceeded, int(samples), p, col.fit, fields, int(seed), dt, criterion=criterion, states=states
    )


def field_words(path: str, info: dict) -> str:
    """An uncertain field in words: ``charge x lognormal factor (beta 0.1)``, ``alpha 14-16 deg (uniform)``."""
    words, unit = split_unit(path.split(".")[-1])
    prm = info["params"]
    if info["relative"]:
        return f"{words} x lognormal factor (beta {prm[1]:g})"
    if info["distribution"] == "uniform":
        return f"{words} {prm[0]:g}-{prm[1]:g}{' ' + unit if unit else ''} (uniform)"
    return f"{words} ({info['distribution']} {', '.join(f'{x:g}' for x in prm)})"
