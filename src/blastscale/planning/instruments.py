"""What the laboratory must buy and set to measure the specimen: pressure gauges, camera,
displacement sensor, trigger (the rules of docs/planning.md, each stated here once).

Every rule works on the specimen's own scales: the pulse (peak reflected and incident pressure,
positive duration t_o, Friedlander decay d, arrival time t_A) and the rocking (time from the shock's
arrival to the first peak of the rotation, or to the tipping point when it overturns; the whole
response; the largest horizontal displacement of the top corner facing the charge).

Rules
-----
* **Gauge range**: 1.5 x the peak the gauge will see (reflected pressure for a gauge flush in a rigid
  wall beside the specimen, incident pressure for a side-on pencil gauge at the same stand-off):
  headroom for the TNT-equivalence uncertainty (+-10-20 %, UFC 3-340-02 Table 2-1) and ringing.
* **Gauge rise time**: ``t_r <= 0.1 t_o / (1 + d)``. The Friedlander pressure falls from its peak at
  the rate ``P (1 + d) / t_o``, so a gauge that needs t_r to respond reads the peak low by about
  ``(1 + d) t_r / t_o``: at most 10 %.
* **Sampling rate**: ``f_s >= max(2 / t_r, 50 / t_o, f_i)``: two samples within the allowed rise time (the
  peak is caught within one rise), 50 over the positive phase (the impulse by the trapezoidal rule
  within 0.5 % for d <= 10) and ``f_i`` (:func:`impulse_rate_needed_hz`), at which the shock's position between
  two samples leaves the impulse uncertain by at most :data:`IMPULSE_ARRIVAL_ERROR` (95 %), rounded up to the
  1-2-5 series; capped at the lab's ``gauge_rate_max_hz`` (the impulse's error at the setting is stated:
  ``pressure_impulse_arrival_error``). The shock lies anywhere between the last sample before it and the first
  after (uniformly over ``1 / f``), and the samples after it are the same wherever it lies: the area
  ``P x (its position)`` is unknown, standard deviation ``P / (f sqrt 12)``, against the impulse
  ``P t_o k(d)`` (``k(d) = (d - 1 + e^-d) / d^2``, paper Eq. 2): the 95 % error
  ``1.96 / (sqrt 12 f t_o k(d))``, so ``f_i = 1.96 / (sqrt 12 IMPULSE_ARRIVAL_ERROR t_o k(d))``: 154 samples over the
  positive phase for d = 1, 629 for d = 10 (the reader of fired gauges states the same term in its
  interval: :mod:`blastscale.fired.gauges`).
* **Gauge resolves the pulse** (``[lab] gauge_rate_max_hz``; :func:`gauge_rate_needed_hz`): at least one
  sample per allowed rise time, ``f_max >= 1 / t_r = 10 (1 + d) / t_o``, i.e. at least
  ``10 (1 + d)`` samples over the positive phase (20 for d = 1). Why that many: the first sample after
  the shock falls at worst one interval ``1 / f`` late, and the Friedlander pressure has then fallen by
  ``(1 + d) / (f t_o)`` of its peak: at most :data:`RISE_PEAK_ERROR` (10 %), the same bound as the
  rise time's. The trapezoidal rule's relative error on ``(1 - t/t_o) e^{-d t / t_o}`` is then small,
  ``(1 + d - e^{-d}) d^2 / (12 N^2 (d - 1 + e^{-d}))`` for N samples (0.09 % for d = 1, N = 20; 0.08 % for
  d = 10, N = 110), but the shock's position between two samples is not: at that rate it leaves the impulse
  uncertain by 7.7 % (d = 1) and 5.7 % (d = 10) (95 %, "Sampling rate" above): a gauge that resolves the peak
  does not yet weigh the charge. A lab gauge slower than that cannot read the peak: the planner rejects the
  design (``gauge_rate_max_hz``); a gauge between it and the setting above is a warning (the peak read low by
  up to ``(1 + d) / (f t_o)``, or the impulse uncertain by more than :data:`IMPULSE_ARRIVAL_ERROR`).
* **Camera frame rate**: ``20 / t_rise`` (20 frames between the shock and the first peak: the peak is
  missed by at most ``1 - cos(pi / 40)`` = 0.3 % of its value on a sine-like rise), rounded up to the
  1-2-5 series; the frames over the pulse, over the rise and over the whole response are reported.
* **Record length**: the camera's, the whole response (to rest, or to the collapse) plus 10 % and a
  pre-trigger of the arrival time. The gauges': the positive and the negative phase twice over after the arrival,
  ``t_A + max(3 t_o, 2 (t_o + t_o-))`` (:func:`negative_duration_s`; at least the old ``t_A + 3 t_o``), so
  that the record holds the negative phase and a tail after it that checks the baseline: the fired reader's
  tail is the record's last tenth, and checks only past the negative phase (:mod:`blastscale.fired.gauges`; a
  record of ``t_A + 3 t_o``, which the rule was, ends inside the negative phase: it lasts 2.5-5.4 positive
  durations at Z = 1-30 and ~38 at Z = 0.5).
* **Displacement range**: 1.5 x the largest horizontal displacement of the top corner facing the
  charge, ``u = 2b (1 - cos theta) + 2h sin theta`` (the block rotates about its far edge), or
  the whole block (2b + 2h) when it overturns.
* **Trigger delay**: the arrival time t_A after the firing signal (the gauges and the camera are
  triggered by the firing pulse and record t_A of pre-trigger).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Optional

from ..analysis.intervals import Z95
from ..blast.friedlander import friedlander_impulse_ratio
from ..blast.negative_phase import NEGATIVE_PHASE_RANGE, negative_phase_unchecked

__all__ = [
    "InstrumentSettings",
    "instrument_settings",
    "round_up_125",
    "top_corner_displacement",
    "GAUGE_HEADROOM",
    "RISE_PEAK_ERROR",
    "SAMPLES_PER_PULSE",
    "FRAMES_PER_RISE",
    "gauge_rate_needed_hz",
    "impulse_arrival_error",
    "impulse_rate_needed_hz",
    "negative_duration_s",
    "IMPULSE_ARRIVAL_ERROR",
]

#: Factor of a gauge's or a sensor's range on the peak it will see [-].
GAUGE_HEADROOM = 1.5
#: Largest fraction by which a gauge's rise may under-read the peak [-].
RISE_PEAK_ERROR = 0.1
#: Samples over the positive phase (impulse by the trapezoidal rule) [-].
SAMPLES_PER_PULSE = 50
#: Largest 95 % error of a gauge's impulse from the shock's position between two samples [-]: 1 % (a third of the
#: 3 % on the effective charge that ~2 % on the impulse makes, :mod:`blastscale.fired.gauges`).
IMPULSE_ARRIVAL_ERROR = 0.01
#: Camera frames between the shock's arrival and the first peak of the rotation [-].
FRAMES_PER_RISE = 20


def gauge_rate_needed_hz(positive_duration_s: float, friedlander_decay: float) -> float:
    """The slowest gauge sampling rate that resolves a pulse [1/s]: one sample per allowed rise time,
    ``10 (1 + d) / t_o`` (module docstring, "Gauge resolves the pulse"), for a positive duration t_o [s] and a
    Friedlander decay d [-].

    >>> gauge_rate_needed_hz(1e-3, 1.0)
    20000.0
    """
    return (1.0 + max(float(friedlander_decay), 0.0)) / (RISE_PEAK_ERROR * float(positive_duration_s))


def impulse_arrival_error(rate_hz: float, positive_duration_s: float, friedlander_decay: float) -> float:
    """The 95 % relative error of a gauge's impulse [-] from the shock's position between two samples at
    ``rate_hz`` [1/s], for a pulse of positive duration t_o [s] and Friedlander decay d [-]:
    ``1.96 / (sqrt 12 f t_o k(d))`` (module docstring, "Sampling rate").

    >>> round(impulse_arrival_error(20e3, 1e-3, 1.0), 4)
    0.0769
    """
    k = float(friedlander_impulse_ratio(max(float(friedlander_decay), 0.0)))
    return Z95 / (math.sqrt(12.0) * float(rate_hz) * float(positive_duration_s) * k)


def impulse_rate_needed_hz(positive_duration_s: float, friedlander_decay: float) -> float:
    """The slowest gauge sampling rate [1/s] at which the shock's position between two samples leaves the
    impulse within :data:`IMPULSE_ARRIVAL_ERROR` (95 %) (:func:`impulse_arrival_error`).

    >>> round(impulse_rate_needed_hz(1e-3, 1.0) * 1e-3, 1), round(impulse_rate_needed_hz(1e-3, 10.0) * 1e-3, 1)
    (153.8, 628.7)
    """
    return impulse_arrival_error(1.0, positive_duration_s, friedlander_decay) / IMPULSE_ARRIVAL_ERROR


def negative_duration_s(scaled_distance: float, charge_kg: float, burst: str = "surface") -> float:
    """The negative phase's duration t_o- [s] of a charge W [kg TNT] at the scaled distance Z [m/kg^(1/3)]:
    Rigby's calibration of UFC 3-340-02 Fig. 2-16 (:mod:`blastscale.blast.negative_phase`), Z held to its range
    (0.07-37.6 m/kg^(1/3), where the duration lies between ~9 and ~17 ms/kg^(1/3)): a record's length, not a load.

    >>> round(negative_duration_s(1.0, 1.0) * 1e3, 2), round(negative_duration_s(100.0, 1.0) * 1e3, 2)
    (9.26, 17.3)
    """
    lo, hi = NEGATIVE_PHASE_RANGE
    z = min(max(float(scaled_distance), lo), hi)
    return float(negative_phase_unchecked(z, float(charge_kg), burst).duration)


def round_up_125(x: float) -> float:
    """The smallest value of the 1-2-5 series (1, 2, 5, 10, 20, ...) at or above ``x`` > 0.

    >>> round_up_125(3.2e5), round_up_125(1000.0), round_up_125(0.012)
    (500000.0, 1000.0, 0.02)
    """
    e = math.floor(math.log10(x))
    for m in (1.0, 2.0, 5.0, 10.0):
        v = m * 10.0**e
        if v >= x * (1 - 1e-12):
            return float(f"{v:.12g}")
    return float(f"{10.0 ** (e + 1):.12g}")  # pragma: no cover - unreachable


def top_corner_displacement(width_m: float, height_m: float, rotation_rad: float) -> float:
    """Horizontal displacement [m] of the top corner facing the charge of a block of ``width_m`` 2b
    and ``height_m`` 2h rotated by ``rotation_rad`` about its far base edge:
    ``u = 2b (1 - cos theta) + 2h sin theta``."""
    th = float(rotation_rad)
    return width_m * (1.0 - math.cos(th)) + height_m * math.sin(th)


@dataclass(frozen=True)
class InstrumentSettings:
    """The specimen's instruments (SI; the rules of the module docstring)."""

    reflected_gauge_range_Pa: float
    incident_gauge_range_Pa: float
    pressure_rise_time_s: float
    pressure_sampling_hz: float
    pressure_sampling_needed_hz: float
    pressure_impulse_arrival_error: float
    pressure_record_s: float
    camera_fps_required: float
    camera_fps: float
    camera_record_s: float
    camera_frames: int
    frames_over_pulse: float
    frames_over_rise: float
    frames_over_response: float
    displacement_range_m: float
    trigger_delay_s: float
    rise_time_s: float
    response_time_s: float

    def to_dict(self) -> dict:
        return asdict(self)


