"""Fragility curves: the probability that the prototype overturns against the charge, under
uncertain parameters, and its lognormal fit.

For every charge W of a grid, N Monte Carlo samples of the uncertain fields (a lognormal factor
of median 1 and log-standard deviation beta on a field's nominal value, or uniform absolute
values) give N scenarios (the same draws at every charge: common random numbers, so the
empirical curve is monotone when the outcome is). Each is decided by the first-swing energy
criterion of :mod:`blastscale.rocking.swing` (overturns at any time; planar rocking of a
block; vectorised through the compiled kernel), and the counts k_j / N are fitted by maximum
likelihood with the lognormal fragility

.. math:: P(\\text{overturn} \\mid W) = \\Phi\\left(\\frac{\\ln(W/\\theta)}{\\beta}\\right),
          \\qquad \\max_{\\theta,\\beta} \\sum_j k_j \\ln\\Phi(z_j) + (N - k_j)\\ln(1 - \\Phi(z_j)),

(Shinozuka et al. 2000; Baker 2015 for the binomial likelihood), with 95 % confidence bounds from
the observed information (the inverse Hessian of the negative log-likelihood in (ln theta, ln beta)).

Known answer: with the charge alone uncertain, lognormal of median W and log-deviation beta, the
block overturns iff ``W eps > W_c`` (W_c the critical charge), so P(overturn | W) =
``Phi(ln(W / W_c) / beta)`` exactly: theta = W_c (tests/integration/test_fragility.py).

References: Shinozuka, M., Feng, M. Q., Lee, J., Naganuma, T. (2000). Statistical analysis of
fragility curves. J. Eng. Mech. 126(12), 1224-1231. Baker, J. W. (2015). Efficient analytical
fragility function fitting using dynamic structural analysis. Earthquake Spectra 31(1), 579-599.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from .. import __version__
from .._validate import BlastscaleInputError
from ..analysis.planar import first_swing_of, planar_system
from ..rocking.solver import RockingSolver
from ..structures import from_spec
from ..study.memory import check_budget
from .budget import FIRST_SWING_SECONDS
from .grids import Distribution
from .spec import SweepSpec

__all__ = ["fragility", "FragilityResult", "fit_lognormal_fragility", "LognormalFit", "overturning_outcomes"]

#: fields that only change the load (the body is then built once)
_LOAD_FIELDS = ("blast.charge_kg", "blast.standoff_m")


@dataclass(frozen=True)
class LognormalFit:
    """Maximum-likelihood lognormal fragility (SI): ``median_charge_kg`` theta [kg], ``beta`` [-],
    95 % bounds ``median_ci_kg`` and ``beta_ci``, standard errors ``se_ln_median`` and
    ``se_ln_beta`` [-], the maximised log-likelihood.

    A bound the data cannot close (a 95 % factor above :data:`OPEN_FACTOR`) is open: 0 and ``inf``
    (``math.inf``; "inf" in JSON), with ``note`` saying why.
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

    def probability(self, charge):
        """Fitted P(overturn | W) at charges W [kg] (a step at the median when ``beta`` is None)."""
        from scipy.stats import norm

        w = np.asarray(charge, dtype=float)
        if not self.beta:
            return (w > self.median_charge_kg).astype(float)
        return norm.cdf(np.log(w / self.median_charge_kg) / self.beta)


#: A 95 % bound further than this factor from its estimate is reported open (0, inf): the data do not
#: bound the quantity within a decade either side (one informative charge, or none).
OPEN_FACTOR = 10.0


def _open_bounds(centre: float, se: float) -> tuple:
    """95 % bounds ``centre x exp(-+1.96 se)``; open (0, inf) where ``se`` is not finite or the factor
    exceeds :data:`OPEN_FACTOR` (this also avoids exp's overflow)."""
    z95 = 1.959963984540054
    if not math.isfinite(se) or z95 * se > math.log(OPEN_FACTOR):
        return 0.0, math.inf
    return centre * math.exp(-z95 * se), centre * math.exp(z95 * se)


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


