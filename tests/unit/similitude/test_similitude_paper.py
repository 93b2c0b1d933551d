"""The paper's numerical results for the design of reduced-scale models (model="masi2021").

All cases use the paper's own Appendix A fits, stand-off R = 2 m unless stated, g = 9.81 m/s^2.
"""

import math
from pathlib import Path

import numpy as np
import pytest

from blastscale.similitude import (
    design_model,
    masi2021_quadratic_roots,
    scaling_factors,
    solve_scaled_distance_factor,
)

DATA = Path(__file__).resolve().parents[2] / "data"


def _table_rows():
    rows = np.loadtxt(DATA / "masi2021_table_blast_loading.csv", delimiter=",", comments="#")
    return [tuple(r) for r in rows]


def _printed_digits(x: float) -> int:
    """Number of decimals the paper printed (3 significant digits at most)."""
    s = f"{x:.3g}"
    return len(s.split(".")[1]) if "." in s else 0


@pytest.mark.parametrize("W, Zp, lam, Wm, Zm", _table_rows())
def test_table_blast_loading_characteristics(W, Zp, lam, Wm, Zm):
    d = design_model(W, 2.0, lam, blast_model="masi2021")
    # Scaled distances are printed with 2 decimals and truncated (0.9985 -> 0.99), so the computed value
    # must lie in [printed, printed + 0.01) up to rounding: tolerance 0.01 m/kg^(1/3) one-sided, +-0.005 slack.
    assert Zp - 0.005 <= d.prototype.scaled_distance < Zp + 0.01
    assert Zm - 0.005 <= d.specimen.scaled_distance < Zm + 0.01
    # Charges: 3 printed significant figures -> relative tolerance 1 % (largest printed rounding error is
    # 1.0 g for 1.0044 g: 0.44 %; 2.06 g for 2.0685 g: 0.41 %).
    assert d.specimen_charge_kg == pytest.approx(Wm, rel=1e-2)


def test_non_slender_block_2500kg_at_3m():
    # Paper Sec. "Non-slender blocks": 2500 kg at 3 m, lambda = 1/200, gamma = 1 -> 14.26 mg (14.27 by our
    # calculation: 14.2656 mg, the paper truncates). Tolerance: 0.01 mg on a 4-digit figure.
    d = design_model(2500.0, 3.0, 1 / 200, blast_model="masi2021")
    assert d.specimen_charge_kg * 1e6 == pytest.approx(14.27, abs=0.01)


def test_overpressure_ratio_near_figure_5_gamma_1():
    # "assuming lambda = 1/200, the model overpressure peak equals 5.8 % the prototype peak, with gamma = 1"
    # (prototype 50 kg at 2 m, Fig. 8 caption). Printed to 2 digits -> +-0.05 %.
    d = design_model(50.0, 2.0, 1 / 200, 1.0, blast_model="masi2021")
    assert 100 * d.pressure_ratio == pytest.approx(5.8, abs=0.05)


def test_overpressure_ratio_near_figure_8_gamma_005():
    # "... with a dissimilar material such that gamma = 0.05, the model overpressure peak reduces to 0.18 %."
    # Our calculation gives 0.189 %; the issue accepts 0.18-0.19 %.
    d = design_model(50.0, 2.0, 1 / 200, 0.05, blast_model="masi2021")
    assert 0.18 <= 100 * d.pressure_ratio <= 0.19


def test_impulse_percentages_near_figure_5_are_10x_the_law():
    # Paper text: impulse "only 0.3 %" of the prototype (general law) and "5 %" (Hopkinson-Cranz) at
    # lambda = 1/200. Its own law gives gamma lambda^1.5 = 0.035 % and lambda = 0.5 %: a 10x slip, recorded
    # in docs/paper_slips.md. We assert the law's values (exact to round-off).
    g = design_model(50.0, 2.0, 1 / 200, 1.0, blast_model="masi2021")
    hc = design_model(50.0, 2.0, 1 / 200, None, law="hopkinson-cranz", blast_model="masi2021")
    assert 100 * g.impulse_ratio == pytest.approx(0.035355, rel=1e-4)
    assert 100 * hc.impulse_ratio == pytest.approx(0.5, rel=1e-12)


