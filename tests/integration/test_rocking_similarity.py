"""Prototype vs up-scaled model in planar rocking (paper Figs. 6-9, Sec. "Equations of motion")."""

from __future__ import annotations

import math

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.scenario import Scenario
from blastscale.study import Study

# the paper's 10 m block (alpha = 15 deg, 2000 kg/m^3), 2 m stand-off, its Appendix A fits
BASE = Scenario.default().with_values({"engine": "planar", "critical_charge": False, "blast.model": "masi2021"})


def compare_rocking(
    charge, scale, gamma=1.0, gravity_ratio=1.0, *, pulse_shape="friedlander", duration=5.0, samples=2001
):
    """The Study's planar comparison of the paper's block (prototype vs up-scaled specimen)."""
    sc = BASE.with_values(
        {
            "charge_kg": charge,
            "length": scale,
            "density_ratio": gamma,
            "gravity_ratio": gravity_ratio,
            "pulse": pulse_shape,
            "duration_s": duration,
            "samples": samples,
        }
    )
    return Study(sc).run().planar


SCALES = [1 / 10, 1 / 20, 1 / 200]
DENSITY_RATIOS = [0.07, 1.0]  # balsa (paper: 140 kg/m^3) and the same material


@pytest.mark.parametrize("scale", SCALES)
@pytest.mark.parametrize("gamma", DENSITY_RATIOS)
@pytest.mark.parametrize("charge", [50.0, 100.0])
def test_impulsive_load_upscaled_model_equals_prototype(scale, gamma, charge):
    """Impulsive limit: the model is an exact similarity transform of the prototype. The solver
    works in dimensionless time, so only the round-off of the design's impulse (solved by the
    general law to ~1e-13) and of the coefficients remains: 1e-10 rad is the acceptance level
    (observed < 1e-13)."""
    s = compare_rocking(charge, scale, gamma, pulse_shape="impulsive", duration=8.0)
    assert s.max_abs_rotation_diff <= 1e-10
    assert s.outcomes_agree
    assert s.first_peak_ratio == pytest.approx(1.0, abs=1e-10)


@pytest.mark.parametrize("scale", SCALES)
@pytest.mark.parametrize("gamma", DENSITY_RATIOS)
@pytest.mark.parametrize("shape", ["friedlander", "triangular"])
def test_finite_pulse_paper_50kg_rocking_similarity(scale, gamma, shape):
    """W = 50 kg (rocks, ~15 impacts in 8 s): the up-scaled model stays within 5e-4 rad of the
    prototype over the whole run (observed 1.2e-4..3.1e-4; the paper's Figs. 7-9 show
    coinciding curves), both survive, and the first peaks agree to 0.1 %."""
    s = compare_rocking(50.0, scale, gamma, pulse_shape=shape, duration=8.0)
    assert s.max_abs_rotation_diff <= 5e-4
    assert s.outcomes_agree and not s.prototype.collapsed
    assert s.first_peak_ratio == pytest.approx(1.0, abs=1e-3)
    assert s.model.n_impacts == s.prototype.n_impacts


@pytest.mark.parametrize("scale", SCALES)
@pytest.mark.parametrize("gamma", DENSITY_RATIOS)
@pytest.mark.parametrize("shape", ["friedlander", "triangular"])
def test_finite_pulse_paper_100kg_both_overturn_rocking_phase_and_fall(scale, gamma, shape):
    """W = 100 kg: both overturn and, after 4 s, both lie on their side (the whole run, fall
    included, is compared). The acceptance level 5e-4 rad holds on the two phases that carry
    the physics:

    * the rocking phase, at equal times up to the earlier tipping point (observed 7e-5..1.5e-4);
    * the fall, on a common phase: the angular velocity at equal angle, in the dimensionless
      time p t (observed 6e-5..1.2e-4). The pulse is long over, so energy conservation makes
      that difference at most the difference at the tipping point (+1e-6 for the linear
      interpolation of the model's samples at the prototype's angles).

    At equal times over the whole run the angles differ by 0.9e-3..1.8e-3 rad (documented,
    not a failure of similarity): the ~1e-4 energy difference shifts the tipping time by
    0.3-0.7 ms and the fall turns that into (fall speed) x (shift), which the last assertion
    checks (1 % for sampling the speed)."""
    s = compare_rocking(100.0, scale, gamma, pulse_shape=shape, duration=4.0)
    assert s.prototype.collapsed and s.model.collapsed and s.outcomes_agree
    assert s.theta_prototype[-1] == s.theta_model[-1] == pytest.approx(math.pi / 2, abs=1e-15)
    p = s.prototype.system.frequency_parameter
    assert s.max_abs_rotation_diff_to_tipping <= 5e-4
    assert abs(s.tipping_angular_velocity_diff) / p <= 5e-4
    assert s.max_fall_phase_diff <= 5e-4
    assert s.max_fall_phase_diff <= abs(s.tipping_angular_velocity_diff) / p + 1e-6
    assert abs(s.collapse_time_diff) <= 2e-3
    lie_shift = s.model.end_time / s.design.factors.time - s.prototype.end_time
    speed = float(np.max(np.abs(s.theta_dot_prototype)))
    shift_bound = 1.01 * speed * max(abs(s.collapse_time_diff), abs(lie_shift))
    assert s.max_abs_rotation_diff <= max(s.max_abs_rotation_diff_to_tipping, shift_bound)


