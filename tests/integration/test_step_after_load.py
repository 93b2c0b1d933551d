"""The 3D step after the load (issue #28, ``step_after_load``): twice the step once every pulse has passed, at most half
of the contact time constant (MuJoCo clamps a time constant below 2 steps), a whole number of steps between recorded
states, one body and gravity alone kept at their step; "same" is the step throughout (before issue #28)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from blastscale._validate import BlastscaleInputError
from blastscale.analysis.compare import _first_peak
from blastscale.blast import blast_parameters
from blastscale.scenario import Scenario
from blastscale.sim3d import ContactSettings, make_load, simulate_structure
from blastscale.sim3d.contact import default_contact
from blastscale.sim3d.integrate import MAX_STEP_FACTOR_AFTER_LOAD, step_factor_after_load
from blastscale.structures import MultiDrumColumn
from blastscale.study import contact_settings


def test_the_factor_is_capped_by_the_contact_time_constants():
    # the column's settings: tau = 4 dt -> x2 puts tau at MuJoCo's bound of 2 steps exactly
    c = ContactSettings(time_constant=1e-3, friction_time_constant=None, timestep=2.5e-4)
    assert step_factor_after_load(c, 10) == MAX_STEP_FACTOR_AFTER_LOAD == 2.0
    # tau = 3 dt: 1.5 steps; the friction time constant counts too (tau_f = 2.4 dt -> 1.2)
    assert step_factor_after_load(replace(c, timestep=1e-3 / 3), 10) == pytest.approx(1.5, rel=1e-12)
    assert step_factor_after_load(replace(c, time_constant=1e-2, friction_time_constant=6e-4), 10) == pytest.approx(1.2)
    assert step_factor_after_load(replace(c, time_constant=5e-4), 10) == 1.0  # tau = 2 dt: no room
    assert step_factor_after_load(c, 1) == 1.0  # one body keeps its step
    assert step_factor_after_load(replace(c, step_after_load="same"), 10) == 1.0
    with pytest.raises(BlastscaleInputError, match="step_after_load = 'half' is not known"):
        ContactSettings(step_after_load="half")


def test_the_scenario_key_reaches_the_contact():
    sc = Scenario.model_validate({"structure": {"kind": "column"}, "blast": {"charge_kg": 250, "standoff_m": 10}})
    col = MultiDrumColumn("square")
    assert contact_settings(sc, col).step_after_load == "double"
    old = sc.with_values({"simulation.step_after_load": "same"})
    assert contact_settings(old, col).step_after_load == "same"


def test_a_column_after_the_load_runs_on_the_longer_step_at_the_same_recorded_times():
    """A 3-drum square column, 250 kg at 10 m, 0.6 s (the pulse lasts ~6 ms): the recorded times and every state up to
    the load's end are bitwise those of "same"; after it the top's first peak moves by < 1 % (the convergence study's
    bound, docs/performance.md; measured 3.6e-4 here) and the history by < 5 % of the peak (measured 2.5 %: the
    impacts after the first peak shift its phase), and the delivered impulse is the same."""
    col = MultiDrumColumn(drums=3, height=3.0, top_width=1.54)
    load = make_load("A", col, blast_parameters(250.0, 10.0))
    c = default_contact(col)
    runs = {
        m: simulate_structure(col, load, 0.6, contact=replace(c, step_after_load=m), record_every=4)
        for m in ("same", "double")
    }
    ds = {m: r.dataset for m, r in runs.items()}
    t = ds["same"]["time"].values
    assert np.array_equal(t, ds["double"]["time"].values)
    x = {m: d["point_displacement"].sel(point=d.attrs["top_point"], component="x").values for m, d in ds.items()}
    loaded = t <= load.end_time - load.first_arrival
    assert loaded.sum() > 5 and np.array_equal(x["same"][loaded], x["double"][loaded])
    peaks = {m: _first_peak(t, v, 0.1)[1] for m, v in x.items()}
    assert peaks["double"] == pytest.approx(peaks["same"], rel=1e-2)
    diff = np.max(np.abs(x["double"] - x["same"])) / np.max(np.abs(x["same"]))
    assert 1e-6 < diff < 5e-2  # it did change (the longer step was taken)
    np.testing.assert_array_equal(
        runs["same"].summary()["delivered_impulse_Ns"], runs["double"].summary()["delivered_impulse_Ns"]
    )
    assert ds["double"].attrs["setting_step_after_load"] == "double"


def test_the_column_command_takes_the_old_step_and_names_a_bad_value(capsys):
    """``column --step-after-load same`` echoes it in ``inputs`` (the default "double" too); a bad value: exit 2, one
    line naming the flag."""
    import json

    from blastscale.cli import main

    base = [
        "column",
        "--drums",
        "2",
        "--height",
        "2",
        "--top-width",
        "1.6",
        "--charge",
        "250",
        "--standoff",
        "10",
        "--duration",
        "0.02",
        "--json",
    ]
    for flag, want in (([], "double"), (["--step-after-load", "same"], "same")):
        with pytest.raises(SystemExit) as e:
            main(base + flag)
        assert (e.value.code or 0) == 0
        assert json.loads(capsys.readouterr().out)["inputs"]["step_after_load"] == want
    with pytest.raises(SystemExit) as e:
        main(base + ["--step-after-load", "half"])
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert "--step-after-load" in err and "half" in err
