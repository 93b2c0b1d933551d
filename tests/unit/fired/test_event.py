"""The monument under the designed event (blastscale.fired.event): the similar prototype charge against the
design's own law, the residual of a track, and the band's closed form (independent log-normal terms)."""

from __future__ import annotations

import math
import tomllib
from types import SimpleNamespace

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.fired.event import (
    Q95,
    REST_FRACTION,
    DesignedEvent,
    designed_event_marker,
    marker_residual,
    similar_prototype_charge,
)
from blastscale.scenario import Scenario
from blastscale.similitude import design_model
from blastscale.study import Study

COLUMN = """
title = "event: a three-drum circular column at 1/10"
[structure]
kind = "column"
section = "circular"
drums = 3
height_m = 3.0
base_width_m = 0.6
top_width_m = 0.5
density_kg_m3 = 2700.0
[blast]
charge_kg = 20.0
standoff_m = 5.0
[scale]
length = "1/10"
[simulation]
engine = "3d"
duration_s = 1.0
critical_charge = false
"""


# -- the similar charge ------------------------------------------------------------------------------
def test_hopkinson_cranz_similar_charge_is_the_cube_law():
    """Hopkinson-Cranz (lambda_Z = 1): W_s = W / lambda^3, R_s = R / lambda, exactly (to the root's 1e-9)."""
    d = design_model(50.0, 2.0, 1 / 20, law="hopkinson-cranz", density_ratio=None)
    w = 1.3 * d.specimen_charge_kg
    ws, rs = similar_prototype_charge(d, w, d.specimen.standoff_m)
    assert ws == pytest.approx(w * 20.0**3, rel=1e-9) and rs == pytest.approx(2.0, rel=1e-12)


@pytest.mark.parametrize("charge_factor, standoff_factor", [(1.0, 1.0), (1.3, 1.0), (0.8, 1.0), (1.1, 1.2)])
def test_general_law_similar_charge_is_the_designs_inverse(charge_factor, standoff_factor):
    """The general law (lambda_Z solved per prototype Z): designing the similar event (W_s at R_s, the same scale
    and fits) gives back the shot as fired, charge and stand-off, to 1e-9; at the design's own load, its
    prototype."""
    d = design_model(50.0, 2.0, 1 / 20, blast_model="masi2021")
    w, r = charge_factor * d.specimen_charge_kg, standoff_factor * d.specimen.standoff_m
    ws, rs = similar_prototype_charge(d, w, r)
    again = design_model(ws, rs, 1 / 20, blast_model="masi2021")
    assert again.specimen_charge_kg == pytest.approx(w, rel=1e-9)
    assert again.specimen.standoff_m == pytest.approx(r, rel=1e-12)
    if charge_factor == standoff_factor == 1.0:
        assert ws == pytest.approx(50.0, rel=1e-9)


def test_similar_charge_outside_the_fits_is_refused():
    """The answer must be "no": a load whose prototype impulse no charge of the fits' range gives."""
    d = design_model(50.0, 2.0, 1 / 20, blast_model="masi2021")
    with pytest.raises(BlastscaleInputError, match="reflected_impulse = .* is out of range"):
        similar_prototype_charge(d, 40.0 * d.specimen_charge_kg, d.specimen.standoff_m)


