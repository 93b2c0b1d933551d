"""The planner's gauge record is one the fired reader can check: it holds the negative phase and a tail past it.

The paper's block at 1/20 (the shipped example's design) and the built-in default at 1/200: the instruments of
planning/instruments.py at the specimen's pulse; a record written here (no code shared with the reader) as the
card asks it: the trigger delay t_A of pre-trigger, the card's sampling rate and record length, a Friedlander
positive phase (paper Eq. 1) and Granstrom's cubic negative phase with Rigby's peak suction and duration at the
specimen's Z (UFC 3-340-02 Fig. 2-16, blast.negative_phase), 0.5 % noise. Read by fired.gauges.fit_gauge: the
tail checks the baseline (the line through the pre-trigger and the tail) and no note. The answer "no": the same
pulse recorded to the old ``t_A + 3 t_o`` ends inside its negative phase: no tail check.
"""

from __future__ import annotations

import numpy as np
import pytest

from blastscale.blast.negative_phase import negative_phase
from blastscale.fired import fit_gauge
from blastscale.planning.instruments import instrument_settings, negative_duration_s
from blastscale.scenario import Scenario
from blastscale.study import Study


def _record(m, settings, record_s, seed=0):
    fs = settings.pressure_sampling_hz
    ta, to, d, P = m.arrival_time, m.positive_duration, m.friedlander_decay, m.reflected_pressure
    neg = negative_phase(m.scaled_distance, m.charge_kg, m.burst)
    rng = np.random.default_rng(seed)
    t = np.arange(-ta, record_s, 1.0 / fs)
    tau = np.clip(t - ta, 0.0, None)
    x = tau / to
    p = np.where((t >= ta) & (tau <= to), P * (1 - x) * np.exp(-d * x), 0.0)
    y = (tau - to) / neg.duration
    p = p - np.where((y >= 0) & (y <= 1), neg.pressure * 6.75 * y * (1 - y) ** 2, 0.0)
    return t, p + 0.005 * P * rng.standard_normal(t.size)


@pytest.mark.parametrize("scale", ["1/20", "1/200"])
def test_the_cards_record_holds_a_tail_past_the_negative_phase(scale):
    d = Study(Scenario.default().with_values({"scale.length": scale})).check().design
    m = d.specimen
    settings = instrument_settings(
        reflected_pressure_Pa=m.reflected_pressure,
        incident_pressure_Pa=m.reflected_pressure / 3,
        positive_duration_s=m.positive_duration,
        friedlander_decay=m.friedlander_decay,
        arrival_time_s=m.arrival_time,
        rise_time_s=0.1,
        response_time_s=1.0,
        top_displacement_m=0.01,
        negative_duration_s=negative_duration_s(m.scaled_distance, m.charge_kg, m.burst),
    )
    g = fit_gauge(*_record(m, settings, settings.pressure_record_s), "g1")
    assert g.baseline_from.startswith("pre-trigger and tail") and g.warnings == ()
    assert g.negative_impulse_Pa_s is not None
    old = fit_gauge(*_record(m, settings, m.arrival_time + 3.0 * m.positive_duration), "g1")
    assert "tail" not in old.baseline_from and old.tail_offset_Pa is None
