"""One pressure-gauge trace -> its blast pulse: baseline, arrival, Friedlander fit, impulse, negative phase.

The steps (docs/fired.md), on plain arrays in SI:

1. **Baseline**: the mean of the pre-trigger samples (t < 0) is the gauge's offset; their standard deviation
   sigma is the noise. Both are removed / used below.
2. **Arrival**: the first sample after the firing signal whose baselined value exceeds the threshold
   ``max(ARRIVAL_NOISE_MULTIPLE sigma, ARRIVAL_PEAK_FRACTION max)``; the shock lies between it and the
   sample before, and the arrival time is their midpoint (error <= half a sample interval). A shock is a
   jump within one sample (Kinney & Graham 1985, ch. 6), so the fraction rule does not lag it.
3. **Friedlander fit**: ``p(tau) = P (1 - tau/t_o) exp(-d tau/t_o)``, tau = t - t_a (paper Eq. 1; Baker
   et al. 1983), by least squares (scipy ``least_squares``, trust-region reflective) on the samples from
   the arrival to the first zero crossing of the smoothed trace, the fit's parameters with 95 %
   confidence intervals from the Jacobian: ``cov = s^2 (J^T J)^-1``, ``s^2`` the residual variance
   (independent residuals assumed: gauge ringing makes them correlated and the intervals optimistic;
   Rigby et al. 2014, "Friedlander fits to near-field records", discuss the bias of fitting near the front).
4. **Impulse**: the trapezoidal integral of the baselined samples from the arrival while the fitted pulse
   stands above the noise sigma, plus the fitted pulse's own impulse from there to its end (the samples
   give the area where they carry it; the fit the tail, where integrating noise and the baseline's error
   over an ill-determined end would only add error: near the charge, d ~ 10-30 and t_o is poorly
   determined while d/t_o is not).
5. **Negative phase** (when the record holds it): the least pressure and the integral of the samples
   after the positive phase up to the smoothed trace's return to zero or the record's end.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from ..blast.friedlander import friedlander_impulse_ratio
from ..blast.pulses import Friedlander
from .records import record_fault

__all__ = [
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
#: 95 % two-sided normal quantile for the confidence intervals.
_Z95 = 1.959963984540054


def friedlander_trace(tau, peak, duration, decay):
    """The Friedlander form ``P (1 - tau/t_o) exp(-d tau/t_o)`` [Pa] at tau [s] after arrival (0 before;
    continued past t_o, where it is negative: the fit's model). Paper Eq. (1)."""
    tau = np.asarray(tau, dtype=float)
    x = tau / duration
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
    """
    t = np.asarray(time_s, dtype=float)
    raw = np.asarray(pressure_Pa, dtype=float)
    column = column or name
    pre = t < 0
    if pre.sum() < MIN_PRETRIGGER:
        raise record_fault(
            source,
            column,
            2,
            f"{int(pre.sum())} pre-trigger samples (t < 0): at least {MIN_PRETRIGGER} are needed for the baseline",
        )
    base = float(raw[pre].mean())
    noise = float(raw[pre].std(ddof=1))
    p = raw - base
    post = np.flatnonzero(~pre)
    thr = max(ARRIVAL_NOISE_MULTIPLE * noise, ARRIVAL_PEAK_FRACTION * float(p[post].max()))
    above = post[p[post] > thr]
    if above.size == 0 or float(p[post].max()) <= 0:
        raise record_fault(
            source,
            column,
            int(post[0]) + 2,
            f"no shock: the trace never rises above {ARRIVAL_NOISE_MULTIPLE:g} x the pre-trigger noise",
        )
    ia = int(above[0])
    ta = 0.5 * (t[ia] + t[ia - 1])
    # end of the positive phase: the first zero crossing of the trace smoothed over 1/50 of the samples after
    # arrival (at least 5), searched after the largest sample
    dt = float(np.median(np.diff(t[ia : ia + 50]))) if t.size > ia + 2 else 0.0
    k = max(5, (t.size - ia) // 50)
    sm = _smooth(p, k)
    after = np.arange(ia + int(np.argmax(p[ia : ia + max(k, 3)])), t.size)
    neg = after[sm[after] < 0]
    end_i = int(neg[0]) if neg.size else t.size - 1
    window = np.arange(ia, end_i + 1)
    if window.size < MIN_PULSE_SAMPLES:
        raise record_fault(
            source,
            column,
            f"{ia + 2}-{end_i + 2}",
            f"{window.size} samples over the pulse: at "
            f"least {MIN_PULSE_SAMPLES} are needed (sample faster or record longer)",
        )
    tau = t[window] - ta
    y = p[window]
    P0 = float(np.max(_smooth(y, 3)[: max(3, window.size // 20)]))
    T0 = max(float(tau[-1]), dt)
    x0 = np.array([1.0, 1.0, 1.0])

    def resid(q):
        return (friedlander_trace(tau, q[0] * P0, q[1] * T0, q[2]) - y) / P0

    sol = least_squares(resid, x0, bounds=([1e-3, 0.2, -0.99], [100.0, 5.0, 50.0]), method="trf", x_scale="jac")
    Pf, Tf, df = sol.x[0] * P0, sol.x[1] * T0, float(sol.x[2])
    J = sol.jac * np.array([1.0 / P0, 1.0 / T0, 1.0]) * P0  # d residual[Pa] / d (P, t_o, d)
    dof = max(window.size - 3, 1)
    s2 = float(np.sum((sol.fun * P0) ** 2)) / dof
    try:
        cov = np.linalg.inv(J.T @ J) * s2
        half = _Z95 * np.sqrt(np.clip(np.diag(cov), 0.0, None))
    except np.linalg.LinAlgError:
        half = np.full(3, np.nan)
    t_end = ta + Tf
    # the samples while the fitted pulse stands above the noise, the fit's own tail after (step 4)
    fine = np.linspace(0.0, Tf, 2001)
    low = np.flatnonzero(friedlander_trace(fine, Pf, Tf, df) < noise)
    tc = float(fine[low[0]]) if low.size else Tf
    tail = Friedlander(Pf, Tf, df)
    imp = _impulse(t, p, ta, min(ta + tc, float(t[-1]))) + tail.impulse - float(tail.cumulative_impulse(tc))
    n_pos = int(np.count_nonzero((t >= ta) & (t <= t_end)))
    neg_p = neg_i = None
    tail = np.flatnonzero(t > t_end)
    if tail.size >= MIN_PULSE_SAMPLES and float(sm[tail].min()) < -3.0 * noise / np.sqrt(k):
        back = tail[sm[tail] >= 0]
        stop = float(t[back[0]]) if back.size and back[0] > tail[0] + k else float(t[-1])
        neg_p = float(sm[tail].min())
        neg_i = _impulse(t, p, t_end, stop)
    return GaugeFit(
        name=name,
        baseline_Pa=base,
        noise_Pa=noise,
        arrival_time_s=float(ta),
        peak_pressure_Pa=float(Pf),
        positive_duration_s=float(Tf),
        decay=df,
        ci95={"peak_pressure_Pa": float(half[0]), "positive_duration_s": float(half[1]), "decay": float(half[2])},
        impulse_Pa_s=imp,
        fit_impulse_Pa_s=float(Pf * Tf * friedlander_impulse_ratio(df)),
        negative_pressure_Pa=neg_p,
        negative_impulse_Pa_s=neg_i,
        samples_positive=n_pos,
    )
