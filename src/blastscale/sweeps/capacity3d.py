"""Capacity of any structure in 3D: the critical charge at a stand-off by bisection on ensembles of 3D
runs, and the pressure-impulse diagram from several stand-offs (docs/capacity.md, "Any structure: 3D").

The critical charge W_c(R) of a structure the planar criterion cannot judge (a column, a wall, an arch, a
block model) is the charge at which its **collapse probability crosses 50 %**; collapse is "a body fell"
(the fall rule of :func:`blastscale.sim3d.record.fallen_flags`: a body's centre of mass dropped by half its
own height or it turned by 45 deg, at any time of the run). Chaos (a circular column wobbles: 1e-10 in the
load moves its history by tens of per cent) is handled as the study's ensembles handle it: at each probed
charge W, ``members`` runs under the load times ``1 + perturbation u_k`` (u_k evenly spread over [-1, 1],
:func:`blastscale.analysis.ensemble.member_factors`) give the fall fraction k / n.

Search, per stand-off, in ln W:

1. **Bracket** (stated in the result): from a given bracket [W_lo, W_hi] (checked: fraction < 1/2 at W_lo,
   >= 1/2 at W_hi), or from the scenario's charge by steps of x2 (down while the fraction is >= 1/2, up while
   it is < 1/2) inside the blast fits' range of scaled distance Z (:func:`~blastscale.blast.inverse.scaled_distance_range`);
   a structure that falls (stands) at the range's end is an error naming it.
2. **Stochastic bisection**: the geometric midpoint is probed; a fraction >= 1/2 moves the upper end, else
   the lower, until W_hi / W_lo <= 1 + ``tolerance``.
3. **The 50 % crossing and its interval**: every probe's counts (W_j, k_j, n) are fitted by the lognormal
   fragility ``P = Phi(ln(W / theta) / beta)`` by maximum likelihood
   (:func:`~blastscale.sweeps.fragility.fit_lognormal_fragility`, the package's one fit): theta is the
   critical charge and its 95 % bounds the interval. When the probes separate the outcomes completely (every
   member stands at every probe below some charge and falls at every probe above: a structure that is not
   chaotic there, or an ensemble too small to see its chaos) the likelihood has no maximum: the critical
   charge is the geometric mean of the final bracket and the interval the bracket itself, within which the
   50 % crossing lies (``interval_basis`` says which). When the fit's bounds are open (too few members to
   bound them) the interval is also the bracket, and ``interval_basis`` says so: run more members.

The probes of all stand-offs run together, round by round (one probe per stand-off per round, all their
members at once) on the project's parallel runs (:func:`blastscale._threads.map_threads`: MuJoCo releases the
GIL, results bitwise those of a serial loop), each run the Study's own prototype system at that charge and
stand-off (:meth:`blastscale.study.Study.check`: the scenario's structure, contact, duration, load method and
load model). The pressure-impulse diagram is the reflected pressure and impulse at each (W_c(R), R).

A block's planar path (``blastscale critical`` / ``capacity`` of a block: the first-swing criterion, exact and
fast) is the same command's instance for a block (docs/capacity.md); ``--engine 3d`` runs a block here too.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np

from .._threads import map_threads
from .._validate import BlastscaleInputError, check_positive, check_range
from ..analysis.ensemble import member_factors
from ..analysis.intervals import wilson_interval
from ..analysis.systems import run_system
from ..blast.inverse import scaled_distance_range
from ..blast.parameters import blast_parameters, model_for_burst
from ..study.study import Study
from .fragility import fit_lognormal_fragility

__all__ = [
    "Critical3D",
    "Probe",
    "critical_charges_3d",
    "pressure_impulse_points",
    "DEFAULT_TOLERANCE",
    "DEFAULT_MEMBERS",
    "STEP_FACTOR",
]

#: Relative width of the final bracket, W_hi / W_lo - 1 [-]: 2 %, well inside the +-5 % within which
#: direct runs must confirm the result (issue #38's acceptance).
DEFAULT_TOLERANCE = 0.02
#: Ensemble members per probed charge when neither the caller nor the scenario's
#: ``simulation.ensemble_members`` says (the paper's circular-column scenarios use 4).
DEFAULT_MEMBERS = 4
#: Factor of each bracketing step [-].
STEP_FACTOR = 2.0


@dataclass(frozen=True)
class Probe:
    """One probed charge: ``charge_kg`` [kg], ``members`` run, ``fell`` of them (a body fell)."""

    charge_kg: float
    members: int
    fell: int

    @property
    def fraction(self) -> float:
        """Fall fraction k / n [-]."""
        return self.fell / self.members

    def to_dict(self) -> dict:
        """Plain dict, with the fraction's 95 % Wilson interval."""
        lo, hi = wilson_interval(self.fell, self.members)
        return {
            "charge_kg": self.charge_kg,
            "members": self.members,
            "fell": self.fell,
            "fraction": self.fraction,
            "fraction_interval_95": [lo, hi],
        }


