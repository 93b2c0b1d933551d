"""At rest before the blast (issue #35, deliverable 5; docs/sim3d.md, "At rest before the blast"): every 3D run
checks the prototype and the specimen under gravity alone over the structure's rest time, 3 sqrt(H / g)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import pytest

from blastscale.scenario import Scenario
from blastscale.sim3d.contact import default_contact, length_time_factors
from blastscale.sim3d.rest import REST_NATURAL_TIMES, rest_check, rest_state, rest_time
from blastscale.structures import MultiDrumColumn, RectangularBlock, arch
from blastscale.study import Study

#: The keys of the ``rest`` block (SPEC35.md).
REST_KEYS = {"creep_m", "creep_rel_height", "final_speed_rel_sqrt_gh", "equilibrium", "duration_s"}


def _arch(t_over_r: float):
    """The semicircular arch of docs/assemblies.md: R = 5 m, 20 voussoirs, 1 m deep, friction 0.8."""
    a = arch(radius_m=5.0, thickness_m=t_over_r * 5.0, depth_m=1.0, voussoirs=20)
    return a, default_contact(a, friction=0.8)


def test_rest_time_is_three_natural_times_at_every_size():
    """T_rest = 3 sqrt(H / g): 3.0289 s for a 10 m block under 9.81 m/s^2 (closed form, 1e-12); a 1/20 specimen's
    is the prototype's x sqrt(1/20) (the time factor of the same gravity); g enters as 1/sqrt(g)."""
    blk = RectangularBlock.from_slenderness(10.0, math.radians(15))
    assert REST_NATURAL_TIMES == 3.0
    assert rest_time(blk) == pytest.approx(3.0 * math.sqrt(10.0 / 9.81), rel=1e-12)
    spec = blk.scaled(length_time_factors(1 / 20, math.sqrt(1 / 20)))
    assert rest_time(spec) == pytest.approx(rest_time(blk) * math.sqrt(1 / 20), rel=1e-12)
    assert rest_time(blk, gravity=4 * 9.81) == pytest.approx(rest_time(blk) / 2, rel=1e-12)


@pytest.mark.parametrize("structure", [RectangularBlock.from_slenderness(10.0, math.radians(15)), MultiDrumColumn()])
def test_a_block_and_a_column_on_flat_ground_are_at_rest(structure):
    """A block and the paper's 10-drum column on flat ground: in equilibrium, creep ~0 (measured 4e-13 H and 3.5e-10 H;
    bound 1e-8 H, four decades below the 1e-4 H tolerance), final speed ~0 (measured 1e-13 and 8e-14 sqrt(g H);
    bound 1e-8, below the 1e-4 of "at rest")."""
    r = rest_check(structure)
    assert set(r) == REST_KEYS
    assert r["equilibrium"] is True
    assert r["creep_rel_height"] < 1e-8 and r["final_speed_rel_sqrt_gh"] < 1e-8
    h = structure.describe()["height_m"]
    assert r["creep_m"] == pytest.approx(r["creep_rel_height"] * h, rel=1e-12)
    assert r["duration_s"] == pytest.approx(rest_time(structure), rel=1e-12)


def test_an_arch_below_its_minimum_thickness_is_not_at_rest():
    """t/R = 0.105, below the minimum thickness 0.1075 of a semicircular arch with radial joints (Milankovitch 1907):
    not in equilibrium. Shortened to 0.5 natural times (0.37 s): it keeps accelerating (its largest displacement grows
    3.5x as much in the second half as in the first, > 2x; 1.1e-2 sqrt(g H) at the end); the answer is the same from
    0.25 natural times to the full rest time, 3 (fallen by then: 0.9 H), docs/sim3d.md. The edge: the same arch at
    t/R = 0.16 over the same time is in equilibrium (and at every duration from 0.25 to 3 natural times)."""
    thin, c = _arch(0.105)
    r = rest_check(thin, c, natural_times=0.5)
    assert r["equilibrium"] is False and r["final_speed_rel_sqrt_gh"] > 1e-3
    thick, c = _arch(0.16)
    r = rest_check(thick, c, natural_times=0.5)
    assert r["equilibrium"] is True and r["creep_rel_height"] < 1e-4