@pytest.mark.parametrize("scale", SCALES)
@pytest.mark.parametrize("gamma", DENSITY_RATIOS)
def test_paper_critical_charge_outcomes_agree(scale, gamma):
    """W = 79.8 kg (the paper's critical charge): both survive. Near the threshold the motion
    is ill-conditioned (the paper notes 'a negligible offset'): the first excursion climbs
    close to the top, where the time spent diverges, so the equal-time difference over 8 s is
    4e-2..9e-2 rad (lambda 1/10..1/200, gamma 0.07..1; not asserted, see docs/rocking.md).
    Only the outcome and the first peak (1 %: near the tipping point theta_max responds to
    the energy like a square root, so the 0.07 % impulse-like difference of 50 kg grows to
    ~0.7 %) are asserted."""
    s = compare_rocking(79.8, scale, gamma, duration=8.0)
    assert s.outcomes_agree and not s.prototype.collapsed
    assert s.first_peak_ratio == pytest.approx(1.0, abs=1e-2)


def test_to_dict_has_the_cli_keys():
    d = compare_rocking(50.0, 1 / 20, duration=2.0).to_dict()
    for part in ("prototype", "model"):
        assert {"collapsed", "max_rotation_rad", "collapse_time_s", "first_impact_time_s"} <= set(d[part])
    assert "max_abs_rotation_diff_rad" in d["similarity"]
    # the model's first impact, up-scaled, is at the prototype's (~1.38 s)
    assert d["model"]["first_impact_time_s"] == pytest.approx(d["prototype"]["first_impact_time_s"], abs=2e-3)


def test_similarity_bad_input():
    with pytest.raises(BlastscaleInputError, match="pulse"):
        compare_rocking(50.0, 0.1, pulse_shape="square")
    with pytest.raises(BlastscaleInputError, match="scale.length"):
        compare_rocking(50.0, -0.1)
    with pytest.raises(BlastscaleInputError, match="samples"):
        compare_rocking(50.0, 0.1, samples=2.5)


def test_centrifuge_gravity_ratio_impulsive_exact():
    """With a gravity ratio (centrifuge model, varsigma = 20) the factors change
    (time sqrt(lambda/varsigma)) and the impulsive similarity stays exact (1e-10 rad)."""
    s = compare_rocking(50.0, 1 / 20, 1.0, 20.0, pulse_shape="impulsive", duration=5.0)
    assert s.design.factors.time == pytest.approx(math.sqrt(1 / 20 / 20), rel=1e-14)
    assert s.max_abs_rotation_diff <= 1e-10 and s.outcomes_agree


@pytest.mark.parametrize("charge", [50.0, 100.0])
def test_contract_reproduces_the_direct_comparison(charge):
    """The rocking comparison goes through the package's comparison contract (datasets with
    ``dimension`` attributes, one up-scaling, interpolation onto the prototype's grid). It must
    give the numbers of the direct computation on the exactly corresponding samples
    (theta_m(t lambda_t) / f.angle): the up-scaled times equal the prototype's to round-off, so
    the interpolation moves the angle by (slope) x 1e-16 s: 1e-13 rad is the acceptance level.
    The contract's first peak from the samples (every 4 ms) agrees with the solver's exact peak
    event to (omega dt)^2 / 8 ~ 1e-5 relative; 1e-4 is asserted."""
    s = compare_rocking(charge, 1 / 20, pulse_shape="friedlander", duration=4.0)
    f = s.design.factors
    direct_th = s.model.theta_eval / f.angle
    direct_om = s.model.theta_dot_eval / f.angular_velocity
    assert s.max_abs_rotation_diff == pytest.approx(
        float(np.max(np.abs(direct_th - s.prototype.theta_eval))), abs=1e-13
    )
    assert s.max_abs_angular_velocity_diff == pytest.approx(
        float(np.max(np.abs(direct_om - s.prototype.theta_dot_eval))), abs=1e-12
    )
    assert np.max(np.abs(s.theta_model - direct_th)) <= 1e-13
    c = s.comparison
    assert c["outcomes_agree"] == s.outcomes_agree and c["outcome_prototype"] == s.prototype.collapsed
    if not s.prototype.collapsed:
        r = c["variables"]["rotation_y"]["block"]
        assert r["first_peak_prototype"] == pytest.approx(s.prototype.peak_angles[0], rel=1e-4)
        assert r["first_peak_ratio"] == pytest.approx(s.first_peak_ratio, rel=1e-4)
