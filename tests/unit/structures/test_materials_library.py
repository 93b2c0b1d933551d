"""The materials library (every material has every property, in range, with a source), the rigidity check
against its closed forms, and the friction thresholds against the impulse-momentum balance solved here."""

import math
import re

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.similitude.friction import friction_check, friction_regime, sliding_thresholds
from blastscale.similitude.rigidity import RIGIDITY_FACTOR, rigidity_check
from blastscale.structures import materials as lib
from blastscale.structures.materials import MATERIAL_PROPERTIES, MATERIALS, get_material, prototype_material

#: The citation keys the module docstring defines ("[KEY] ..." at the start of a line).
KEYS = set(re.findall(r"^\[([A-Z0-9]+)\]", lib.__doc__, flags=re.M))


@pytest.mark.parametrize("name", list(MATERIALS))
def test_every_material_has_every_property_with_a_source(name):
    m = MATERIALS[name]
    for prop, src in MATERIAL_PROPERTIES.items():
        v = getattr(m, prop)
        assert math.isfinite(v) and v > 0, (name, prop)
        cited = set(re.findall(r"\b([A-Z][A-Z0-9]+)\b", getattr(m, src))) & KEYS
        assert cited, f"{name}.{src} = {getattr(m, src)!r} cites none of {sorted(KEYS)}"
    assert m.density_low <= m.density <= m.density_high
    assert 0 < m.friction_low <= m.friction <= m.friction_high < 2
    assert m.kind in ("stone", "masonry", "metal", "wood")


def test_library_values_within_physical_bounds():
    """Orders of magnitude a wrong unit would break: strengths 1 MPa - 1 GPa, moduli 1 - 300 GPa,
    E / f between 100 and 5000 (rocks: MR 200-1000, Hoek & Diederichs 2006; metals ~ 300-3000)."""
    for m in MATERIALS.values():
        assert 1e6 <= m.compressive_strength_Pa <= 1e9 and 1e9 <= m.youngs_modulus_Pa <= 3e11, m.name
        assert 100 <= m.youngs_modulus_Pa / m.compressive_strength_Pa <= 5000, m.name
    with pytest.raises(BlastscaleInputError, match="valid values are marble"):
        get_material("cheese")


def test_prototype_material_named_or_nearest_stone():
    assert prototype_material(2000.0, 0.7).name == "tuff"  # the paper's block: nearest stone/masonry by density
    assert prototype_material(2700.0, 0.7).name == "marble"  # never aluminium (2700 too): not a prototype kind
    m = prototype_material(2650.0, 0.55, "marble")
    assert (m.density, m.friction) == (2650.0, 0.55)  # the scenario's own
    assert m.compressive_strength_Pa == MATERIALS["marble"].compressive_strength_Pa


def test_rigidity_lead_for_marble_refused_granite_accepted():
    """Closed forms (docs/planning.md "Materials"): r_b = ls f_p / f_s, r_i = sqrt(ls E_s / E_p) f_p / f_s,
    r_d = ls E_p / E_s with ls = gamma varsigma lambda; lead under Hopkinson-Cranz (lambda = 1 / gamma^2, so
    ls = 1 / gamma): r_b = 4.31 (issue #37: 'about 5x'). Exact to rounding (rel 1e-12)."""
    lead, marble, granite = MATERIALS["lead"], MATERIALS["marble"], MATERIALS["granite"]
    ls = marble.density / lead.density
    r = rigidity_check(ls, lead, marble)
    fp, fs, ep, es = 100e6, 5.5e6, 70e9, 16e9
    assert r.bearing_ratio == pytest.approx(ls * fp / fs, rel=1e-12) == pytest.approx(4.306, abs=1e-3)
    assert r.impact_ratio == pytest.approx(math.sqrt(ls * es / ep) * fp / fs, rel=1e-12)
    assert r.deflection_ratio == pytest.approx(ls * ep / es, rel=1e-12)
    assert not r.ok and r.reason.startswith("not rigid: lead in place of marble: stress-to-strength")
    g = rigidity_check(0.05 * granite.density / marble.density, granite, marble)  # 1/20 in granite
    assert g.ok and max(g.bearing_ratio, g.impact_ratio, g.deflection_ratio) < 1