def test_the_studys_3d_summaries_carry_the_rest_block_the_models_upscaled():
    """A study under a blast: ``3d.prototype.rest`` and ``3d.model.rest`` (the model's in prototype units). The 1/20
    specimen in the same material is the prototype's exact model (the same engine model): its up-scaled rest block
    equals the prototype's (creep and rest time to 1e-12, equilibrium the same)."""
    sc = Scenario.from_dict(
        {
            "structure": {"kind": "block", "height_m": 2.0, "alpha_deg": 15.0},
            "blast": {"charge_kg": 0.5, "standoff_m": 5.0},
            "scale": {"length": "1/20"},
            "simulation": {"engine": "3d", "duration_s": 0.2},
        }
    )
    s = Study(sc).run().summary()["3d"]
    p, m = s["prototype"]["rest"], s["model"]["rest"]
    assert set(p) == set(m) == REST_KEYS
    assert p["equilibrium"] is m["equilibrium"] is True
    assert p["duration_s"] == pytest.approx(3.0 * math.sqrt(2.0 / 9.81), rel=1e-12)  # scenario gravity 9.81
    for k in ("creep_m", "duration_s", "creep_rel_height", "final_speed_rel_sqrt_gh"):
        assert m[k] == pytest.approx(p[k], rel=1e-12, abs=1e-300), k


def test_gravity_alone_has_no_rest_block():
    """Under gravity alone the run itself is the check (its ``stability``): no ``rest`` block."""
    sc = Scenario.from_dict(
        {
            "structure": {"kind": "block", "height_m": 2.0, "alpha_deg": 15.0},
            "simulation": {"engine": "3d", "duration_s": 0.1},
        }
    )
    s = Study(sc).run().summary()["3d"]["prototype"]
    assert "rest" not in s and s["stability"] == "stands"


def _motion(x, v):
    """A one-body response of the 10 m block moving along x over 3 s: displacement x(t) [m], speed v(t) [m/s]."""
    import numpy as np
    import xarray as xr

    z = np.zeros_like(x)
    ds = xr.Dataset(
        {
            "com_displacement": (("time", "body", "component"), np.stack([x, z, z], axis=1)[:, None, :]),
            "com_velocity": (("time", "body", "component"), np.stack([v, z, z], axis=1)[:, None, :]),
            "angular_velocity": (("time", "body", "component"), np.zeros((x.size, 1, 3))),
            "residual_displacement": (("body",), np.array([abs(x[-1])])),
            "fallen": (("time", "body"), np.zeros((x.size, 1), dtype=bool)),
        },
        coords={"time": np.linspace(0.0, 3.0, x.size)},
        attrs={"collapsed": 0},
    )
    resp = SimpleNamespace(dataset=ds, structure=RectangularBlock.from_slenderness(10.0, math.radians(15)))
    return rest_state(resp, 10.0, 9.81)


@pytest.mark.parametrize(
    "power, equilibrium",
    [(1.0, True), (2.0, False), (1.5, True), (1.7, False), (0.5, True)],
)
def test_keeps_accelerating_tells_a_mechanism_from_creep_and_settling(power, equilibrium):
    """x = c t^p over [0, T]: the second half's growth over the first's is 2^p - 1 (closed form): 1 for a creep at
    constant speed (p = 1), 3 from rest at constant acceleration (p = 2), < 1 for a settling (p = 0.5); the rule's
    edge 2 is p = log2(3) = 1.585, bracketed by p = 1.5 (1.83: in equilibrium) and 1.7 (2.25: not). The speed at
    the end is 1.5e-4 sqrt(g H) (still moving) in every case."""
    import numpy as np

    t = np.linspace(0.0, 3.0, 301)
    v_end = 1.5e-4 * math.sqrt(9.81 * 10.0)
    c = v_end / (power * 3.0 ** (power - 1.0))  # x' = c p t^(p-1) = v_end at t = 3 s
    r = _motion(c * t**power, c * power * np.maximum(t, 1e-9) ** (power - 1.0))
    assert r["final_speed_rel_sqrt_gh"] > 1e-4
    assert r["equilibrium"] is equilibrium


def test_a_motion_that_has_stopped_is_in_equilibrium():
    """Accelerating displacement, but slower than 1e-4 sqrt(g H) at the end (at rest): in equilibrium."""
    import numpy as np

    t = np.linspace(0.0, 3.0, 301)
    r = _motion(1e-6 * t**2, np.full_like(t, 0.5e-4 * math.sqrt(9.81 * 10.0)))
    assert r["final_speed_rel_sqrt_gh"] < 1e-4 and r["equilibrium"] is True


