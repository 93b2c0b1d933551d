"""Explosives: TNT equivalence for impulse (the specimen's charge) and for pressure (safety), UFC 3-340-02
Table 2-1, the initiator's own contribution and its warning."""

import math

import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.blast.explosives import (EXPLOSIVES, INITIATOR_WARNING_FRACTION, UFC_3_340_02_TABLE_2_1, Explosive,
                                         charge_equivalence, get_explosive)

#: UFC 3-340-02 (2008) Table 2-1 "Equivalent load factors", the rows blastscale uses most, as printed:
#: (pressure factor, impulse factor).
TABLE_2_1 = {"c-4": (1.37, 1.19), "composition-b": (1.11, 0.98), "pentolite": (1.42, 1.00), "h-6": (1.38, 1.15),
             "tritonal": (1.07, 0.96), "anfo": (0.82, 0.82), "tnt": (1.00, 1.00)}


@pytest.mark.parametrize("name", sorted(TABLE_2_1))
def test_factors_are_the_tables(name):
    p, i = TABLE_2_1[name]
    ex = EXPLOSIVES[name]
    assert (ex.pressure_factor, ex.impulse_factor) == (p, i)
    assert UFC_3_340_02_TABLE_2_1[name][:2] == (p, i)


def test_c4_mass_uses_the_impulse_factor_and_safety_the_pressure_factor():
    """1 g of TNT for the impulse: 1 / 1.19 g of C-4, whose pressure equivalent is 1.37 / 1.19 g of TNT."""
    c = charge_equivalence(1e-3, "c-4")
    assert c.explosive_mass_kg == pytest.approx(1e-3 / 1.19, rel=1e-15)
    assert c.tnt_equivalent_impulse_kg == pytest.approx(1e-3, rel=1e-15)
    assert c.tnt_equivalent_pressure_kg == pytest.approx(1e-3 * 1.37 / 1.19, rel=1e-15)


def test_petn_has_no_impulse_factor_in_the_table_and_says_so():
    ex = EXPLOSIVES["petn"]
    assert UFC_3_340_02_TABLE_2_1["petn"][1] is None
    assert ex.impulse_factor == ex.pressure_factor == 1.27
    assert "no impulse factor" in ex.source and "%" in ex.uncertainty


def test_lead_azide_by_its_heat_of_explosion():
    assert EXPLOSIVES["lead-azide"].pressure_factor == pytest.approx(1536.0 / 4184.0, rel=1e-12)


def test_initiator_is_its_own_contribution_and_warns_above_ten_percent():
    W, w0 = 1e-3, 0.2e-3
    c = charge_equivalence(W, "c-4", w0)
    assert c.explosive_mass_kg == pytest.approx((W - w0) / 1.19, rel=1e-15)
    assert c.tnt_equivalent_pressure_kg == pytest.approx((W - w0) / 1.19 * 1.37 + w0, rel=1e-15)
    assert c.initiator_fraction == pytest.approx(0.2) and len(c.warnings) == 1 and "20 %" in c.warnings[0]
    assert charge_equivalence(W, "c-4", INITIATOR_WARNING_FRACTION * W * 0.999).warnings == ()
    with pytest.raises(BlastscaleInputError, match="initiator_tnt_kg"):
        charge_equivalence(W, "tnt", W)


def test_user_defined_and_unknown_explosives():
    mine = Explosive("mine", 1.2, 1.1, None, "test", "none")
    assert charge_equivalence(1.0, "mine", custom={"mine": mine}).explosive_mass_kg == pytest.approx(1 / 1.1)
    with pytest.raises(BlastscaleInputError, match="explosive = 'semtex' is not known"):
        get_explosive("semtex")
    with pytest.raises(BlastscaleInputError, match="pressure_factor"):
        Explosive("bad", math.nan, 1.0, None, "", "")
