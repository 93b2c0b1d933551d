"""Issue #23: an arch study measures "the top" at its crown. Before, the top point was the last monitoring
point, the +y springer (0.26 m above the ground while the crown's front centre is at 2.50 m), so every
"top" figure of an arch (first-peak ratio, largest top displacement) was its foot's. Shortened: 0.1 s of the
prototype (the first peak of the crown is inside it)."""

from __future__ import annotations

import numpy as np
import pytest

from blastscale.scenario import Scenario
from blastscale.study import Study


@pytest.fixture(scope="module")
def arch_result():
    sc = Scenario.from_dict(
        {
            "structure": {"kind": "arch"},  # semicircular, R 2.5 m, t 0.5 m, 15 voussoirs
            "blast": {"charge_kg": 5.0, "standoff_m": 5.0, "blast_model": "kingery-bulmash"},
            "scale": {"length": 0.1},
            "simulation": {"engine": "3d", "duration_s": 0.1, "critical_charge": False},
        }
    )
    return Study(sc).run()


def test_an_arch_study_measures_the_top_at_its_crown(arch_result):
    cmp = arch_result.response3d
    ds = cmp.prototype_dataset
    s = arch_result.summary()["3d"]
    sim = s["similarity"]
    assert ds.attrs["top_point"] == cmp.top_point == sim["top_point"] == "V8"  # the crown voussoir of 15
    # the top figures are the crown's, read from the histories independently
    assert sim["top_first_peak_ratio"] == sim["points"]["V8"]["first_peak_ratio"]
    assert sim["max_abs_top_displacement_diff_m"] == sim["points"]["V8"]["max_abs_displacement_diff_m"]
    d = ds["point_displacement"].sel(component=["x", "y"])
    crown = float(np.hypot(*d.sel(point="V8").transpose("component", "time").values).max())
    springer = float(np.hypot(*d.sel(point="V15").transpose("component", "time").values).max())
    assert s["prototype"]["max_top_displacement_m"] == pytest.approx(crown, rel=1e-15)
    # and it matters: the crown moves several times as far as the springer taken before (measured 6.0x)
    assert crown > 3.0 * springer