@dataclass(frozen=True)
class Critical3D:
    """The 3D critical charge at one stand-off (module docstring) [SI].

    Attributes
    ----------
    standoff_m : float
        Stand-off R [m].
    critical_charge_kg : float or None
        The charge at which the collapse probability crosses 50 % [kg]; None when the search failed (``note``).
    interval_kg : tuple or None
        Its interval [kg] (``interval_basis``).
    interval_basis : str
        "lognormal fit, 95 %" or "bisection bracket" (why in ``note``).
    bracket_kg : tuple or None
        The final bracket (fraction < 1/2 at its lower end, >= 1/2 at its upper) [kg].
    initial_bracket_kg : tuple or None
        The bracket the bisection started from (given, or found by steps of x2) [kg].
    probes : tuple of Probe
        Every probed charge, in the order probed.
    beta : float or None
        The fitted lognormal dispersion [-] (None: not estimable).
    note : str
        Why the interval is the bracket, or why the search failed.
    """

    standoff_m: float
    critical_charge_kg: Optional[float]
    interval_kg: Optional[tuple]
    interval_basis: str
    bracket_kg: Optional[tuple]
    initial_bracket_kg: Optional[tuple]
    probes: tuple
    beta: Optional[float] = None
    note: str = ""

    @property
    def runs(self) -> int:
        """3D runs made [-]."""
        return sum(p.members for p in self.probes)

    def to_dict(self) -> dict:
        """Plain dict (lists; None where absent)."""
        lst = lambda t: None if t is None else [float(x) for x in t]
        return {
            "standoff_m": self.standoff_m,
            "critical_charge_kg": self.critical_charge_kg,
            "interval_kg": lst(self.interval_kg),
            "interval_basis": self.interval_basis,
            "bracket_kg": lst(self.bracket_kg),
            "initial_bracket_kg": lst(self.initial_bracket_kg),
            "beta": self.beta,
            "runs": self.runs,
            "probes": [p.to_dict() for p in self.probes],
            "note": self.note,
        }


@dataclass
class _Search:
    """The bisection at one stand-off as a state machine: :meth:`pending` charges to probe, :meth:`tell` their
    counts (module docstring)."""

    standoff: float
    w_range: tuple  # (W_min, W_max) [kg]: the blast fits' range of Z at this stand-off
    start: float
    tolerance: float
    given: Optional[tuple] = None
    probes: list = field(default_factory=list)
    lo: Optional[float] = None
    hi: Optional[float] = None
    initial: Optional[tuple] = None
    failed: str = ""
    _next: list = field(default_factory=list)

    def __post_init__(self):
        self._next = list(self.given) if self.given is not None else [self.start]

    @property
    def done(self) -> bool:
        return bool(self.failed) or (not self._next and self._bracketed() and self.hi / self.lo <= 1 + self.tolerance)

    def _bracketed(self) -> bool:
        return self.lo is not None and self.hi is not None

    def pending(self) -> list:
        """The charges [kg] to probe in this round (empty when done)."""
        if self.done:
            return []
        if not self._next and self._bracketed():
            self._next = [math.sqrt(self.lo * self.hi)]
        return list(self._next)

    def tell(self, results: dict) -> None:
        """The counts of this round: charge -> (fell, members)."""
        charges, self._next = self._next, []
        for w in charges:
            k, n = results[w]
            self.probes.append(Probe(float(w), int(n), int(k)))
        if self.given is not None and self.initial is None:
            self._check_given()
            return
        (w,) = charges
        falls = self.probes[-1].fraction >= 0.5
        if falls:
            self.hi = w
        else:
            self.lo = w
        if self._bracketed():
            if self.initial is None:
                self.initial = (self.lo, self.hi)
            return
        wmin, wmax = self.w_range
        nxt = max(w / STEP_FACTOR, wmin) if falls else min(w * STEP_FACTOR, wmax)
        if nxt == w:
            self.failed = (
                f"a body falls in at least half the members down to {w:.6g} kg (the blast fits' largest Z)"
                if falls
                else f"every body stands in more than half the members up to {w:.6g} kg (the blast fits' smallest Z)"
            )
            return
        self._next = [nxt]

    def _check_given(self) -> None:
        a, b = self.probes[-2], self.probes[-1]
        if a.fraction >= 0.5 or b.fraction < 0.5:
            self.failed = (
                f"bracket = [{a.charge_kg:.6g}, {b.charge_kg:.6g}] kg does not bracket the crossing: fall fractions "
                f"{a.fell}/{a.members} and {b.fell}/{b.members} (need < 1/2 at the lower end, >= 1/2 at the upper)"
            )
            return
        self.lo, self.hi = a.charge_kg, b.charge_kg
        self.initial = (self.lo, self.hi)

    def result(self) -> Critical3D:
        """The critical charge, its interval and the probes (module docstring, step 3)."""
        probes = tuple(self.probes)
        if self.failed:
            return Critical3D(self.standoff, None, None, "", None, self.initial, probes, None, self.failed)
        W = np.array([p.charge_kg for p in probes])
        k = np.array([p.fell for p in probes])
        n = np.array([p.members for p in probes])
        fit = fit_lognormal_fragility(W, k, n)  # never all 0 or all n: the bracket has both sides
        bracket = (self.lo, self.hi)
        if fit.beta is not None and fit.bounded:
            return Critical3D(
                self.standoff,
                fit.median_charge_kg,
                tuple(fit.median_ci_kg),
                "lognormal fit, 95 %",
                bracket,
                self.initial,
                probes,
                fit.beta,
            )
        why = (
            "every member stands at every probe below the bracket and falls at every probe above it: the 50 % "
            "crossing lies inside the bracket (no dispersion to fit)"
            if fit.beta is None
            else "the lognormal fit's 95 % bounds are open (too few members): the interval is the bisection "
            "bracket, where the members' fall fraction crosses 1/2; run more members for a fitted interval"
        )
        return Critical3D(
            self.standoff,
            math.sqrt(self.lo * self.hi),
            bracket,
            "bisection bracket",
            bracket,
            self.initial,
            probes,
            fit.beta,
            why,
        )