def test_the_t_r_016_arch_settles_and_creeps_within_the_limit():
    """Issue #35's acceptance on the arch t/R = 0.16 under gravity alone. (1) The settling tolerance of assemblies
    (1e-8 above 10 bodies, ASSEMBLY_SETTLE_TOLERANCE) against the settling of before (1e-10, the run's tolerance): the
    same run to round-off (5e-9 of the largest displacement; bitwise at impratio 10); the rule is harmless here. (2) The creep: <= 0.5 mm over 5 s (the issue's limit, about 1e-4 of
    the arch's height, 5.4 m). Shortened to 1 s: the creep grows linearly in time (impratio 10: 0.119 mm at
    1 s, 0.569 mm at 5 s; 20: 0.057 mm and 0.284 mm), so the bound is 0.1 mm at 1 s. It falls as 1 / impratio
    (ASSEMBLY_IMPRATIO = 20 against the columns' 10: half, within 10 %); the answer "no": impratio 10, the default
    before, creeps more than the bound (0.119 mm)."""
    import dataclasses

    import numpy as np

    from blastscale.sim3d import simulate_structure
    from blastscale.sim3d.contact import ASSEMBLY_IMPRATIO, ASSEMBLY_SETTLE_TOLERANCE

    a, c = _arch(0.16)
    assert c.settle_tolerance == ASSEMBLY_SETTLE_TOLERANCE and c.impratio == ASSEMBLY_IMPRATIO == 20.0
    runs = [
        simulate_structure(a, None, 1.0, record_every=100, contact=dataclasses.replace(c, **ch))
        for ch in ({}, {"settle_tolerance": 1e-10}, {"impratio": 10.0})
    ]
    d = [r.dataset["com_displacement"].values for r in runs[:2]]
    assert np.abs(d[0] - d[1]).max() <= 1e-6 * np.abs(d[0]).max()  # measured 5e-9 (bitwise at impratio 10)
    creep = [r.summary()["max_residual_displacement_m"] for r in runs]
    assert creep[0] <= 0.1e-3 < creep[2], creep  # 0.5 mm over 5 s at the linear rate
    assert creep[2] / creep[0] == pytest.approx(2.0, rel=0.1)  # 1 / impratio


def test_the_check_is_shared_by_exact_models_and_by_other_materials_only():
    """The cache key (sim3d.rest.model_key): the paper's column, its exact 1/20 specimen (scale-consistent contact) and
    a copy 1.35x denser (marble for limestone: gravity alone does not see a uniform density factor) share one key;
    a column one drum shorter (another geometry) and one with friction 0.8 (other contact settings) do not."""
    import dataclasses

    from blastscale.sim3d.reference import reference_scene
    from blastscale.sim3d.rest import model_key
    from blastscale.similitude.factors import scaling_factors

    def key(s, friction=0.7):
        c = default_contact(s, friction=friction)
        return model_key(reference_scene(s, c, 9.81)[0])

    col = MultiDrumColumn()
    lam = 1 / 20
    spec = col.scaled(length_time_factors(lam, math.sqrt(lam)))
    dense = col.scaled(dataclasses.replace(scaling_factors(1.0, 1.35, 1.0), length=1.0, time=1.0))
    assert key(col) == key(spec) == key(dense)
    assert key(MultiDrumColumn(drums=9, height=9.0)) != key(col)
    assert key(col, 0.8) != key(col)


def test_a_study_reports_the_thin_arch_not_at_rest_before_its_blast():
    """End to end: a Study of the t/R = 0.105 arch under a blast (10 kg at 20 m, 1/20, 0.05 s after the arrival) says in
    both 3D summaries that the structure is not in equilibrium before the blast (its full rest time, 2.2 s: fallen)."""
    sc = Scenario.from_dict(
        {
            "structure": {"kind": "arch", "radius_m": 5.0, "thickness_m": 0.525, "voussoirs": 20, "friction": 0.8},
            "blast": {"charge_kg": 10.0, "standoff_m": 20.0},
            "scale": {"length": "1/20"},
            "simulation": {"engine": "3d", "duration_s": 0.05},
        }
    )
    s = Study(sc).run().summary()["3d"]
    for system in ("prototype", "model"):
        r = s[system]["rest"]
        assert r["equilibrium"] is False and r["creep_rel_height"] > 0.1, (system, r)
        assert r["duration_s"] == pytest.approx(rest_time(arch(5.0, 0.525, 1.0, 20), 9.81), rel=1e-9)