def instrument_settings(
    *,
    reflected_pressure_Pa: float,
    incident_pressure_Pa: float,
    positive_duration_s: float,
    friedlander_decay: float,
    arrival_time_s: float,
    rise_time_s: float,
    response_time_s: float,
    top_displacement_m: float,
    camera_max_fps: float = math.inf,
    gauge_rate_max_hz: Optional[float] = None,
    negative_duration_s: float = 0.0,
) -> InstrumentSettings:
    """The instruments for a specimen's pulse and rocking (module docstring rules).

    Parameters
    ----------
    reflected_pressure_Pa, incident_pressure_Pa : float
        Peak reflected and incident overpressure at the specimen [Pa].
    positive_duration_s : float
        Positive-phase duration t_o [s].
    friedlander_decay : float
        Friedlander decay d [-] (paper Eq. 2).
    arrival_time_s : float
        Shock arrival time t_A [s].
    rise_time_s : float
        Time from the arrival to the first peak of the rotation (or to the tipping point) [s].
    response_time_s : float
        The whole response, from the arrival to rest or to the collapse [s].
    top_displacement_m : float
        Largest horizontal displacement of the top corner facing the charge [m].
    camera_max_fps : float
        The lab camera's fastest rate [1/s]: the setting is the 1-2-5 value at or above the required
        rate, but not above this (a camera that cannot reach the required rate is the planner's
        business: ``camera_fps_required`` says it).
    gauge_rate_max_hz : float, optional
        The lab gauges' fastest sampling rate [1/s] (None: no limit): the setting is capped at it;
        ``pressure_sampling_needed_hz`` is the rate below which the pulse is not resolved.
    negative_duration_s : float
        The negative phase's duration t_o- [s] (:func:`negative_duration_s`): the gauges' record holds it and a
        tail after it (module docstring); 0: the positive phase alone (``t_A + 3 t_o``).
    """
    to, d = float(positive_duration_s), float(friedlander_decay)
    tr = RISE_PEAK_ERROR * to / (1.0 + max(d, 0.0))
    fs = round_up_125(max(2.0 / tr, SAMPLES_PER_PULSE / to, impulse_rate_needed_hz(to, d)))
    if gauge_rate_max_hz is not None:
        fs = min(fs, float(gauge_rate_max_hz))
    need = FRAMES_PER_RISE / float(rise_time_s)
    fps = min(round_up_125(need), max(float(camera_max_fps), need))
    record = 1.1 * float(response_time_s) + float(arrival_time_s)
    return InstrumentSettings(
        reflected_gauge_range_Pa=GAUGE_HEADROOM * float(reflected_pressure_Pa),
        incident_gauge_range_Pa=GAUGE_HEADROOM * float(incident_pressure_Pa),
        pressure_rise_time_s=tr,
        pressure_sampling_hz=fs,
        pressure_sampling_needed_hz=gauge_rate_needed_hz(to, d),
        pressure_impulse_arrival_error=impulse_arrival_error(fs, to, d),
        pressure_record_s=float(arrival_time_s) + max(3.0 * to, 2.0 * (to + float(negative_duration_s))),
        camera_fps_required=need,
        camera_fps=fps,
        camera_record_s=record,
        camera_frames=int(math.ceil(fps * record)),
        frames_over_pulse=fps * to,
        frames_over_rise=fps * float(rise_time_s),
        frames_over_response=fps * float(response_time_s),
        displacement_range_m=GAUGE_HEADROOM * float(top_displacement_m),
        trigger_delay_s=float(arrival_time_s),
        rise_time_s=float(rise_time_s),
        response_time_s=float(response_time_s),
    )