def fit_lognormal_fragility(charges, collapsed, samples) -> LognormalFit:
    """Fit ``P = Phi(ln(W / theta) / beta)`` to binomial counts by maximum likelihood.

    Parameters
    ----------
    charges : array_like
        Charges W_j [kg] > 0.
    collapsed : array_like
        Overturning counts k_j [-].
    samples : int or array_like
        Trials N_j [-] per charge.

    Returns
    -------
    LognormalFit

    Raises
    ------
    BlastscaleInputError
        When every count is 0 or every count is N (no transition in the charge range: the median is
        not identifiable).
    """
    from scipy.optimize import minimize
    from scipy.stats import norm

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
        lo, hi = cut
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
                f"every draw stands at W <= {lo:.6g} kg and overturns at W >= {hi:.6g} kg: the median lies "
                f"between them and beta cannot be estimated (open bounds; add charges between {lo:.6g} and "
                f"{hi:.6g} kg)"
            ),
        )
    lw = np.log(W)

    def nll(x):
        z = (lw - x[0]) / math.exp(x[1])
        return -float(np.sum(k * norm.logcdf(z) + (n - k) * norm.logsf(z)))

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
    # observed information: central-difference Hessian of the negative log-likelihood
    h = 1e-4
    H = np.empty((2, 2))
    for i in range(2):
        for j in range(2):
            e_i, e_j = np.eye(2)[i] * h, np.eye(2)[j] * h
            H[i, j] = (nll(x + e_i + e_j) - nll(x + e_i - e_j) - nll(x - e_i + e_j) + nll(x - e_i - e_j)) / (4 * h * h)
    try:
        cov = np.linalg.inv(H)
        se = np.sqrt(np.maximum(np.diag(cov), 0.0))
    except np.linalg.LinAlgError:
        se = np.array([math.nan, math.nan])
    theta, beta = math.exp(x[0]), math.exp(x[1])
    m_ci, b_ci = _open_bounds(theta, float(se[0])), _open_bounds(beta, float(se[1]))
    opened = [name for name, ci in (("median", m_ci), ("beta", b_ci)) if math.isinf(ci[1])]
    return LognormalFit(
        median_charge_kg=theta,
        beta=beta,
        median_ci_kg=m_ci,
        beta_ci=b_ci,
        se_ln_median=float(se[0]),
        se_ln_beta=float(se[1]),
        log_likelihood=-float(res.fun),
        note=(
            f"the data do not bound the {' and the '.join(opened)} (open 95 % bounds): add charges where "
            "some but not all draws overturn"
        )
        if opened
        else "",
        bounded=not opened,
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
            f"structure.kind = {base.structure.kind!r}: fragility by the first-swing criterion needs a block"
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


@dataclass(frozen=True)
class FragilityResult:
    """A fragility curve (SI): ``charge_kg`` (n,) [kg], ``collapsed`` (n,) counts over ``samples``
    draws, ``probability`` (n,) [-], the lognormal ``fit`` (None when no transition was seen),
    the uncertain ``fields`` (description), ``seed``, ``seconds`` [s] of computing."""

    charge_kg: np.ndarray
    collapsed: np.ndarray
    samples: int
    probability: np.ndarray
    fit: LognormalFit | None
    fields: dict
    seed: int
    seconds: float
    extra: dict = field(default_factory=dict)

    @property
    def standard_error(self) -> np.ndarray:
        """Binomial standard error of each probability, sqrt(p (1 - p) / samples) [-]."""
        return np.sqrt(self.probability * (1 - self.probability) / self.samples)

    def to_dict(self) -> dict:
        """Plain dict with unit-suffixed keys (JSON-ready)."""

        f = self.fit
        return {
            "blastscale_version": __version__,
            "method": "first-swing energy criterion (planar rocking of the prototype), binomial maximum likelihood",
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
            **self.extra,
        }


def fragility(
    scenario, charges, *, lognormal=None, uniform=None, samples: int = 1000, seed: int = 0
) -> FragilityResult:
    """Probability of overturning against the charge, with a lognormal fit (module docstring).

    Parameters
    ----------
    scenario : Scenario
        The base scenario (a block; its charge is replaced by the grid).
    charges : array_like
        Charges W [kg] > 0 (a non-empty 1-D grid).
    lognormal : dict, optional
        Field (bare or dotted) -> beta [-] >= 0: the field is its nominal value times a lognormal
        factor of median 1 and log-standard deviation beta (``charge_kg`` included).
    uniform : dict, optional
        Field -> (lo, hi): uniform absolute values, in the field's unit.
    samples : int
        Draws per charge (>= 1).
    seed : int
        Seed of numpy's ``default_rng``.

    Returns
    -------
    FragilityResult
    """

    W = np.atleast_1d(np.asarray(charges, dtype=float))
    if W.ndim != 1 or W.size == 0 or not np.all(np.isfinite(W) & (W > 0)):
        bad = next((f"{w:g} kg" for w in W.ravel() if not (np.isfinite(w) and w > 0)), "empty")
        shown = ", ".join(f"{w:g}" for w in W.ravel()[:6]) + (", ..." if W.size > 6 else "")
        raise BlastscaleInputError(
            f"charges = [{shown}] is out of range ({bad}): give a non-empty list of charges > 0 kg"
        )
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

    draws = W.size * int(samples)
    check_budget(
        "samples",
        samples,
        "",
        draws * 8.0 * (len(rel) + len(absolute) + 6) * 3,
        draws * FIRST_SWING_SECONDS,
        hint=f"{W.size} charges x samples draws",
    )
    spec = SweepSpec.build(scenario, {"charge_kg": W}, absolute, relative=rel, samples=samples, seed=seed)
    t0 = time.perf_counter()
    over = overturning_outcomes(spec)
    dt = time.perf_counter() - t0
    k = over.sum(axis=1).astype(np.int64)
    p = k / samples
    try:
        fit = fit_lognormal_fragility(W, k, samples)
    except BlastscaleInputError:
        fit = None
    fields = {
        s.name: {
            "path": s.path,
            "distribution": s.distribution.kind,
            "params": list(s.distribution.params),
            "relative": s.relative,
        }
        for s in spec.sampled
    }
    return FragilityResult(W, k, int(samples), p, fit, fields, int(seed), dt)
