"""The odds of a test: the lab's tolerances propagated by Monte Carlo through the fast planar
kernels (the first-swing criterion and peak of :mod:`blastscale.rocking.swing`, vectorised), or
through small 3D ensembles (one Study of the design's specimen per member,
:meth:`~blastscale.study.Study.from_design`, on Dask when asked).

Tolerances are one standard deviation (``[lab]``): the explosive's mass relative, lognormal
(``m eps``, ``ln eps ~ N(0, s_W)``; the initiator is not perturbed); the stand-off absolute, normal
(``R + s_R z``, kept above 1 % of R); the specimen's density relative, normal (``rho (1 + s_rho z)``,
kept above 1 %); the friction coefficient absolute, normal, around the specimen's own (its material's,
:func:`specimen_friction`; 3D only: the planar block rocks without sliding, friction plays no part in
it, and the planner checks its regime in closed form, :mod:`blastscale.similitude.friction`). The draws come from numpy's ``default_rng(seed)`` in that
order (charge, stand-off, density, friction), so a seed reproduces the odds exactly.

What comes out (:class:`Odds`): the probability that the specimen's outcome (overturns or not, at
any time) equals the prototype's, with its Wilson interval (95 %,
:func:`~blastscale.analysis.intervals.wilson_interval`: right for small ensembles, where a binomial
standard error reads "+- 0" at k = n; ``agree_count`` of ``trials``), the spread of the specimen's first
peak (the largest rotation of a block that survives), and the weighing precision: the relative
standard deviation of the charge that keeps the first peak within ``target`` with 95 %
probability, ``s_W = ln(1 + target) / (1.96 |d ln theta / d ln W|)`` (the sensitivity by central
differences at +-1 % of the charge), and the one that keeps the outcome with 95 %
(``s_W = |ln((W_c - W_init) / m)| / 1.645``, W_c the specimen's critical charge).

Known answer (tests/unit/planning/test_odds.py): with the charge alone uncertain and no initiator the
specimen overturns iff ``W eps > W_c``, so ``P(overturn) = Phi(ln(W / W_c) / s_W)`` exactly.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import asdict, dataclass, replace
from typing import Optional

import numpy as np

from .._extras import require
from .._threads import map_threads
from .._validate import BlastscaleInputError
from ..analysis.intervals import Z95, odds_text, wilson_interval
from ..blast.parameters import blast_parameters_unchecked, valid_scaled_distance_range
from ..similitude.factors import scaling_factors, to_specimen
from ..study.study import Study
from ..sweeps.grids import Distribution

__all__ = [
    "specimen_friction",
    "Tolerances",
    "Odds",
    "planar_odds",
    "SpecimenMember",
    "specimen_members",
    "ensemble_odds_3d",
    "outcome_odds_text",
    "Z90_ONE_SIDED",
]

Z90_ONE_SIDED = 1.6448536269514722  # one-sided 95 % normal quantile


@dataclass(frozen=True)
class Tolerances:
    """One standard deviation of each lab quantity: ``charge`` relative (lognormal log-sd) [-],
    ``standoff_m`` [m], ``density`` relative [-], ``friction`` [-]."""

    charge: float = 0.0
    standoff_m: float = 0.0
    density: float = 0.0
    friction: float = 0.0

    @classmethod
    def from_lab(cls, lab) -> "Tolerances":
        return cls(lab.charge_tolerance, lab.standoff_tolerance_m, lab.density_tolerance, lab.friction_tolerance)

    def for_shot(self, charge) -> "Tolerances":
        """These tolerances for one design's charge: a calibrated source's shot
        (:class:`~blastscale.blast.sources.SourceShot`) draws its charge with its own log-normal standard deviation,
        the source's repeatability and its fit's uncertainty at the shot's control value in quadrature, in place of
        ``[lab] charge_tolerance`` (the calibration's shot-to-shot scatter holds the bank's charging precision;
        docs/planning.md, "Sources"); a chemical charge keeps them."""
        s = getattr(charge, "sigma_ln_impulse", None)
        return self if s is None else replace(self, charge=float(s))


@dataclass(frozen=True)
class Odds:
    """Monte Carlo odds of a specimen test (module docstring); angles [rad], probabilities [-]."""

    engine: str
    samples: int
    seed: int
    prototype_collapsed: bool
    p_outcome_agree: float
    p_outcome_agree_low: float
    p_outcome_agree_high: float
    specimen_collapse_probability: float
    first_peak_nominal_rad: Optional[float]
    first_peak_spread: Optional[float]
    first_peak_p05_rad: Optional[float]
    first_peak_p95_rad: Optional[float]
    first_peak_sensitivity: Optional[float]
    specimen_critical_charge_kg: Optional[float]
    charge_tolerance_for_peak: Optional[float]
    charge_tolerance_for_outcome: Optional[float]
    samples_outside_fits: int = 0  # draws whose scaled distance leaves the blast fits: left out of the odds
    agree_count: int = 0  # draws whose outcome agrees with the prototype's
    trials: int = 0  # draws counted in the odds (inside the blast fits)

    @property
    def charge_tolerance_needed(self) -> Optional[float]:
        """The tighter of the two weighing precisions (relative, one standard deviation) [-]."""
        vals = [v for v in (self.charge_tolerance_for_peak, self.charge_tolerance_for_outcome) if v is not None]
        return min(vals) if vals else None

    def to_dict(self) -> dict:
        return {**asdict(self), "charge_tolerance_needed": self.charge_tolerance_needed}


def _draws(n: int, seed: int, tol: Tolerances):
    rng = np.random.default_rng(seed)
    z = rng.standard_normal((4, n))
    return np.exp(tol.charge * z[0]), tol.standoff_m * z[1], tol.density * z[2], tol.friction * z[3]


def planar_odds(
    specimen,
    *,
    charge_kg: float,
    standoff_m: float,
    prototype_collapsed: bool,
    explosive_fraction: float = 1.0,
    gravity: float = 9.81,
    restitution: Optional[float] = None,
    pulse_shape: str = "friedlander",
    blast_model="kingery-bulmash",
    tolerances: Tolerances = Tolerances(),
    samples: int = 2000,
    seed: int = 0,
    target: float = 0.05,
    critical: bool = True,
) -> Odds:
    """Odds of a block specimen by Monte Carlo through the planar first-swing kernel.

    Parameters
    ----------
    specimen : RectangularBlock
        The specimen block (its nominal density).
    charge_kg, standoff_m : float
        The specimen's nominal TNT charge (impulse basis, initiator included) [kg] and stand-off [m].
    prototype_collapsed : bool
        The prototype's outcome (overturns at any time).
    explosive_fraction : float
        Share of the TNT charge carried by the weighed explosive (1 - initiator fraction) [-]: only
        that part is perturbed.
    gravity, restitution, pulse_shape, blast_model
        As the Study's (restitution None: Housner's).
    tolerances : Tolerances
    samples, seed : int
    target : float
        Largest relative error of the first peak for the weighing precision [-].
    critical : bool
        Search the specimen's critical charge (the weighing precision that keeps the outcome).
    """
    from ..analysis.planar import critical_of, first_swing_of, first_swing_under, planar_system  # noqa: PLC0415 -- start-up: at module top `blastscale` would load numba, scipy

    n = int(samples)
    W0, R0 = float(charge_kg), float(standoff_m)
    w_init = W0 * (1.0 - float(explosive_fraction))
    m_tnt = W0 - w_init
    eps, dR, drho, _ = _draws(n, seed, tolerances)
    W = w_init + m_tnt * eps
    R = np.maximum(R0 + dR, 0.01 * R0)
    rho = np.maximum(1.0 + drho, 0.01)
    base = planar_system(specimen, gravity, restitution)
    kw = dict(pulse_shape=pulse_shape, blast_model=blast_model)

    W, R, rho, outside, extrapolate = _inside_fits(W, R, rho, blast_model)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        # a homogeneous block: the density changes only the load per unit pressure (q = S l / (m g r cos alpha))
        bp = blast_parameters_unchecked(W, R, blast_model, extrapolate=extrapolate)
        fs = first_swing_under(base, bp, pulse_shape, density_ratio=rho)
        nominal = first_swing_of(base, np.array([W0 * 0.99, W0, W0 * 1.01]), R0, extrapolate=True, **kw)
        wc = None
        if critical:
            try:
                wc = float(critical_of(base, standoff=R0, **kw).charge_kg)
            except Exception:  # noqa: BLE001 - no threshold inside the fits' range: the outcome is not at risk
                wc = None
    agree = fs.collapsed == bool(prototype_collapsed)
    p = float(np.mean(agree))
    k = int(W.size)
    lo, hi = wilson_interval(int(agree.sum()), k)
    peak_nom, sens, spread, p05, p95, tol_peak = _peak_figures(nominal, fs, target)
    tol_out = None
    if wc is not None and wc > w_init and m_tnt > 0:
        tol_out = abs(math.log((wc - w_init) / m_tnt)) / Z90_ONE_SIDED
    return Odds(
        "planar",
        n,
        int(seed),
        bool(prototype_collapsed),
        p,
        lo,
        hi,
        float(np.mean(fs.collapsed)),
        peak_nom,
        spread,
        p05,
        p95,
        sens,
        wc,
        tol_peak,
        tol_out,
        outside,
        int(agree.sum()),
        k,
    )


def _inside_fits(W, R, rho, blast_model) -> tuple:
    """(W, R, rho, draws left out, extrapolate) of the drawn charges [kg], stand-offs [m] and density factors:
    the draws whose scaled distance the blast fits cover (those outside are left out and counted); every draw
    kept, extrapolating, when none is covered."""
    zlo, zhi = valid_scaled_distance_range(blast_model)
    Z = R / np.cbrt(W)
    inside = (Z >= zlo) & (Z <= zhi)
    outside = int(W.size - inside.sum())
    extrapolate = not inside.any()
    if extrapolate:
        inside[:] = True
    return W[inside], R[inside], rho[inside], outside, extrapolate


def _peak_figures(nominal, fs, target: float) -> tuple:
    """(nominal first peak [rad], sensitivity d ln theta / d ln W, relative spread, 5 % and 95 % first peaks [rad],
    charge tolerance for ``target``) of the first swings: ``nominal`` at 0.99, 1 and 1.01 x the charge, ``fs`` of
    the draws (None where the nominal specimen overturns)."""
    peak_nom = None if nominal.collapsed[1] else float(nominal.max_rotation[1])
    sens = spread = p05 = p95 = tol_peak = None
    surv = fs.max_rotation[~fs.collapsed]
    if peak_nom is not None and not np.any(nominal.collapsed):
        sens = float(np.log(nominal.max_rotation[2] / nominal.max_rotation[0]) / (2.0 * math.log(1.01)))
        if surv.size >= 2:
            spread = float(np.std(surv, ddof=1) / np.median(surv))
            p05, p95 = (float(x) for x in np.quantile(surv, [0.05, 0.95]))
        if sens != 0.0:
            tol_peak = math.log(1.0 + target) / (Z95 * abs(sens))
    return peak_nom, sens, spread, p05, p95, tol_peak


@dataclass(frozen=True)
class SpecimenMember:
    """One member of a specimen's 3D ensemble: the design's specimen under the lab's tolerances drawn once.

    Attributes
    ----------
    charge_kg, standoff_m : float
        The load [kg TNT], [m].
    friction : float
        The friction coefficient [-].
    density_factor : float
        The specimen's density relative to the design's [-].
    """

    charge_kg: float
    standoff_m: float
    friction: float
    density_factor: float


def specimen_friction(scenario, design) -> float:
    """The specimen's nominal friction coefficient [-]: the prototype's (``structure.friction``) x the design's
    friction factor lambda_mu (its material's joint friction, :mod:`blastscale.structures.materials`)."""
    return float(to_specimen(float(scenario.structure.friction), design.factors, "friction", "structure.friction"))


def specimen_members(scenario, design, tolerances: Tolerances, members: int, seed: int = 0) -> list:
    """The members of a specimen's 3D ensemble (:class:`SpecimenMember`): the design's specimen charge, stand-off,
    the specimen's friction (:func:`specimen_friction`: its material's) and its density drawn as in :func:`planar_odds` from
    ``numpy.random.default_rng(seed)``, in the order stand-off (normal, absolute), friction (normal, absolute),
    charge (lognormal, relative), density (normal, relative): the draws of the sweeps' samples of that order."""
    n = int(members)
    if n < 1:
        raise BlastscaleInputError(f"members = {members!r} is out of range: must be a whole number >= 1")
    rng = np.random.default_rng(int(seed))
    dists = (
        Distribution("normal", (float(design.specimen_standoff_m), max(tolerances.standoff_m, 1e-12))),
        Distribution("normal", (specimen_friction(scenario, design), max(tolerances.friction, 1e-12))),
        Distribution("lognormal", (1.0, max(tolerances.charge, 1e-12))),
        Distribution("normal", (1.0, max(tolerances.density, 1e-12))),
    )
    standoff, friction, charge, density = (d.sample(rng, n) for d in dists)
    w = float(design.specimen_charge_kg)
    return [
        SpecimenMember(float(w * charge[k]), float(standoff[k]), float(friction[k]), float(density[k]))
        for k in range(n)
    ]


def _member_outcome(task) -> tuple:
    """(collapsed, largest top displacement [m]) of one member (NaN where the Study refuses its inputs): the
    design's specimen alone on the 3D engine (:meth:`~blastscale.study.Study.from_design`), its density x the
    member's factor (``structure.scaled(factors)``) and its friction the member's."""
    scenario, design, m = task
    factors = scaling_factors(1.0, density_ratio=m.density_factor)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # an ensemble reports results, not one warning per member
        try:
            r = Study.from_design(
                scenario,
                design,
                charge_kg=m.charge_kg,
                standoff_m=m.standoff_m,
                engine="3d",
                structure=design.specimen_structure.scaled(factors),
                friction=m.friction,
            ).run()
        except BlastscaleInputError:
            return math.nan, math.nan
    s = r.summary()["3d"]["prototype"]
    return float(bool(s["collapsed"])), float(s["max_top_displacement_m"])


def ensemble_odds_3d(
    scenario,
    design,
    *,
    prototype_collapsed: bool,
    tolerances: Tolerances,
    members: int,
    seed: int = 0,
    workers: int = 0,
    scheduler: Optional[str] = None,
    tick=None,
) -> dict:
    """Odds of a specimen by a small 3D ensemble: ``members`` runs (3D engine, MuJoCo) of the design's specimen
    alone (:meth:`~blastscale.study.Study.from_design`, the scenario's engine settings), its charge, stand-off,
    friction and density drawn by :func:`specimen_members`, on ``workers`` local Dask processes or a
    ``scheduler`` (one member per task), or in this process on native threads (0 and None:
    ``simulation.threads``). ``tick(done)`` after each member (members done so far).

    Returns
    -------
    dict
        ``members`` and ``trials`` (the members that ran), ``agree_count`` (those whose outcome, collapse or not,
        is the prototype's), ``p_outcome_agree`` (their fraction), its Wilson interval at ``[verdict] confidence``
        ``p_outcome_agree_low``, ``p_outcome_agree_high`` (None without a member),
        ``specimen_collapse_probability``, ``first_peak_spread`` (relative
        standard deviation of the largest top displacement of the members that stand) [-], and the
        5-95 % band of the largest top displacement of every member, ``top_displacement_p05_m`` and
        ``top_displacement_p95_m`` [m, the specimen's].
    """

    tasks = [(scenario, design, m) for m in specimen_members(scenario, design, tolerances, members, seed)]
    if workers or scheduler is not None:
        out = _map_on_dask(_member_outcome, tasks, scheduler, workers, tick)
    else:
        out = map_threads(_member_outcome, tasks, scenario.simulation.threads, done=tick)
    col = np.array([c for c, _ in out], dtype=float)
    top = np.array([t for _, t in out], dtype=float)
    ok = np.isfinite(col)
    collapsed = col[ok] == 1.0
    k = int(np.sum(collapsed == bool(prototype_collapsed)))
    p = k / int(ok.sum()) if ok.any() else math.nan
    lo, hi = wilson_interval(k, int(ok.sum()), scenario.verdict.confidence) if ok.any() else (None, None)
    stand = top[ok][~collapsed]
    spread = float(np.std(stand, ddof=1) / np.median(stand)) if stand.size >= 2 else None
    tops = top[ok & np.isfinite(top)]
    p05, p95 = (float(x) for x in np.quantile(tops, [0.05, 0.95])) if tops.size else (None, None)
    return {
        "members": int(ok.sum()),
        "trials": int(ok.sum()),
        "agree_count": k,
        "p_outcome_agree": p,
        "p_outcome_agree_low": lo,
        "p_outcome_agree_high": hi,
        "specimen_collapse_probability": float(np.mean(collapsed)) if ok.any() else math.nan,
        "first_peak_spread": spread,
        "top_displacement_p05_m": p05,
        "top_displacement_p95_m": p95,
    }


def outcome_odds_text(odds, confidence: float = 0.95) -> str:
    """The odds that the outcome agrees, in words with their Wilson interval
    (:func:`~blastscale.analysis.intervals.odds_text`, e.g. "P >= 0.68 (95 %, 8 of 8)"), of an :class:`Odds`'
    dict or an :func:`ensemble_odds_3d` dict (``agree_count`` of ``trials``); "-" for None or no trial."""
    if not odds or not odds.get("trials"):
        return "-"
    return odds_text(int(odds["agree_count"]), int(odds["trials"]), confidence)


def _map_on_dask(fn, items: list, scheduler: Optional[str], workers: int, tick=None) -> list:
    """``[fn(x) for x in items]`` on a Dask ``scheduler`` or, without one, ``workers`` local worker processes (one
    item per task); ``tick(done)`` as each completes, in order."""
    distributed = require("dask.distributed", "sweeps", "a 3D ensemble on Dask workers")
    cluster = None
    if scheduler is None:
        with warnings.catch_warnings():  # the scheduler's HTTP (health) server takes another port when 8787 is busy
            warnings.filterwarnings("ignore", message="Port .* is already in use", category=UserWarning)
            cluster = distributed.LocalCluster(
                n_workers=int(workers), threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
            )
        client = distributed.Client(cluster)
    else:
        try:
            client = distributed.Client(scheduler, timeout="20s")
        except (OSError, TimeoutError) as exc:
            raise BlastscaleInputError(f"scheduler = {scheduler!r} cannot be reached: {exc}") from None
    try:
        out = []
        for fut in client.map(fn, items, pure=False):
            out.append(fut.result())
            if tick is not None:
                tick(len(out))
        return out
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