# -- the residual ------------------------------------------------------------------------------------
def test_residual_is_the_tail_mean_and_none_while_moving():
    """A history that ends at rest at (3, 4) mm: residual 5 mm (|mean|), standard error noise / sqrt(n) with n
    the last 5 % of the frames; one still swinging at its end by more than 1 % of its peak: None."""
    n = 2000
    rng = np.random.default_rng(0)
    ux = np.concatenate([np.linspace(0, 0.02, n // 2), np.full(n // 2, 0.003)]) + 5e-5 * rng.standard_normal(n)
    uz = np.full(n, 0.004) + 5e-5 * rng.standard_normal(n)
    r, se = marker_residual(ux, uz, 5e-5, 0.02)
    assert r == pytest.approx(0.005, abs=3 * 5e-5 / math.sqrt(100))
    assert se == pytest.approx(5e-5 / math.sqrt(100), rel=1e-12)
    swing = 0.02 * np.sin(np.linspace(0, 40, n))
    assert marker_residual(swing, None, 5e-5, 0.02)[0] is None
    # at the edge: a tail range just under 1 % of the peak is at rest
    calm = np.concatenate([np.zeros(n - 100), np.linspace(0, 0.99 * REST_FRACTION * 0.02, 100)])
    assert marker_residual(calm, None, 0.0, 0.02)[0] is not None


# -- the band ----------------------------------------------------------------------------------------
def _design():
    return Study(Scenario.from_dict(tomllib.loads(COLUMN), source="test")).check().design


def _histories(u_end_meas=0.002, u_end_pred=0.0016, u_end_refit=0.0021):
    """Measured, predicted and refit marker histories (specimen, [m]) that end at rest."""
    n = 400
    ramp = np.linspace(0.0, 1.0, n)
    meas = {
        "peak": SimpleNamespace(first_peak_m=0.030, first_peak_time_s=0.15, noise_m=5e-5, first_peak_sigma_m=4e-5),
        "ux": np.where(ramp < 0.5, 0.03 * ramp, u_end_meas),
        "uz": None,
    }
    pred = {"first_peak_m": 0.024, "first_peak_time_s": 0.14, "ux": np.where(ramp < 0.5, 0.02, u_end_pred)}
    refit = {"first_peak_m": 0.0306, "first_peak_time_s": 0.152, "ux": np.where(ramp < 0.5, 0.03, u_end_refit)}
    return meas, pred, refit


def _summary(ensemble=True):
    judged = [
        {"quantity": "first peak", "where": "P-3", "prototype": 0.20, "model": 0.21},
        {"quantity": "first peak", "where": "P-1", "prototype": 0.05, "model": 0.06},
        {"quantity": "residual displacement", "where": "D-3", "prototype": 0.018, "model": 0.0162},
    ]
    ens = {
        "points": {"P-3": {"first_peak_prototype_p05_m": 0.18, "first_peak_prototype_p95_m": 0.25}},
        "bodies": {
            "D-3": {"residual_displacement_prototype_p05_m": 0.01, "residual_displacement_prototype_p95_m": 0.03}
        },
    }
    return {"verdict": {"judged": judged}, **({"ensemble": ens} if ensemble else {})}


def test_band_is_the_independent_log_normal_terms():
    """The closed form: u_e = 10 u (u_pred / u_refit) (lambda = 1/10), sigma^2 the sum of the terms' squares
    (load s sigma_W, track: the first peak's standard error / u, refit |ln(u_refit / u)|, similarity |ln(m / p)| at the marker's point
    P-3, ensemble ln(p95 / p05) / 3.29), the band u_e exp(-+1.645 sigma), to 1e-12; the residual likewise,
    corrected by the runs' residuals (1.6 / 2.1) and up-scaled."""
    d = _design()
    meas, pred, refit = _histories()
    e = designed_event_marker(
        meas, pred, refit, (0.0, 0.0, 0.3), 2.0, DesignedEvent(d, _summary(), True, 0.01, -math.log(1.1))
    )
    u = 10.0 * 0.030 * 0.024 / 0.0306
    terms = {
        "load": 2.0 * 0.01,
        "track": 4e-5 / 0.030,  # the first peak's standard error, not the single-sample noise (5e-5)
        "refit": math.log(0.0306 / 0.030),
        "similarity": math.log(0.21 / 0.20),
        "ensemble": math.log(0.25 / 0.18) / (2 * Q95),
    }
    sig = math.sqrt(sum(v**2 for v in terms.values()))
    assert e["point"] == "P-3" and e["body"] == "D-3"
    assert {k: v["sigma_ln"] for k, v in e["band_terms"].items()} == pytest.approx(terms, rel=1e-12)
    assert e["first_peak_m"] == pytest.approx(u, rel=1e-12)
    assert e["sigma_ln"] == pytest.approx(sig, rel=1e-12)
    assert e["first_peak_p05_m"] == pytest.approx(u * math.exp(-Q95 * sig), rel=1e-12)
    assert e["first_peak_p95_m"] == pytest.approx(u * math.exp(Q95 * sig), rel=1e-12)
    assert e["as_fired_first_peak_m"] == pytest.approx(0.30, rel=1e-12)
    assert e["first_peak_time_s"] == pytest.approx(0.15 * (0.14 / 0.152) / math.sqrt(0.1), rel=1e-12)
    # the residual: 2 mm measured, corrected by 1.6 / 2.1, x 10
    rc = 0.0016 / 0.0021
    assert e["residual_correction"] == pytest.approx(rc, rel=1e-12)
    assert e["residual_displacement_m"] == pytest.approx(10 * 0.002 * rc, rel=1e-12)
    rt = {k: v["sigma_ln"] for k, v in e["residual_band_terms"].items()}
    assert rt["load"] == pytest.approx(abs(math.log(rc) / math.log(1 / 1.1)) * 0.01, rel=1e-12)
    assert rt["similarity"] == pytest.approx(math.log(0.018 / 0.0162), rel=1e-12)
    assert rt["ensemble"] == pytest.approx(math.log(3.0) / (2 * Q95), rel=1e-12)
    rs = math.sqrt(sum(v**2 for v in rt.values() if v is not None))
    assert e["residual_displacement_p95_m"] == pytest.approx(e["residual_displacement_m"] * math.exp(Q95 * rs))
    assert e["notes"] == []


def test_a_chaotic_structure_without_an_ensemble_says_so():
    """No ensemble for circular drums: the term is null and a note says how to get it; not chaotic: no note."""
    d = _design()
    meas, pred, refit = _histories()
    e = designed_event_marker(
        meas, pred, refit, (0.0, 0.0, 0.3), 2.0, DesignedEvent(d, _summary(False), True, 0.01, -0.1)
    )
    assert e["band_terms"]["ensemble"]["sigma_ln"] is None
    assert any("ensemble_members >= 2" in n for n in e["notes"])
    e = designed_event_marker(
        meas, pred, refit, (0.0, 0.0, 0.3), 2.0, DesignedEvent(d, _summary(False), False, 0.01, -0.1)
    )
    assert e["band_terms"]["ensemble"]["sigma_ln"] is None and e["notes"] == []


def test_a_residual_within_the_noise_has_a_band_from_zero():
    """The edge: a measured residual not clear of its standard error has no log-normal band: [0, its 95 %
    bound], said in the notes."""
    d = _design()
    meas, pred, refit = _histories(u_end_meas=1e-6)
    e = designed_event_marker(meas, pred, refit, (0.0, 0.0, 0.3), 2.0, DesignedEvent(d, _summary(), False, 0.01, -0.1))
    assert e["residual_displacement_p05_m"] == 0.0 and e["residual_sigma_ln"] is None
    assert e["residual_displacement_p95_m"] > e["residual_displacement_m"]
    assert any("within the track's noise" in n for n in e["notes"])
