"""3D runs in parallel native threads (blastscale._threads): ensemble members and the 3D cases of a
sweep chunk give bitwise the histories and scalars of the serial run; the knob is checked."""

from __future__ import annotations

import math

import numpy as np
import pytest

from blastscale import _threads as th
from blastscale._validate import BlastscaleInputError


def test_map_threads_keeps_order_and_counts_and_nests_serially():
    seen = []

    def f(x):
        return x * x, th.default_threads()

    out = th.map_threads(f, range(7), threads=3, done=seen.append)
    assert [v for v, _ in out] == [x * x for x in range(7)]
    assert {n for _, n in out} == {1}  # a run inside a parallel run gets one thread: no nested pools
    assert seen == list(range(1, 8))
    assert th.map_threads(f, [], threads=2) == []


def test_threads_knob_is_checked_and_the_environment_sets_the_default(monkeypatch):
    for bad in (0, -1, 1.5, True):
        with pytest.raises(BlastscaleInputError, match="threads"):
            th.resolve_threads(bad)
    monkeypatch.setenv(th.THREADS_ENV, "3")
    assert th.default_threads() == 3 and th.resolve_threads(None) == 3
    monkeypatch.delenv(th.THREADS_ENV)
    assert th.default_threads() == th.available_cores() >= 1


def test_map_threads_raises_the_runs_error():
    def f(x):
        if x == 2:
            raise BlastscaleInputError("x = 2 is out of range")
        return x

    with pytest.raises(BlastscaleInputError, match="x = 2"):
        th.map_threads(f, range(4), threads=2)


def test_ensemble_members_in_parallel_are_bitwise_the_serial_members():
    """The chaotic circular column (docs/columns.md: 1e-10 on the load moves it by tens of % of its peak),
    4 prototype members under 200 kg at 10 m, 0.3 s: every recorded displacement is the same float."""
    from blastscale.analysis.ensemble import ensemble_compare
    from blastscale.analysis.systems import Settings3D, System3D, Systems3D
    from blastscale.blast import blast_parameters
    from blastscale.structures import MultiDrumColumn

    col = MultiDrumColumn("circular")
    systems = Systems3D(System3D(col, blast_parameters(200.0, 10.0), duration=0.3))
    serial = ensemble_compare(systems, Settings3D(record_every=4), n=4, perturbation=1e-6, threads=1)
    parallel = ensemble_compare(systems, Settings3D(record_every=4), n=4, perturbation=1e-6, threads=4)
    assert np.array_equal(serial.prototype_members, parallel.prototype_members)
    assert np.array_equal(serial.time, parallel.time)
    assert np.ptp(serial.prototype_members[:, -1, -1]) > 0.0  # the members do differ from each other


def test_3d_sweep_chunk_in_threads_equals_the_serial_loop():
    from blastscale.scenario import Scenario
    from blastscale.sweeps import SweepSpec, study_scalars
    from blastscale.sweeps.cases import evaluate_chunk

    base = Scenario.default().with_values({"engine": "3d", "duration_s": 0.15, "critical_charge": False, "threads": 2})
    spec = SweepSpec.build(base, {"charge_kg": [40.0, 60.0, 80.0]})
    got = evaluate_chunk(spec.to_payload(), 0, 3)["values"]
    for k in range(3):
        want = study_scalars(spec.scenario(k))
        for key, v in want.items():
            g = got[key][k]
            assert (isinstance(v, float) and math.isnan(v) and math.isnan(g)) or g == v, key


def test_prototype_and_model_in_parallel_are_bitwise_the_serial_runs():
    from blastscale.analysis.structure3d import compare_structure3d
    from blastscale.analysis.systems import Settings3D, Systems3D
    from blastscale.similitude import design_model
    from blastscale.structures import MultiDrumColumn

    col = MultiDrumColumn("circular")
    systems = Systems3D.of_design(design_model(200.0, 10.0, 0.01), col, duration=0.2)
    a, b = (compare_structure3d(systems, Settings3D(record_every=4), threads=n) for n in (1, 2))
    for x, y in ((a.prototype_dataset, b.prototype_dataset), (a.upscaled_dataset, b.upscaled_dataset)):
        assert np.array_equal(x["point_displacement"].values, y["point_displacement"].values)