def _prototype_only(scenario):
    """The scenario's prototype alone in 3D (no [scale], no ensemble of the study's own: the members are ours)."""
    sc = scenario.with_values({"simulation.engine": "3d", "simulation.ensemble_members": 0})
    return sc.model_copy(update={"scale": None}) if sc.scale is not None else sc


def critical_charges_3d(
    scenario,
    standoffs,
    *,
    bracket: Optional[tuple] = None,
    members: Optional[int] = None,
    tolerance: float = DEFAULT_TOLERANCE,
    threads: Optional[int] = None,
    progress: Optional[Callable[[int, int], None]] = None,
) -> tuple:
    """The 3D critical charge of the scenario's prototype at each stand-off (module docstring).

    Parameters
    ----------
    scenario : Scenario
        The structure, its contact, the duration of each run (``simulation.duration_s``: long enough for a body
        to fall), the load method, pulse shape and load model, the ensembles' ``simulation.ensemble_perturbation``.
        Its charge starts the bracket search; its ``[scale]`` is not used.
    standoffs : array_like
        Stand-offs R [m], > 0.
    bracket : (float, float), optional
        Charges [W_lo, W_hi] [kg], 0 < W_lo < W_hi, used at every stand-off (default: searched by steps of x2
        from the scenario's charge).
    members : int, optional
        Ensemble members per probed charge, 1-64 (default: ``simulation.ensemble_members`` when >= 2, else
        :data:`DEFAULT_MEMBERS`).
    tolerance : float
        Final bracket's relative width W_hi / W_lo - 1, in [1e-4, 1] (default :data:`DEFAULT_TOLERANCE`).
    threads : int, optional
        Runs in flight at once (:mod:`blastscale._threads`; default: the scenario's ``simulation.threads``, else the
        cores); the results do not depend on it.
    progress : callable, optional
        ``progress(runs_done, round)`` after each round.

    Returns
    -------
    tuple of Critical3D
        One per stand-off, in their order.
    """
    R = np.atleast_1d(check_positive("standoffs", standoffs, "m")).astype(float)
    check_range("tolerance", tolerance, 1e-4, 1.0)
    n = members_of(scenario, members)
    if bracket is not None:
        lo, hi = (float(x) for x in check_positive("bracket", bracket, "kg"))
        if not lo < hi:
            raise BlastscaleInputError(f"bracket = [{lo:g}, {hi:g}] kg is out of range: the lower end must be smaller")
        bracket = (lo, hi)
    base = _prototype_only(scenario)
    bl = base.blast
    zlo, zhi = scaled_distance_range(model_for_burst(bl.blast_model, bl.burst), bl.extrapolate)
    searches = []
    for r in R:
        wr = ((r / zhi) ** 3, (r / zlo) ** 3)
        start = min(max(float(bl.charge_kg), wr[0]), wr[1])
        searches.append(_Search(float(r), wr, start, float(tolerance), bracket))
    factors = member_factors(n, base.simulation.ensemble_perturbation)
    threads = threads if threads is not None else base.simulation.threads
    done_runs, rounds = 0, 0
    while True:
        asked = [(j, w) for j, s in enumerate(searches) for w in s.pending()]
        if not asked:
            break
        systems = {(j, w): _system(base, w, searches[j].standoff) for j, w in asked}
        tasks = [(key, f) for key in systems for f in factors]
        fell = map_threads(lambda t: _fell(systems[t[0]], t[1]), tasks, threads)
        counts: dict = {}
        for (key, _), f in zip(tasks, fell):
            k, m = counts.get(key, (0, 0))
            counts[key] = (k + int(f), m + 1)
        for j in sorted({j for j, _ in asked}):
            searches[j].tell({w: counts[(j, w)] for w in searches[j]._next})
        done_runs += len(tasks)
        rounds += 1
        if progress is not None:
            progress(done_runs, rounds)
    return tuple(s.result() for s in searches)