def test_rigidity_threshold_edge():
    """The prototype's own material: every ratio a function of ls alone (r_b = r_d = ls, r_i = sqrt(ls)):
    at ls = 2 exactly the check passes (<=), a hair above it fails."""
    m = MATERIALS["marble"]
    at = rigidity_check(RIGIDITY_FACTOR, m, m)
    assert at.ok and at.bearing_ratio == at.deflection_ratio == RIGIDITY_FACTOR
    assert at.impact_ratio == pytest.approx(math.sqrt(2.0), rel=1e-15)
    assert not rigidity_check(RIGIDITY_FACTOR * (1 + 1e-9), m, m).ok


def _impulsive_reactions(B: float, H: float, z: float) -> tuple:
    """(R_H, R_V) per unit impulse of a block pivoting on its far base corner, from the impulse-momentum
    balance solved as a linear system (unknowns v_x, v_y, omega, R_H, R_V): m v = J + R, I_G omega = the
    moments about G, v = omega x r (pivot at rest); an independent check of the closed form."""
    m, b, h = 1.0, B / 2, H / 2
    ig = m * (b * b + h * h) / 3.0
    # pivot at (b, 0), G at (0, h), clockwise omega: v_G = omega (h, b); J = 1 at height z on x = -b
    A = np.array(
        [
            [m, 0, 0, -1, 0],  # m v_x - R_H = J
            [0, m, 0, 0, -1],  # m v_y - R_V = 0
            [0, 0, ig, h, b],  # I_G w = J (z - h) - R_H h - R_V b  (clockwise moments about G; R at (b, -h))
            [1, 0, -h, 0, 0],  # v_x = w h
            [0, 1, -b, 0, 0],  # v_y = w b
        ]
    )
    rhs = np.array([1.0, 0.0, z - h, 0.0, 0.0])
    vx, vy, w, RH, RV = np.linalg.solve(A, rhs)
    return RH, RV


@pytest.mark.parametrize("B,H,z", [(2.68, 10.0, 5.0), (0.6, 1.0, 0.5), (1.0, 2.0, 0.3), (3.5, 10.0, 8.0)])
def test_impulsive_threshold_is_the_impulse_balance(B, H, z):
    """mu_i = |R_H| / R_V of the no-slip impulsive reactions (rel 1e-12: the same linear algebra)."""
    RH, RV = _impulsive_reactions(B, H, z)
    static, impulsive = sliding_thresholds(B, H, z)
    assert RV > 0 and impulsive == pytest.approx(abs(RH) / RV, rel=1e-12)
    assert static == pytest.approx(B / H, rel=1e-15)


def test_friction_follows_the_material_regimes():
    """The paper's slender block (alpha = 15 deg): B/H = tan 15 = 0.268, mu_i = (4 B^2 + H^2) / (3 B H) = 1.60:
    stone (0.7) and balsa (0.4) both slide and rock: accepted. A squat block B/H = 0.6 (mu_i = 1.356): the
    stone slides and rocks, balsa (0.4 < 0.6) slides without tipping: refused. Edges: mu = B/H slides
    (a block tips only for mu > B/H), mu = mu_i rocks."""
    B = 10.0 * math.tan(math.radians(15.0))
    static, imp = sliding_thresholds(B, 10.0)
    assert imp == pytest.approx((4 * B * B + 100.0) / (30.0 * B), rel=1e-12) == pytest.approx(1.60, abs=5e-3)
    balsa, stone = MATERIALS["balsa"].friction, MATERIALS["marble"].friction
    assert friction_check(stone, balsa, B, 10.0).ok
    squat = friction_check(stone, balsa, 0.6, 1.0)
    assert not squat.ok and (squat.prototype_regime, squat.specimen_regime) == ("slides and rocks", "slides")
    assert squat.friction_ratio == pytest.approx(0.4 / 0.7, rel=1e-15)
    assert friction_regime(0.6, 0.6, 1.0) == "slides" and friction_regime(0.6 + 1e-9, 0.6, 1.0) == "slides and rocks"
    mu_i = sliding_thresholds(0.6, 1.0)[1]
    assert friction_regime(mu_i, 0.6, 1.0) == "rocks" and friction_regime(mu_i * (1 - 1e-9), 0.6, 1.0) != "rocks"
