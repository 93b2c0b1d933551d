"""One pressure-gauge trace -> its blast pulse: baseline, arrival, Friedlander fit, impulse, negative phase.

The steps (docs/fired.md), on plain arrays in SI:

1. **Baseline**: a straight line ``b0 + b1 t`` fitted by least squares to the pre-trigger samples (t < 0)
   is the gauge's offset and drift (a charge amplifier's leakage, a thermal drift: linear over a record's
   milliseconds); it is removed from the whole record, and the residuals' standard deviation sigma is the
   noise. The line's covariance ``s^2 (X^T X)^-1`` (X = [1, t]) gives the drift's interval and, integrated over
   the positive phase, the baseline's part of the impulse's uncertainty. The slope is kept when it differs
   from zero at 95 % (``|b1| > 1.96 sigma_b1``), else the line is the samples' mean (a slope the record does
   not resolve would add its noise, not remove a drift), and the covariance is the line's plus the left-out
   slope's error (``u u^T``, u = b1 [-t_mean, 1]: the mean-squared error of the baseline). **The
   record's tail** (its last :data:`TAIL_FRACTION` in time), when it lies :data:`TAIL_AFTER` positive
   durations past the arrival (the pulse found on the trace baselined by the line through the pre-trigger and
   the tail), checks the pre-trigger's line: the tail's mean offset from it within :data:`TAIL_AGREEMENT`
   standard errors (the noise's and the line's at the tail, floored at the samples' resolution, one unit in
   the last place of the largest sample: a noiseless record has neither), the line through the pre-trigger
   and the tail together is the baseline (the tail's lever arm pins the slope); beyond, the drift is not
   linear, the pre-trigger's line is kept, the tail's offset enters the uncertainty (as a drift growing
   linearly from the firing signal to the tail) and a warning names the gauge. A tail still inside the negative
   phase (the trace, baselined by the pre-trigger's line, has not come back within the check's tolerance of
   zero after its deepest suction) cannot tell a drift from the suction: it checks nothing, the pre-trigger's
   line is kept and a note says so (the negative phase lasts 2.5-5.4 positive durations at Z = 1-30 and ~38 at
   Z = 0.5: a tail a few durations after the pulse can lie in it).
2. **Arrival**: the first sample after the firing signal whose baselined value exceeds the threshold
   ``max(ARRIVAL_NOISE_MULTIPLE sigma, ARRIVAL_PEAK_FRACTION max)``; the shock lies between it and the
   sample before, and the arrival time is their midpoint (error <= half a sample interval; uniform over the
   interval: standard deviation dt / sqrt 12). A shock is a jump within one sample (Kinney & Graham 1985,
   ch. 6), so the fraction rule does not lag it.
3. **Friedlander fit**: ``p(tau) = P (1 - tau/t_o) exp(-d tau/t_o)``, tau = t - t_a (paper Eq. 1; Baker
   et al. 1983), by least squares (scipy ``least_squares``, trust-region reflective) on the samples from
   the arrival to the first zero crossing of the smoothed trace (smoothed over a fiftieth of the record after
   the arrival, then again over a twentieth of the pulse so found, within half the first width before the first
   crossing: a long record's wide smoothing crosses zero late, by ~0.15 of its width where the suction is
   shallower than the pulse's fall), the fit's parameters with 95 %
   confidence intervals from the Jacobian: ``cov = s^2 (J^T J)^-1``, ``s^2`` the residual variance
   (independent residuals assumed: gauge ringing makes them correlated and the intervals optimistic;
   Rigby et al. 2014, "Friedlander fits to near-field records", discuss the bias of fitting near the front).
4. **Impulse**: the fitted pulse's impulse from the arrival to the first sample after the shock (a straight
   line from the sample before the shock would halve the pressure there: P dt / 8 too little on average), the
   trapezoidal integral of the baselined samples from there while the fitted pulse stands above the noise
   sigma, less the trapezoidal rule's error on the fitted pulse sampled at the same times (its bias on a
   curved pulse, ``(1 + d - e^-d) d^2 / (12 N^2 (d - 1 + e^-d))``), plus the fitted pulse's own impulse from
   there to its end (the samples give the area where they carry it; the fit the tail, where integrating
   noise and the baseline's error over an ill-determined end would only add error: near the charge, d ~
   10-30 and t_o is poorly determined while d/t_o is not).
5. **Negative phase** (when the record holds it): the least pressure and the integral of the samples
   after the positive phase up to the smoothed trace's return to zero or the record's end.
6. **The impulse's uncertainty**: the 95 % half-width of the impulse from the samples' noise integrated over
   the samples' part of step 4 (``sigma dt sqrt(n)``, white noise), the baseline line's error integrated
   over it (``g^T C g``, g = [t2 - t1, (t2^2 - t1^2)/2], C the line's covariance) and the shock's position
   between its two samples (the pulse after the first sample is the same wherever it lies, so the area
   ``P x (its offset from the midpoint)`` is unknown: ``P dt / sqrt 12``; 1-2 % of the impulse at 100-400
   samples over t_o for d = 6-15, the largest term of a clean record), in quadrature. The peak's interval
   holds the same position's term, the pulse's slope ``(1 + d) P / t_o`` times ``dt / sqrt 12``, with the
   fit's. Over synthetic records (tests/unit/fired/test_gauge_interval.py) the truth lies inside the impulse's
   interval in 119 of 120 and the peak's in 119 of 120 (17 % and 11 % without the position's term). A record whose
   baseline alone makes the impulse uncertain by more than :data:`DRIFT_WARNING_FRACTION` (95 %), or whose
   tail disagrees with its line, gets a warning naming the gauge: 2 % on the impulse is ~3 % on the effective
   charge (W ~ i^(3/2) at Z ~ 1-10: i ~ W^(2/3) at a fixed distance... the inversion's own slope) and ~6 %
   on a rocking first peak (~W^2), beyond what the charge's other errors add.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from ..analysis.intervals import Z95
from ..blast.friedlander import friedlander_impulse_ratio
from ..blast.pulses import Friedlander
from .records import record_fault

__all__ = [
    "DRIFT_WARNING_FRACTION",
    "GaugeDriftWarning",
    "TAIL_AFTER",
    "TAIL_FRACTION",
    "TAIL_AGREEMENT",
    "ARRIVAL_NOISE_MULTIPLE",
    "ARRIVAL_PEAK_FRACTION",
    "MIN_PRETRIGGER",
    "MIN_PULSE_SAMPLES",
    "GaugeFit",
    "fit_gauge",
    "friedlander_trace",
]

#: Arrival threshold: the trace must exceed this many pre-trigger standard deviations ...
ARRIVAL_NOISE_MULTIPLE = 10.0
#: ... and this fraction of its largest baselined value.
ARRIVAL_PEAK_FRACTION = 0.25
#: Fewest pre-trigger samples for a baseline; fewest samples over the positive phase for a fit.
MIN_PRETRIGGER = 10
MIN_PULSE_SAMPLES = 20


class GaugeDriftWarning(UserWarning):
    """A gauge whose baseline (its drift) makes the impulse unreliable (:data:`DRIFT_WARNING_FRACTION`)."""


#: A warning names a gauge whose baseline alone makes its impulse uncertain by more than this fraction (95 %).
DRIFT_WARNING_FRACTION = 0.02
#: The record's tail is its last tenth in time ...
TAIL_FRACTION = 0.1
#: ... when it starts this many positive durations after the arrival and after the trace's return from its negative
#: phase (which lasts 2.5-5.4 positive durations over Z = 1-30 m/kg^(1/3) and ~38 at Z = 0.5: Rigby's calibration of
#: UFC 3-340-02 Fig. 2-16, :mod:`blastscale.blast.negative_phase`, against Kingery-Bulmash's t_o; so the pulse's
#: length alone does not place the tail past it) ...
TAIL_AFTER = 5.0
#: ... and agrees with the pre-trigger's baseline line within this many standard errors.
TAIL_AGREEMENT = 3.0


def friedlander_trace(tau, peak, duration, decay):
    """The Friedlander form ``P (1 - tau/t_o) exp(-d tau/t_o)`` [Pa] at tau [s] after arrival (0 before;
    continued past t_o, where it is negative: the fit's model). Paper Eq. (1)."""
    tau = np.asarray(tau, dtype=float)
    x = np.clip(tau, 0.0, None) / duration  # before the arrival the form is not evaluated (exp would overflow)
    return np.where(tau >= 0, peak * (1.0 - x) * np.exp(-decay * x), 0.0)


@dataclass(frozen=True)
class GaugeFit:
    """What one gauge measured (SI).

    Attributes
    ----------
    name : str
    baseline_Pa, noise_Pa : float
        Pre-trigger mean (removed) and standard deviation [Pa].
    arrival_time_s : float
        Shock arrival after the firing signal [s].
    peak_pressure_Pa, positive_duration_s, decay : float
        Friedlander fit P [Pa], t_o [s], d [-].
    ci95 : dict
        ``peak_pressure_Pa``, ``positive_duration_s``, ``decay`` -> half-width of the 95 % interval.
    impulse_Pa_s : float
        Integral of the samples over the positive phase [Pa s].
    fit_impulse_Pa_s : float
        The fitted pulse's impulse ``P t_o (e^-d + d - 1)/d^2`` [Pa s] (paper Eq. 2).
    negative_pressure_Pa, negative_impulse_Pa_s : float or None
        The negative phase's least pressure [Pa] (< 0) and its impulse [Pa s] (< 0); None when the record
        ends before it.
    samples_positive : int
        Samples over the fitted positive phase.
    drift_Pa_per_s, ci95_drift_Pa_per_s : float
        The baseline line's slope b1 [Pa/s] (removed) and its 95 % half-width.
    drift_impulse_Pa_s : float
        The impulse the removed drift would have added over the positive phase, ``b1 (t2^2 - t1^2)/2`` [Pa s]
        (t from the firing signal).
    ci95_impulse_Pa_s : float
        95 % half-width of the impulse [Pa s]: the samples' noise and the baseline's error (step 6).
    baseline_from : str
        ``"pre-trigger"`` or ``"pre-trigger and tail"`` (the line's samples).
    tail_offset_Pa : float or None
        The record's tail's mean offset from the pre-trigger's line [Pa]; None without a tail.
    warnings : tuple of str
        One line per reason the impulse is unreliable (each naming the gauge).
    """

    name: str
    baseline_Pa: float
    noise_Pa: float
    arrival_time_s: float
    peak_pressure_Pa: float
    positive_duration_s: float
    decay: float
    ci95: dict
    impulse_Pa_s: float
    fit_impulse_Pa_s: float
    negative_pressure_Pa: float | None
    negative_impulse_Pa_s: float | None
    samples_positive: int
    drift_Pa_per_s: float = 0.0
    ci95_drift_Pa_per_s: float = 0.0
    drift_impulse_Pa_s: float = 0.0
    ci95_impulse_Pa_s: float = 0.0
    baseline_from: str = "pre-trigger"
    tail_offset_Pa: float | None = None
    warnings: tuple = ()

    def pressure(self, t):
        """The fitted pulse [Pa] at times ``t`` [s] after the firing signal (0 outside the positive phase)."""
        tau = np.asarray(t, dtype=float) - self.arrival_time_s
        p = friedlander_trace(tau, self.peak_pressure_Pa, self.positive_duration_s, self.decay)
        return np.where(tau <= self.positive_duration_s, p, 0.0)

    def to_dict(self) -> dict:
        return {
            "peak_pressure_Pa": self.peak_pressure_Pa,
            "impulse_Pa_s": self.impulse_Pa_s,
            "arrival_time_s": self.arrival_time_s,
            "positive_duration_s": self.positive_duration_s,
            "decay": self.decay,
            "fit_impulse_Pa_s": self.fit_impulse_Pa_s,
            "baseline_Pa": self.baseline_Pa,
            "noise_Pa": self.noise_Pa,
            "negative_pressure_Pa": self.negative_pressure_Pa,
            "negative_impulse_Pa_s": self.negative_impulse_Pa_s,
            "ci95_peak_pressure_Pa": self.ci95["peak_pressure_Pa"],
            "ci95_positive_duration_s": self.ci95["positive_duration_s"],
            "ci95_decay": self.ci95["decay"],
            "samples_positive": self.samples_positive,
            "drift_Pa_per_s": self.drift_Pa_per_s,
            "ci95_drift_Pa_per_s": self.ci95_drift_Pa_per_s,
            "drift_impulse_Pa_s": self.drift_impulse_Pa_s,
            "ci95_impulse_Pa_s": self.ci95_impulse_Pa_s,
            "baseline_from": self.baseline_from,
            "tail_offset_Pa": self.tail_offset_Pa,
            "warnings": list(self.warnings),
        }


def _smooth(y: np.ndarray, k: int) -> np.ndarray:
    if k <= 1:
        return y
    return np.convolve(y, np.ones(k) / k, mode="same")


def _impulse(t: np.ndarray, p: np.ndarray, t0: float, t1: float) -> float:
    """Trapezoidal integral of the samples between t0 and t1 [s], the ends linearly interpolated."""
    inside = (t > t0) & (t < t1)
    tt = np.concatenate(([t0], t[inside], [t1]))
    pp = np.concatenate(([np.interp(t0, t, p)], p[inside], [np.interp(t1, t, p)]))
    return float(np.trapezoid(pp, tt)) if hasattr(np, "trapezoid") else float(np.trapz(pp, tt))


def fit_gauge(time_s, pressure_Pa, name: str = "gauge", *, source: str = "gauges", column: str = "") -> GaugeFit:
    """Process one gauge trace (steps in the module docstring).

    Parameters
    ----------
    time_s : array_like
        Sample times [s], increasing, zero at the firing signal, some before it.
    pressure_Pa : array_like
        The gauge's signal [Pa], baseline included.
    name : str
        The gauge's name (results and messages).
    source, column : str
        File and column named by the error messages.

    Returns
    -------
    GaugeFit

    Raises
    ------
    BlastscaleInputError
        Too few pre-trigger samples, no arrival above the threshold, or too few samples over the positive
        phase (one line naming the file, the column and the rows).

    Notes
    -----
    A noiseless record (zero scatter) gets the uncertainties its data give: 0 from the noise and the baseline,
    no floor added; only the tail check's standard error is floored, at the samples' resolution (step 1).
    """
    t = np.asarray(time_s, dtype=float)
    raw = np.asarray(pressure_Pa, dtype=float)
    where = (source, column or name)
    pre = _pretrigger(t, where)
    line, steps, tail, offset, se, notes = _baseline(t, raw, pre, name, where)
    agrees = offset is not None and abs(offset) <= TAIL_AGREEMENT * se
    ia, ta, fit, neg_p, neg_i, _, (impulse, sampled_end) = steps
    t_end = ta + fit.duration
    window = (ta, sampled_end)
    dt = float(np.median(np.diff(t[ia : ia + 50]))) if t.size > ia + 2 else 0.0
    n_pos = int(np.count_nonzero((t >= ta) & (t <= t_end)))
    n_sampled = int(np.count_nonzero((t >= ta) & (t <= sampled_end)))
    s_noise = line.noise * dt * math.sqrt(max(n_sampled, 1))
    s_base = line.integral_sigma(*window)
    s_tail = 0.0
    if offset is not None and not agrees:
        t_tail = float(t[tail].mean())
        s_tail = abs(offset) * (window[1] ** 2 - window[0] ** 2) / (2.0 * t_tail)
        notes.append(
            f"gauge {name!r}: the record's tail sits {offset:.4g} Pa off the pre-trigger's baseline line "
            f"({abs(offset) / se:.3g} standard errors, more than {TAIL_AGREEMENT:g}): the drift is not linear and "
            "the impulse is unreliable"
        )
    # the shock lies anywhere between the last sample before it and the first after (uniformly): the arrival, taken
    # at their midpoint, is off by up to half that interval, the impulse by the pressure behind the shock times
    # that (the samples cannot tell: the pulse after the first sample is the same), the peak by its slope times it
    h = float(t[ia] - t[ia - 1]) / math.sqrt(12.0)  # the arrival's standard error [s]
    s_front = fit.peak * h
    s_front_peak = fit.peak * (1.0 + fit.decay) / fit.duration * h
    half = Z95 * math.sqrt(s_noise**2 + s_base**2 + s_tail**2 + s_front**2)
    base_half = Z95 * math.hypot(s_base, s_tail)
    if base_half > DRIFT_WARNING_FRACTION * impulse:
        notes.append(
            f"gauge {name!r}: the baseline (drift {line.slope:.4g} +- {Z95 * line.slope_sigma:.3g} Pa/s from the "
            f"{line.source}) makes the impulse uncertain by {100 * base_half / impulse:.2g} % (95 %), more than "
            f"{100 * DRIFT_WARNING_FRACTION:g} %: the impulse is unreliable (record a longer pre-trigger or tail)"
        )
    return GaugeFit(
        name=name,
        baseline_Pa=line.offset,
        noise_Pa=line.noise,
        arrival_time_s=float(ta),
        peak_pressure_Pa=float(fit.peak),
        positive_duration_s=float(fit.duration),
        decay=fit.decay,
        ci95={
            "peak_pressure_Pa": float(math.hypot(fit.half[0], Z95 * s_front_peak)),
            "positive_duration_s": float(fit.half[1]),
            "decay": float(fit.half[2]),
        },
        impulse_Pa_s=impulse,
        fit_impulse_Pa_s=float(fit.peak * fit.duration * friedlander_impulse_ratio(fit.decay)),
        negative_pressure_Pa=neg_p,
        negative_impulse_Pa_s=neg_i,
        samples_positive=n_pos,
        drift_Pa_per_s=line.slope,
        ci95_drift_Pa_per_s=Z95 * line.slope_sigma,
        drift_impulse_Pa_s=line.slope * (window[1] ** 2 - window[0] ** 2) / 2.0,
        ci95_impulse_Pa_s=half,
        baseline_from=line.source,
        tail_offset_Pa=offset,
        warnings=tuple(notes),
    )


def _steps(t: np.ndarray, p: np.ndarray, pre: np.ndarray, noise: float, where: tuple):
    """Steps 2-5 on the baselined trace ``p`` [Pa]: (arrival index, arrival [s], the fit, the negative phase's
    least pressure [Pa], impulse [Pa s] and end [s] (None: it runs to the record's end), (the positive impulse
    [Pa s], the end of its sampled part [s]))."""
    ia, ta = _arrival(p, t, pre, noise, where)
    window, sm, k, dt = _positive_window(t, p, ia, where)
    fit = _fit_friedlander(t[window] - ta, p[window], dt)
    neg_p, neg_i, neg_end = _negative_phase(t, p, sm, k, ta + fit.duration, noise)
    return ia, ta, fit, neg_p, neg_i, neg_end, _positive_impulse(t, p, ia, ta, fit, noise)


def _baseline(t: np.ndarray, raw: np.ndarray, pre: np.ndarray, name: str, where: tuple) -> tuple:
    """Step 1: the baseline line and the steps 2-5 on the trace it baselines (:func:`_steps`), the record's tail
    (a mask; None where it checks nothing), its mean offset from the pre-trigger's line [Pa] (None: not
    checked) and that offset's standard error [Pa], and the notes (a tail still in the negative phase)."""
    line = _Line.fit(t, raw, pre)
    tail, offset, se, notes = _tail(t), None, 0.0, []
    if tail is not None:
        both = _Line.fit(t, raw, pre | tail, "pre-trigger and tail")
        trial = _steps(t, raw - both(t), pre, both.noise, where)
        past = t[tail][0] > trial[1] + TAIL_AFTER * trial[2].duration
        se = _tail_error(line, t, tail, raw)
        if past and _still_negative(t, raw - line(t), trial, line.noise, float(t[tail][0]), TAIL_AGREEMENT * se):
            notes.append(
                f"gauge {name!r}: the record's tail is still below the pre-trigger's baseline, in the negative phase "
                "(or a drift): it cannot check the baseline (record longer to check it)"
            )
            past = False
        if past:  # the tail lies past the pulse and its negative phase: it checks
            offset = float((raw[tail] - line(t[tail])).mean())
            if abs(offset) <= TAIL_AGREEMENT * se:  # the line holds to the tail: the line through both (its lever arm)
                return both, trial, tail, offset, se, notes
        else:
            tail = None
    return line, _steps(t, raw - line(t), pre, line.noise, where), tail, offset, se, notes


def _still_negative(t: np.ndarray, p: np.ndarray, steps: tuple, noise: float, t_tail: float, tolerance: float) -> bool:
    """Whether the trace ``p`` [Pa] (baselined by the pre-trigger's line), after the positive phase of ``steps``
    (:func:`_steps`), holds a negative phase that has not come back within ``tolerance`` [Pa] of zero (the tail
    check's own: the line's error grows away from the pre-trigger) by ``t_tail`` [s]."""
    ia, ta, fit = steps[0], steps[1], steps[2]
    k = _smoothing_width(t, ia)
    least, _, back = _negative_phase(t, p, _smooth(p, k), k, ta + fit.duration, noise, -tolerance)
    return least is not None and least < -tolerance and (back is None or back > t_tail)


def _tail_error(line: "_Line", t: np.ndarray, tail: np.ndarray, raw: np.ndarray) -> float:
    """The standard error of the tail's mean offset from ``line`` [Pa]: the noise's over the tail's samples and
    the line's at the tail, in quadrature, floored at the samples' resolution (:func:`_resolution`; on a
    noiseless record both are 0, and a ratio to 0 is no answer)."""
    se = math.hypot(line.noise / math.sqrt(int(tail.sum())), line.sigma_at(float(t[tail].mean())))
    return max(se, _resolution(raw))


def _resolution(raw: np.ndarray) -> float:
    """The resolution of the record's samples [Pa]: one unit in the last place of its largest magnitude
    (float64, ``np.spacing``). The floor of the tail check's standard error: on a noiseless record (zero
    residual scatter) the noise's and the line's errors are 0, and an offset within a few of these units is
    the samples' rounding, not a drift."""
    return float(np.spacing(float(np.max(np.abs(raw)))))


def _tail(t: np.ndarray) -> np.ndarray | None:
    """The record's tail: its last :data:`TAIL_FRACTION` in time (a mask), None when fewer than
    :data:`MIN_PRETRIGGER` samples."""
    tail = t >= t[-1] - TAIL_FRACTION * (t[-1] - t[0])
    return tail if int(tail.sum()) >= MIN_PRETRIGGER else None


@dataclass(frozen=True)
class _Line:
    """The baseline ``b0 + b1 t`` [Pa] and its covariance; ``noise`` the residuals' standard deviation [Pa]."""

    offset: float
    slope: float
    cov: np.ndarray
    noise: float
    source: str

    @classmethod
    def fit(cls, t: np.ndarray, raw: np.ndarray, mask: np.ndarray, source: str = "pre-trigger") -> "_Line":
        """The least-squares line through the samples ``mask``; its slope kept when it differs from zero at 95 %
        (``|b1| > 1.96 sigma_b1``), else the samples' mean (a slope the record does not resolve would add
        its noise, not remove a drift), its covariance then the line's plus the left-out slope's error
        ``u u^T``, u = b1 [-t_mean, 1] (the drift the record cannot exclude enters the impulse's uncertainty)."""
        X = np.column_stack([np.ones(int(mask.sum())), t[mask]])
        coef, *_ = np.linalg.lstsq(X, raw[mask], rcond=None)
        resid = raw[mask] - X @ coef
        s2 = float(resid @ resid) / max(resid.size - 2, 1)
        cov = np.linalg.inv(X.T @ X) * s2
        if abs(coef[1]) <= Z95 * math.sqrt(max(float(cov[1, 1]), 0.0)):
            # the mean is the line of slope 0 through the samples' mean time: it leaves out the fitted slope b1,
            # whose error e(t) = b1 (t - t_mean) joins the covariance (the mean-squared error matrix)
            u = np.array([-coef[1] * float(t[mask].mean()), coef[1]])
            mean = float(raw[mask].mean())
            return cls(mean, 0.0, cov + np.outer(u, u), math.sqrt(s2), source + " (no resolved drift: its mean)")
        return cls(float(coef[0]), float(coef[1]), cov, math.sqrt(s2), source)

    def __call__(self, t):
        return self.offset + self.slope * np.asarray(t, dtype=float)

    @property
    def slope_sigma(self) -> float:
        return math.sqrt(max(float(self.cov[1, 1]), 0.0))

    def sigma_at(self, t: float) -> float:
        """Standard error of the line at ``t`` [s] [Pa]."""
        g = np.array([1.0, t])
        return math.sqrt(max(float(g @ self.cov @ g), 0.0))

    def integral_sigma(self, t1: float, t2: float) -> float:
        """Standard error of the line's integral over [t1, t2] [s] [Pa s]."""
        g = np.array([t2 - t1, 0.5 * (t2**2 - t1**2)])
        return math.sqrt(max(float(g @ self.cov @ g), 0.0))


def _pretrigger(t: np.ndarray, where: tuple) -> np.ndarray:
    """Step 1's samples: the pre-trigger (t < 0); ``where`` = (file, column) for the error of too few."""
    pre = t < 0
    if pre.sum() < MIN_PRETRIGGER:
        raise record_fault(
            *where,
            2,
            f"{int(pre.sum())} pre-trigger samples (t < 0): at least {MIN_PRETRIGGER} are needed for the baseline",
        )
    return pre


def _arrival(p: np.ndarray, t: np.ndarray, pre: np.ndarray, noise: float, where: tuple) -> tuple[int, float]:
    """Step 2: the first sample above the threshold and the arrival time [s], the midpoint between it and the
    sample before."""
    post = np.flatnonzero(~pre)
    thr = max(ARRIVAL_NOISE_MULTIPLE * noise, ARRIVAL_PEAK_FRACTION * float(p[post].max()))
    above = post[p[post] > thr]
    if above.size == 0 or float(p[post].max()) <= 0:
        raise record_fault(
            *where,
            int(post[0]) + 2,
            f"no shock: the trace never rises above {ARRIVAL_NOISE_MULTIPLE:g} x the pre-trigger noise",
        )
    ia = int(above[0])
    return ia, 0.5 * (t[ia] + t[ia - 1])


def _smoothing_width(t: np.ndarray, ia: int) -> int:
    """The first smoothing's width of step 3 [samples]: a fiftieth of the samples after the arrival ``ia``, at
    least 5."""
    return max(5, (t.size - ia) // 50)


def _positive_window(t: np.ndarray, p: np.ndarray, ia: int, where: tuple):
    """The samples of the positive phase: from the arrival ``ia`` to the first zero crossing of the trace
    smoothed over 1/50 of the samples after arrival (at least 5), searched after the largest sample.
    Returns (the window's indices, the smoothed trace, its width k, the sample interval [s] at arrival)."""
    dt = float(np.median(np.diff(t[ia : ia + 50]))) if t.size > ia + 2 else 0.0
    k = _smoothing_width(t, ia)
    sm = _smooth(p, k)
    after = np.arange(ia + int(np.argmax(p[ia : ia + max(k, 3)])), t.size)
    neg = after[sm[after] < 0]
    end_i = int(neg[0]) if neg.size else t.size - 1
    # a record long against its pulse smooths over a good part of it, and the centred average crosses zero late
    # where the suction after the pulse is shallower than the pulse's fall (by ~0.15 k: 10 % of t_o for a record
    # of 30 t_o): once more with the smoothing a twentieth of the first pulse's samples, so the fit's window ends
    # within ~1 % of the pulse's end; sought only within the half-width k / 2 the first crossing can be late by (a
    # steep pulse that has sunk into the noise long before crosses zero anywhere there) and kept only with the
    # samples a fit needs
    k2 = max(5, min(k, (end_i - ia) // 20))
    if k2 < k:
        near = np.arange(max(int(after[0]), end_i - k // 2 - 1), end_i + 1)
        sooner = near[_smooth(p, k2)[near] < 0]
        if sooner.size and sooner[0] - ia + 1 >= MIN_PULSE_SAMPLES:
            end_i = int(sooner[0])
    window = np.arange(ia, end_i + 1)
    if window.size < MIN_PULSE_SAMPLES:
        raise record_fault(
            *where,
            f"{ia + 2}-{end_i + 2}",
            f"{window.size} samples over the pulse: at "
            f"least {MIN_PULSE_SAMPLES} are needed (sample faster or record longer)",
        )
    return window, sm, k, dt


@dataclass(frozen=True)
class _Fit:
    """A fitted Friedlander pulse: peak [Pa], positive duration [s], decay [-] and the 95 % half-widths of the
    three (NaN where the Jacobian is singular)."""

    peak: float
    duration: float
    decay: float
    half: np.ndarray


def _fit_friedlander(tau: np.ndarray, y: np.ndarray, dt: float) -> _Fit:
    """Step 3: the least-squares Friedlander fit of the samples ``y`` [Pa] at ``tau`` [s] after arrival, with
    its confidence intervals (``cov = s^2 (J^T J)^-1``)."""
    P0 = float(np.max(_smooth(y, 3)[: max(3, tau.size // 20)]))
    T0 = max(float(tau[-1]), dt)
    x0 = np.array([1.0, 1.0, 1.0])

    def resid(q):
        return (friedlander_trace(tau, q[0] * P0, q[1] * T0, q[2]) - y) / P0

    sol = least_squares(resid, x0, bounds=([1e-3, 0.2, -0.99], [100.0, 5.0, 50.0]), method="trf", x_scale="jac")
    J = sol.jac * np.array([1.0 / P0, 1.0 / T0, 1.0]) * P0  # d residual[Pa] / d (P, t_o, d)
    dof = max(tau.size - 3, 1)
    s2 = float(np.sum((sol.fun * P0) ** 2)) / dof
    try:
        cov = np.linalg.inv(J.T @ J) * s2
        half = Z95 * np.sqrt(np.clip(np.diag(cov), 0.0, None))
    except np.linalg.LinAlgError:
        half = np.full(3, np.nan)
    return _Fit(sol.x[0] * P0, sol.x[1] * T0, float(sol.x[2]), half)


def _positive_impulse(t: np.ndarray, p: np.ndarray, ia: int, ta: float, fit: _Fit, noise: float) -> tuple[float, float]:
    """Step 4: the fitted pulse's impulse [Pa s] from the arrival ``ta`` [s] to the first sample past the shock
    (``ia``: the shock lies between two samples, and a straight line across it would halve the pressure there),
    the samples' from there while the fitted pulse stands above the noise (trapezoidal, less the trapezoid's
    error on the fitted pulse sampled at the same times: the rule's bias on a curved pulse), the fit's own tail
    after; and the end of the samples' part [s] (what the baseline's error is integrated over)."""
    fine = np.linspace(0.0, fit.duration, 2001)
    low = np.flatnonzero(friedlander_trace(fine, fit.peak, fit.duration, fit.decay) < noise)
    tc = float(fine[low[0]]) if low.size else fit.duration
    pulse = Friedlander(fit.peak, fit.duration, fit.decay)
    end = min(ta + tc, float(t[-1]))
    first = min(float(t[ia]), end)
    front = float(pulse.cumulative_impulse(first - ta))
    upto_end = float(pulse.cumulative_impulse(end - ta))
    on_grid = friedlander_trace(t - ta, fit.peak, fit.duration, fit.decay)
    # the trapezoid's error on the curved pulse ((1 + d - e^-d) d^2 / (12 N^2 (d - 1 + e^-d)) of it for N samples
    # over t_o: planning/instruments.py), taken from the fitted pulse sampled on the same times, off the samples'
    curvature = _impulse(t, on_grid, first, end) - (upto_end - front)
    sampled = _impulse(t, p, first, end) - curvature
    return front + sampled + pulse.impulse - upto_end, end


def _negative_phase(
    t: np.ndarray, p: np.ndarray, sm: np.ndarray, k: int, t_end: float, noise: float, zero: float | None = None
) -> tuple:
    """Step 5: the least pressure [Pa] and the impulse [Pa s] of the samples after the positive phase (ending
    at ``t_end`` [s]) up to the smoothed trace's return to zero after its least value (the smoothing spreads the
    positive phase past its end, and the noise crosses zero where the suction is shallow: the return is sought
    after the deepest point; zero within the smoothed noise, or above ``zero`` [Pa] when given) or the record's
    end, and that return [s] (None at the record's end); (None, None, None) when the record does not hold a
    negative phase above the smoothed noise."""
    tail = np.flatnonzero(t > t_end)
    if tail.size >= MIN_PULSE_SAMPLES and float(sm[tail].min()) < -3.0 * noise / np.sqrt(k):
        deepest = tail[int(np.argmin(sm[tail]))]
        if zero is None:  # zero within the smoothed noise (a noiseless record: its round-off)
            zero = -max(noise / np.sqrt(k), _resolution(p))
        back = tail[(tail > deepest) & (sm[tail] >= zero)]
        stop = float(t[back[0]]) if back.size else float(t[-1])
        return float(sm[deepest]), _impulse(t, p, t_end, stop), stop if back.size else None
    return None, None, None