def planned_probes(bracket: Optional[tuple] = None, tolerance: float = DEFAULT_TOLERANCE) -> int:
    """Probed charges per stand-off [-]: exactly, with a ``bracket`` [kg] (its two ends, then the bisection of
    ln(HI / LO) down to ln(1 + ``tolerance``)); without one, the fewest (two steps of x2 that bracket, then the
    bisection of ln 2), the size said before a search starts."""
    width = math.log(bracket[1] / bracket[0]) if bracket is not None else math.log(STEP_FACTOR)
    halvings = max(0, math.ceil(math.log2(width / math.log1p(tolerance)))) if width > math.log1p(tolerance) else 0
    return 2 + halvings


def members_of(scenario, members: Optional[int]) -> int:
    """Ensemble members per probed charge [-]: ``members`` (checked, 1-64), else the scenario's
    ``simulation.ensemble_members`` when >= 2, else :data:`DEFAULT_MEMBERS`."""
    if members is None:
        given = scenario.simulation.ensemble_members
        return int(given) if given >= 2 else DEFAULT_MEMBERS
    if isinstance(members, bool) or not isinstance(members, (int, np.integer)) or not 1 <= members <= 64:
        raise BlastscaleInputError(f"members = {members!r} is out of range: valid range is whole numbers 1-64")
    return int(members)


def _system(base, charge: float, standoff: float):
    """The prototype system of the scenario at ``charge`` [kg] and ``standoff`` [m], with the study's settings:
    (System3D, Settings3D) from :meth:`blastscale.study.Study.check` (built in the calling thread)."""
    plan = Study(base.with_values({"blast.charge_kg": float(charge), "blast.standoff_m": float(standoff)})).check()
    return plan.systems3d.prototype, plan.settings3d


def _fell(system_settings, factor: float) -> bool:
    """Whether a body fell in the run under the load times ``factor``."""
    system, settings = system_settings
    return run_system(system, settings, factor).response.bodies_summary()["fallen_blocks"] > 0


def pressure_impulse_points(scenario, results) -> dict:
    """The P-I diagram's points: the reflected pressure [Pa] and impulse [Pa s] at each (W_c(R), R) of
    ``results`` (:class:`Critical3D`), with those at the ends of each interval (None where the search failed)."""
    bl = _prototype_only(scenario).blast

    def at(w, r):
        if w is None:
            return None, None
        bp = blast_parameters(w, r, bl.blast_model, extrapolate=bl.extrapolate, burst=bl.burst)
        return float(bp.reflected_pressure), float(bp.reflected_impulse)

    out = {
        k: []
        for k in ("reflected_pressure_Pa", "reflected_impulse_Pa_s", "interval_pressure_Pa", "interval_impulse_Pa_s")
    }
    for c in results:
        p, i = at(c.critical_charge_kg, c.standoff_m)
        out["reflected_pressure_Pa"].append(p)
        out["reflected_impulse_Pa_s"].append(i)
        ends = [at(w, c.standoff_m) for w in (c.interval_kg or (None, None))]
        out["interval_pressure_Pa"].append(None if ends[0][0] is None else [e[0] for e in ends])
        out["interval_impulse_Pa_s"].append(None if ends[0][0] is None else [e[1] for e in ends])
    return out