@pytest.mark.parametrize("lam", [1 / 10, 1 / 20, 1 / 100, 1 / 200])
def test_hopkinson_cranz_identities(lam):
    # Table 2: lambda_Z = 1, lambda_W = lambda^3, gamma = lambda^-1/2, impulse factor lambda, same pressure,
    # mass lambda^(5/2), inertia lambda^(9/2). Identities hold to round-off (1e-12).
    d = design_model(100.0, 5.0, lam, None, law="hopkinson-cranz", blast_model="masi2021")
    assert d.scaled_distance_factor == 1.0
    assert d.specimen.scaled_distance == pytest.approx(d.prototype.scaled_distance, rel=1e-12)
    assert d.specimen_charge_kg == pytest.approx(100.0 * lam**3, rel=1e-12)
    assert d.density_ratio == pytest.approx(lam**-0.5, rel=1e-12)
    assert d.pressure_ratio == pytest.approx(1.0, rel=1e-12)
    assert d.impulse_ratio == pytest.approx(lam, rel=1e-12)
    assert d.duration_ratio == pytest.approx(lam, rel=1e-12)
    assert d.factors.mass == pytest.approx(lam**2.5, rel=1e-12)
    assert d.factors.inertia == pytest.approx(lam**4.5, rel=1e-12)
    # the general law with gamma = lambda^-1/2 has the Hopkinson-Cranz root lambda_Z = 1
    sol = solve_scaled_distance_factor(d.prototype.scaled_distance, lam, lam**-0.5, blast_model="masi2021")
    assert sol.factor == pytest.approx(1.0, abs=1e-12)


def test_general_law_quadratic_has_one_physical_root():
    # docs/design.md: for the paper's fit the law is a quadratic in ln(lambda_Z); the other root is ~1e12.
    Z = 2.0 / 50.0 ** (1 / 3)
    target = math.sqrt(1 / 200)
    phys, other = masi2021_quadratic_roots(Z, target)
    sol = solve_scaled_distance_factor(Z, 1 / 200, blast_model="masi2021")
    assert sol.factor == pytest.approx(phys, rel=1e-12)  # Brent's root == closed-form physical root
    assert other > 1e11
    assert "taken" in sol.note and "rejected" in sol.note


def test_table_1_acceleration_factors_follow_the_pi_terms():
    # The paper's Table 1 swaps the acceleration entries; pi_13 = x''/g and pi_11 = theta'' l / g give
    # lambda_x'' = varsigma and lambda_theta'' = varsigma / lambda. Exact.
    f = scaling_factors(1 / 20)
    assert f.acceleration == 1.0
    assert f.angular_acceleration == pytest.approx(20.0, rel=1e-15)
    assert f.velocity == pytest.approx(math.sqrt(1 / 20), rel=1e-15)
    assert f.time == pytest.approx(math.sqrt(1 / 20), rel=1e-15)


@pytest.mark.parametrize("sig", [1.0, 1000.0])
def test_impulsive_check_is_to_times_housner_p_for_prototype_and_model(sig):
    # The paper's 10 m block (alpha = 15 deg), 50 kg at 2 m, lambda = 1/200, in a centrifuge (varsigma = 1000:
    # the model's ratio then exceeds the prototype's, 3.1e-3 vs 1.4e-3; at varsigma = 1 it is 6x smaller) or
    # not. By hand: r = h / cos(alpha) (h = 5 m), p = sqrt(3 g / (4 r)), the model has r lambda and g varsigma.
    # Same formula, evaluated independently: round-off tolerance (1e-12).
    from blastscale.structures import RectangularBlock

    lam, g = 1 / 200, 9.81
    block = RectangularBlock.from_slenderness(10.0, math.radians(15.0))
    d = design_model(50.0, 2.0, lam, 1.0, sig, blast_model="masi2021", geometry=block)
    r = 5.0 / math.cos(math.radians(15.0))
    p_proto = math.sqrt(3 * g / (4 * r))
    p_model = math.sqrt(3 * g * sig / (4 * r * lam))
    assert d.impulsive.prototype_ratio == pytest.approx(d.prototype.positive_duration * p_proto, rel=1e-12)
    assert d.impulsive.model_ratio == pytest.approx(d.specimen.positive_duration * p_model, rel=1e-12)
    assert d.impulsive.prototype_ratio == pytest.approx(1.39e-3, rel=0.01)  # docs/design.md: "about 1e-3"
    assert d.impulsive.impulsive  # both far below the 0.4 bound
    # The verdict needs BOTH systems impulsive: with the bound between the two ratios it must be False.
    between = math.sqrt(d.impulsive.prototype_ratio * d.impulsive.model_ratio)
    assert d.impulsive.prototype_ratio != pytest.approx(d.impulsive.model_ratio, rel=1e-3)
    d2 = design_model(50.0, 2.0, lam, 1.0, sig, blast_model="masi2021", geometry=block, impulsive_threshold=between)
    assert d2.impulsive.impulsive is False
    assert design_model(50.0, 2.0, lam, blast_model="masi2021").impulsive is None  # no geometry, no check


