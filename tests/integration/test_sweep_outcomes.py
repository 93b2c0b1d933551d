"""Sweep outcome mode (planar blocks): the first-swing outcome and largest rotation against full
simulations and against the Study, and the sweep machinery in that mode.

Tolerances: the full simulations (RockingSolver, rtol 1e-10, atol 1e-12, to rest) locate each
peak on the 4th-order dense output; the first-swing peak is closed-form from the state at the
pulse end. Measured: 3e-12 rad apart (40 random blocks, all three pulse shapes); asserted 1e-8 rad,
the kernel's own accuracy on an angle of a swing. The general law's model charge is found here by
inverting the blast model's impulse (45 halvings of a < 16-wide ln-range: 5e-13), the Study's
by Brent to 1e-15: asserted 1e-10 relative.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings, strategies as st

from blastscale._validate import BlastscaleInputError
from blastscale.blast import blast_parameters
from blastscale.io.sweep_store import open_sweep
from blastscale.rocking import RockingSystem, critical_charge, first_swing, simulate
from blastscale.scenario import Scenario
from blastscale.structures.block import RectangularBlock
from blastscale.sweeps import OUTCOME_KEYS, SweepSpec, planar_outcomes, select, store_location, study_scalars
from blastscale.sweeps.run import run_sweep

ANGLE_TOL = 1e-8  # rad (module docstring)


@settings(max_examples=24, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(
    height=st.floats(0.05, 20.0),
    alpha_deg=st.floats(6.0, 30.0),
    r_over_h=st.floats(0.2, 3.0),
    load=st.floats(-0.7, 0.3),
    shape=st.sampled_from(["friedlander", "triangular", "impulsive"]),
    restitution=st.one_of(st.none(), st.floats(0.0, 1.0)),
)
def test_first_swing_equals_full_simulation(height, alpha_deg, r_over_h, load, shape, restitution):
    """A block at rest under a blast (charge W_c e^load, around its critical charge): overturned
    identical and the largest |theta| of the whole motion within 1e-8 rad of the full simulation
    to rest (every impact)."""
    system = RockingSystem.from_block(
        RectangularBlock.from_slenderness(height, math.radians(alpha_deg)), restitution=restitution
    )
    R = r_over_h * height
    try:
        wc = critical_charge(system, R, pulse_shape=shape, blast_model="kingery-bulmash").charge_kg
    except BlastscaleInputError as exc:  # no critical charge within the fits' range of Z for this draw
        assume("no critical" not in str(exc))
        raise
    W = wc * math.exp(load)
    assume(abs(load) > 1e-6)  # off the threshold itself, where round-off decides
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fs = first_swing(system, W, R, pulse_shape=shape, blast_model="kingery-bulmash")
        pulse = blast_parameters(W, R, "kingery-bulmash").pulse(shape)
    full = simulate(system, pulse, pulse.duration + 200.0 / system.frequency_parameter)
    assert bool(fs.collapsed[0]) == full.collapsed
    if full.collapsed:
        assert fs.max_rotation[0] == 0.5 * math.pi
    else:
        assert abs(fs.max_rotation[0] - full.max_rotation) < ANGLE_TOL


BASE = Scenario.default().with_values(
    {"engine": "planar", "critical_charge": False, "duration_s": 20.0, "samples": 101}
)


@pytest.mark.parametrize(
    "extra",
    [
        {"length": [0.005, 0.2], "pulse": ["friedlander", "impulsive"]},
        {"law": ["hopkinson-cranz"], "density_ratio": [None], "model": ["kingery-bulmash"], "restitution": [0.5]},
        {"extrapolate": [True], "model": ["masi2021", "kingery-bulmash"], "standoff_m": [0.3, 2.0, 40.0]},
        {"model": ["kingery-bulmash"], "negative_phase": [True], "clearing": [True], "specimen_burst": ["free-air"]},
    ],
)
def test_outcome_mode_equals_the_study(extra):
    """Against the Study on a grid with cases the Study refuses (a scaled distance outside the masi2021 fits; with
    extrapolate, outside the impulse fit the general law is solved on): validity, outcomes, model
    charge; the largest angle where neither overturns (20 s of motion: every first swing is over
    by then)."""
    spec = SweepSpec.build(
        BASE, {"charge_kg": [20.0, 60.0, 200.0], "standoff_m": [1.0, 2.0, 9.0], **extra}, outcomes=True
    )
    got = planar_outcomes(spec, 0, spec.n_cases)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        rows = [study_scalars(spec.scenario(k)) for k in range(spec.n_cases)]
    valid = np.array([r["sweep.valid"] for r in rows])
    assert np.array_equal(got["sweep.valid"], valid)
    assert valid.any() and (spec.n_cases > valid.sum() or "law" in extra)
    survive = 0
    for i, r in enumerate(rows):
        if not r["sweep.valid"]:
            assert all(math.isnan(got[k][i]) for k in OUTCOME_KEYS if k != "sweep.valid")
            continue
        for who in ("prototype", "model"):
            assert bool(got[f"planar.{who}.collapsed"][i]) == r[f"planar.{who}.collapsed"]
        assert bool(got["planar.similarity.outcomes_agree"][i]) == r["planar.similarity.outcomes_agree"]
        assert got["design.model_charge_kg"][i] == pytest.approx(r["design.model_charge_kg"], rel=1e-10)
        assert got["design.model_standoff_m"][i] == r["design.model_standoff_m"]
        if not (r["planar.prototype.collapsed"] or r["planar.model.collapsed"]):
            survive += 1
            for who in ("prototype", "model"):
                assert abs(got[f"planar.{who}.max_rotation_rad"][i] - r[f"planar.{who}.max_rotation_rad"]) < ANGLE_TOL
            ratio = r["planar.model.max_rotation_rad"] / r["planar.prototype.max_rotation_rad"]
            assert got["planar.similarity.max_rotation_ratio"][i] == pytest.approx(ratio, rel=1e-6)
    assert survive >= 3


def test_outcome_sweep_is_independent_of_chunking_and_refuses_other_engines(tmp_path):
    """Sampled restitution (and friction, which plays no part) and a varied body (two groups): the
    store is the same whatever the chunk size (and equals planar_outcomes over all the cases at
    once); engine 'both' is refused."""
    from blastscale.sweeps.grids import Distribution

    spec = SweepSpec.build(
        BASE,
        {"charge_kg": np.geomspace(30, 150, 7), "height_m": [8.0, 10.0]},
        {"restitution": Distribution("uniform", (0.3, 0.95)), "friction": Distribution("uniform", (0.5, 0.8))},
        samples=5,
        seed=2,
        outcomes=True,
    )
    stores = []
    for chunk in (7, 70):
        run_sweep(spec, tmp_path / f"c{chunk}.zarr", workers=0, chunk=chunk)
        stores.append(open_sweep(tmp_path / f"c{chunk}.zarr"))
    assert stores[0].equals(stores[1])  # values and coordinates (the root attributes carry the chunk size)
    assert not stores[0]["design"].attrs  # constants are variables (equal above), not group attributes
    whole = planar_outcomes(spec, 0, spec.n_cases)
    for k in OUTCOME_KEYS:
        assert np.array_equal(select(stores[0], k).values.ravel(), whole[k], equal_nan=True)
    held = {(n.path.strip("/"), v) for n in stores[0].subtree for v in n.data_vars}
    assert held == {store_location(k)[:2] for k in OUTCOME_KEYS}
    assert stores[0]["planar"]["collapsed"].dims == ("charge_kg", "height_m", "sample", "system")
    assert "outcomes" not in SweepSpec.build(BASE, {"charge_kg": [30.0]}).describe()  # old fingerprints hold
    with pytest.raises(BlastscaleInputError, match="outcome mode takes planar block cases only"):
        SweepSpec.build(BASE.with_values({"engine": "both"}), {"charge_kg": [30.0]}, outcomes=True)


def test_cli_outcomes_refuses_a_3d_scenario_in_one_line(tmp_path, capsys):
    from blastscale.cli import main

    toml = tmp_path / "s.toml"
    toml.write_text(Scenario.default().to_toml())
    with pytest.raises(SystemExit) as e:
        main(["sweep", str(toml), "--vary", "charge_kg=30,60", "--out", str(tmp_path / "x.zarr"), "--outcomes"])
    err = capsys.readouterr().err.strip().splitlines()
    assert e.value.code == 2 and len(err) == 1 and "outcome mode" in err[0]
    assert not (tmp_path / "x.zarr").exists()


def test_cli_outcomes_refuses_a_prototype_only_scenario_in_one_line(tmp_path, capsys):
    """The outcome mode compares the prototype with its specimen: without [scale] it has none."""
    from blastscale.cli import main

    data = BASE.to_dict()
    data.pop("scale")
    toml = tmp_path / "prototype.toml"
    toml.write_text(Scenario.from_dict(data, source="test").to_toml())
    with pytest.raises(SystemExit) as e:
        main(["sweep", str(toml), "--vary", "charge_kg=30,60", "--out", str(tmp_path / "x.zarr"), "--outcomes"])
    err = capsys.readouterr().err.strip().splitlines()
    assert e.value.code == 2 and len(err) == 1 and "prototype-only" in err[0] and "outcome mode" in err[0]
    assert not (tmp_path / "x.zarr").exists() and not (tmp_path / "x.zarr.parts").exists()


@pytest.mark.parametrize("threads", [2, 3])
def test_outcome_mode_on_threads_is_bitwise_one_thread(threads):
    """The cases of a group dealt out over threads (alternately; 3 threads leave shares of unequal
    size) give every output bitwise as one thread does: valid and refused cases (stand-offs whose
    scaled distance leaves the fits), overturned and surviving ones, sampled restitution, two
    bodies (two groups)."""
    grid = {
        "charge_kg": np.geomspace(5.0, 400.0, 29),
        "standoff_m": np.linspace(0.8, 12.0, 29),
        "height_m": [8.0, 10.0],
    }
    got = {}
    for k in (1, threads):
        spec = SweepSpec.build(BASE.with_values({"threads": k}), grid, outcomes=True)
        got[k] = planar_outcomes(spec, 0, spec.n_cases)
    assert spec.n_cases // 2 >= threads * 256  # every group is split (MIN_CASES_PER_THREAD)
    valid = got[1]["sweep.valid"]
    assert valid.any() and not valid.all()
    assert got[1]["planar.prototype.collapsed"][valid].any() and not got[1]["planar.prototype.collapsed"][valid].all()
    for key in OUTCOME_KEYS:
        assert got[1][key].dtype == got[threads][key].dtype
        assert np.array_equal(got[1][key], got[threads][key], equal_nan=True), key