def test_centrifuge_at_one_over_lambda_gives_complete_similarity():
    # gamma = 1, varsigma = 1/lambda: Eq. (8) has the root lambda_Z = 1 (Hopkinson-Cranz), durations scale
    # as lambda and p as 1/lambda, so t_o p is the same in model and prototype. Exact to round-off (1e-12).
    from blastscale.structures import RectangularBlock

    block = RectangularBlock.from_slenderness(10.0, math.radians(15.0))
    d = design_model(50.0, 2.0, 1 / 200, 1.0, 200.0, blast_model="masi2021", geometry=block)
    assert d.scaled_distance_factor == pytest.approx(1.0, abs=1e-12)
    assert d.impulsive.model_ratio == pytest.approx(d.impulsive.prototype_ratio, rel=1e-12)


@pytest.mark.parametrize(
    "kwargs, words",
    [
        (dict(scale=[0.01, 0.1]), ["scale has shape (2,)", "single number"]),
        (dict(scale=float("inf")), ["scale = inf", "finite"]),
        (dict(density_ratio=0.0), ["density ratio = 0", "> 0"]),
        (dict(gravity_ratio=-1.0), ["gravity ratio = -1", "> 0"]),
        (dict(density_ratio=None), ["density ratio = None"]),
        (dict(law="cube-root"), ["law = 'cube-root'", "general, hopkinson-cranz"]),
        (dict(impulsive_threshold=0.0), ["impulsive threshold = 0", "> 0"]),
    ],
)
def test_design_bad_input_names_parameter_value_range(kwargs, words):
    from blastscale._validate import BlastscaleInputError

    args = dict(charge=50.0, standoff=2.0, scale=1 / 200) | kwargs
    with pytest.raises(BlastscaleInputError) as e:
        design_model(**args)
    msg = str(e.value)
    assert "\n" not in msg and all(w in msg for w in words), msg


@pytest.mark.parametrize(
    "kwargs, words",
    [
        (dict(height=[10.0, 5.0], width=2.0), ["height has shape (2,)"]),
        (dict(height=10.0, width=float("nan")), ["width = nan m", "finite"]),
        (dict(height=10.0, width=2.0, density=0.0), ["density = 0 kg/m^3", "> 0"]),
    ],
)
def test_block_bad_input_names_parameter(kwargs, words):
    from blastscale._validate import BlastscaleInputError
    from blastscale.structures import RectangularBlock

    with pytest.raises(BlastscaleInputError) as e:
        RectangularBlock(**kwargs)
    assert all(w in str(e.value) for w in words), str(e.value)


@pytest.mark.parametrize("model", ["masi2021", "kingery-bulmash"])
@pytest.mark.parametrize("law", ["general", "hopkinson-cranz"])
def test_a_design_of_arrays_equals_the_designs_of_its_elements(model, law):
    """design_model over arrays of charges and stand-offs (the sweeps' outcome mode) solves the same
    law with the same code as one design at a time: every valid element equals the scalar design to
    1e-12 relative (the vectorised Friedlander-decay fit may differ in the last bits); the cases a
    scalar design refuses (a scaled distance outside the fits) are invalid and NaN, not raised."""
    from blastscale._validate import BlastscaleInputError
    from blastscale.structures import RectangularBlock

    block = RectangularBlock.from_slenderness(10.0, math.radians(15.0))
    W = np.array([20.0, 50.0, 200.0, 50.0, 1e-3])
    R = np.array([1.0, 2.0, 9.0, 0.05, 40.0])
    gamma = None if law == "hopkinson-cranz" else 1.0
    d = design_model(W, R, 1 / 200, gamma, law=law, blast_model=model, geometry=block)
    for k in range(W.size):
        try:
            one = design_model(W[k], R[k], 1 / 200, gamma, law=law, blast_model=model, geometry=block)
        except BlastscaleInputError:
            assert not d.valid[k] and np.isnan(d.specimen_charge_kg[k])
            continue
        assert d.valid[k]
        for got, want in (
            (d.specimen_charge_kg[k], one.specimen_charge_kg),
            (d.factors.charge[k], one.factors.charge),
            (d.specimen.reflected_impulse[k], one.specimen.reflected_impulse),
            (d.specimen.friedlander_decay[k], one.specimen.friedlander_decay),
            (d.impulsive.model_ratio[k], one.impulsive.model_ratio),
        ):
            assert got == pytest.approx(want, rel=1e-12)
    assert d.valid.sum() >= 3 and not d.valid.all()
